#include "study/pareto_sweep.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <optional>

#include "core/parallel_runner.hpp"
#include "study/recorded_error.hpp"
#include "study/reference.hpp"

namespace shpb {

std::vector<ParetoJob> pareto_jobs(const Scene& scene, const std::vector<ParetoCase>& cases) {
  std::vector<ParetoJob> jobs;
  if (!exact_reference(scene)) jobs.push_back({fine_reference_case(kReferenceResolution), true, 0});
  std::vector<std::size_t> order(cases.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](auto a, auto b) { return cases[a].resolution > cases[b].resolution; });
  for (std::size_t i : order) jobs.push_back({cases[i], false, i});
  return jobs;
}

ParetoJobResult run_pareto_job(const Scene& scene, const ParetoJob& job,
                               const std::function<bool()>& cancel) {
  SimulationOptions options;
  options.record_field = false;
  options.cancel = cancel;
  options.stabilize = job.reference;  // a case is charted as its method runs
  SimulationResult r = simulate(
      job.reference ? fine_reference_scene(scene, job.run.resolution) : scene_for(scene, job.run),
      options);
  ParetoJobResult out;
  out.stable = r.stable;
  out.failure = r.failure;
  out.wall_time_s = r.wall_time_s;
  out.node_updates = r.node_updates;
  // An unstable case has no error; an unstable reference keeps its gauges (and says so).
  if (r.stable || job.reference) out.gauges = std::move(r.gauges);
  return out;
}

ParetoStudy assemble_pareto(const Scene& scene, const std::vector<ParetoJob>& jobs,
                            const std::vector<ParetoJobResult>& results) {
  std::optional<GaugeReference> reference = exact_reference(scene);
  std::size_t cases = 0;
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    if (!jobs[j].reference) {
      cases = std::max(cases, jobs[j].row + 1);
      continue;
    }
    const ParetoJobResult& r = results[j];
    reference = fine_mesh_reference(scene, jobs[j].run.resolution, r.stable, r.failure, r.gauges,
                                    r.wall_time_s);
  }
  ParetoStudy study;
  study.reference = reference->description;
  study.reference_exact = reference->exact;
  study.reference_wall_time_s = reference->wall_time_s;
  study.rows.resize(cases);
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    if (jobs[j].reference) continue;
    const ParetoJobResult& r = results[j];
    ParetoRow& row = study.rows[jobs[j].row];
    row.run = jobs[j].run;
    row.stable = r.stable;
    row.failure = r.failure;
    row.wall_time_s = r.wall_time_s;
    row.node_updates = r.node_updates;
    row.error =
        r.stable ? gauge_error(r.gauges, *reference) : std::numeric_limits<double>::quiet_NaN();
    row.recorded_error = r.stable ? recorded_gauge_error(r.gauges, *reference)
                                  : std::numeric_limits<double>::quiet_NaN();
  }
  return study;
}

ParetoStudy run_pareto_sweep(const Scene& scene, const std::vector<ParetoCase>& cases, int threads,
                             const std::function<void(std::size_t, std::size_t)>& progress,
                             const std::function<bool()>& cancel) {
  const std::vector<ParetoJob> jobs = pareto_jobs(scene, cases);
  std::vector<ParetoJobResult> results(jobs.size());
  run_parallel(
      jobs.size(), threads,
      [&](std::size_t j) { results[j] = run_pareto_job(scene, jobs[j], cancel); }, progress);
  return assemble_pareto(scene, jobs, results);
}

}  // namespace shpb
