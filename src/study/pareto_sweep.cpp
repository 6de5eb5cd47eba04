#include "study/pareto_sweep.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <optional>

#include "solver/simulation.hpp"
#include "study/parallel_runner.hpp"
#include "study/reference.hpp"

namespace shpb {

ParetoStudy run_pareto_sweep(const Scene& scene, const std::vector<ParetoCase>& cases, int threads,
                             const std::function<void(std::size_t, std::size_t)>& progress,
                             const std::function<bool()>& cancel) {
  SimulationOptions options;
  options.record_field = false;
  options.cancel = cancel;

  std::optional<GaugeReference> reference = exact_reference(scene);
  const bool need_fine = !reference;
  // Job 0 is the fine-mesh reference when there is one; the others are the cases, started
  // finest first so that the longest runs do not come last (results go to fixed slots).
  std::vector<std::size_t> order(cases.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](auto a, auto b) { return cases[a].resolution > cases[b].resolution; });
  std::vector<SimulationResult> results(cases.size());
  std::optional<GaugeReference> fine;
  const std::size_t jobs = cases.size() + (need_fine ? 1 : 0);
  run_parallel(
      jobs, threads,
      [&](std::size_t j) {
        if (need_fine && j == 0) {
          fine = fine_mesh_reference(scene, kReferenceResolution, options);
          return;
        }
        const std::size_t i = order[j - (need_fine ? 1 : 0)];
        results[i] = simulate(scene_for(scene, cases[i]), options);
      },
      progress);

  ParetoStudy study;
  if (need_fine) reference = std::move(fine);
  study.reference = reference->description;
  study.reference_exact = reference->exact;
  study.reference_wall_time_s = reference->wall_time_s;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const SimulationResult& r = results[i];
    ParetoRow row;
    row.run = cases[i];
    row.stable = r.stable;
    row.failure = r.failure;
    row.wall_time_s = r.wall_time_s;
    row.node_updates = r.node_updates;
    row.error =
        r.stable ? gauge_error(r.gauges, *reference) : std::numeric_limits<double>::quiet_NaN();
    study.rows.push_back(row);
  }
  return study;
}

}  // namespace shpb
