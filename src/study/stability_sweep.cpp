#include "study/stability_sweep.hpp"

#include "core/error.hpp"
#include "core/parallel_runner.hpp"

namespace shpb {

std::vector<StabilityJob> stability_jobs(const std::vector<StabilityPoint>& grid) {
  // The lines of the map: one per (method, ε_s/k, R/R_crit); plain and node-to-node bipenalty
  // twice (tied, as used).
  std::vector<StabilityJob> jobs;
  for (const StabilityPoint& p : grid) {
    if (p.courant != kCourantNumbers.front()) continue;
    jobs.push_back({p, true});
    if (p.method != ContactMethod::kLocalizedBipenalty) {
      StabilityPoint tied = p;
      tied.tied = true;
      jobs.push_back({tied, true});
    }
  }
  for (const StabilityPoint& p : grid) jobs.push_back({p, false});
  return jobs;
}

StabilityJobResult run_stability_job(const Scene& probe, const StabilityJob& job) {
  StabilityJobResult r;
  if (job.boundary)
    r.critical_courant =
        measured_critical_courant(probe, job.point, kBoundaryCourantMin, kBoundaryCourantMax);
  else
    r.verdict = judge_stability(probe, job.point);
  return r;
}

StabilityStudy assemble_stability(const Scene& probe, const std::vector<StabilityJob>& jobs,
                                  const std::vector<StabilityJobResult>& results) {
  StabilityStudy study;
  study.probe = probe.name;
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    const StabilityPoint& p = jobs[j].point;
    if (!jobs[j].boundary) {
      study.rows.push_back({p, results[j].verdict});
      continue;
    }
    StabilityBoundary b;
    b.line = p;
    b.critical_courant = results[j].critical_courant;
    b.closed_form_courant = p.method == ContactMethod::kPenalty
                                ? penalty_critical_courant(p.stiffness_factor)
                                : bipenalty_critical_courant(p.mass_ratio);
    study.boundaries.push_back(b);
  }
  return study;
}

StabilityStudy run_stability_sweep(const Scene& scene, const std::vector<ContactMethod>& methods,
                                   int threads,
                                   const std::function<void(std::size_t, std::size_t)>& progress,
                                   const std::function<bool()>& cancel) {
  const Scene probe = stability_probe_scene(scene);
  const std::vector<StabilityJob> jobs = stability_jobs(stability_grid(methods));
  std::vector<StabilityJobResult> results(jobs.size());
  run_parallel(
      jobs.size(), threads,
      [&](std::size_t j) {
        if (cancel && cancel()) throw Interrupted();
        results[j] = run_stability_job(probe, jobs[j]);
      },
      progress);
  return assemble_stability(probe, jobs, results);
}

}  // namespace shpb
