#pragma once
// `shpb study --sweep stability` (docs/methods.md §2): the stability map of each contact
// method over penalty stiffness, Courant number and (bipenalty methods) mass ratio, run on the
// scene's stability probe (study/stability_probe.hpp), and the measured stability boundary of
// every line of the map next to its closed form.
#include <functional>
#include <string>
#include <vector>

#include "model/scene.hpp"
#include "study/stability_probe.hpp"
#include "study/sweep.hpp"

namespace shpb {

struct StabilityRow {
  StabilityPoint point;
  StabilityVerdict verdict;
};

// The largest stable Courant number of one line of the map (method, ε_s/k, R/R_crit), by
// bisection, and the closed form it should follow: for plain penalty the exact limit of the
// discrete system (penalty_critical_courant), for the bipenalty methods 1 at or below R_crit and
// 2/√R above (bipenalty_critical_courant). Plain and node-to-node bipenalty are measured twice:
// with the link acting in tension too (`tied`, the linear system of the closed forms) and as
// used (unilateral).
struct StabilityBoundary {
  StabilityPoint line;  // courant unused
  double critical_courant = 0;
  double closed_form_courant = 0;
};

struct StabilityStudy {
  std::string probe;  // what the probe scene is
  std::vector<StabilityRow> rows;
  std::vector<StabilityBoundary> boundaries;
};

// Lower and upper end of the boundary bisection.
inline constexpr double kBoundaryCourantMin = 3e-4;
inline constexpr double kBoundaryCourantMax = 1.1;

// One job of the sweep: a point of the map, or the boundary bisection of the line through
// `point` (its courant unused). Independent of each other (core/shards.hpp).
struct StabilityJob {
  StabilityPoint point;
  bool boundary = false;
};

struct StabilityJobResult {
  double critical_courant = 0;  // boundary jobs
  StabilityVerdict verdict;     // point jobs
};

// The bisections of every line first (they are the longer jobs), then the grid's points in order.
std::vector<StabilityJob> stability_jobs(const std::vector<StabilityPoint>& grid);

StabilityJobResult run_stability_job(const Scene& probe, const StabilityJob& job);

// The study from every job's result (results[i] of jobs[i]); `probe` names the probe scene.
StabilityStudy assemble_stability(const Scene& probe, const std::vector<StabilityJob>& jobs,
                                  const std::vector<StabilityJobResult>& results);

StabilityStudy run_stability_sweep(
    const Scene& scene, const std::vector<ContactMethod>& methods, int threads,
    const std::function<void(std::size_t, std::size_t)>& progress = {},
    const std::function<bool()>& cancel = {});

}  // namespace shpb
