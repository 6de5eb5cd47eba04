#include "study/stability_sweep.hpp"

#include "core/error.hpp"
#include "study/parallel_runner.hpp"

namespace shpb {

StabilityStudy run_stability_sweep(const Scene& scene, const std::vector<ContactMethod>& methods,
                                   int threads,
                                   const std::function<void(std::size_t, std::size_t)>& progress,
                                   const std::function<bool()>& cancel) {
  StabilityStudy study;
  const Scene probe = stability_probe_scene(scene);
  study.probe = probe.name;
  const std::vector<StabilityPoint> grid = stability_grid(methods);

  // The lines of the map: one per (method, ε_s/k, R/R_crit); plain and node-to-node bipenalty
  // twice (tied, as used).
  std::vector<StabilityBoundary> lines;
  for (const StabilityPoint& p : grid) {
    if (p.courant != kCourantNumbers.front()) continue;
    StabilityBoundary b;
    b.line = p;
    b.closed_form_courant = p.method == ContactMethod::kPenalty
                                ? penalty_critical_courant(p.stiffness_factor)
                                : bipenalty_critical_courant(p.mass_ratio);
    lines.push_back(b);
    if (p.method != ContactMethod::kLocalizedBipenalty) {
      b.line.tied = true;
      lines.push_back(b);
    }
  }
  study.rows.resize(grid.size());
  run_parallel(
      grid.size() + lines.size(), threads,
      [&](std::size_t j) {
        if (cancel && cancel()) throw Interrupted();
        if (j < lines.size()) {  // the bisections first: they are the longer jobs
          lines[j].critical_courant = measured_critical_courant(
              probe, lines[j].line, kBoundaryCourantMin, kBoundaryCourantMax);
        } else {
          const std::size_t i = j - lines.size();
          study.rows[i] = {grid[i], judge_stability(probe, grid[i])};
        }
      },
      progress);
  study.boundaries = std::move(lines);
  return study;
}

}  // namespace shpb
