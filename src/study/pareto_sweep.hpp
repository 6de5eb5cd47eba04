#pragma once
// `shpb study --sweep pareto`: every contact method × stepping × mesh resolution run on
// the scene, each measured against one reference (exact or fine mesh, study/reference.hpp) and
// by its cost (wall time of the solve, node updates). The sweep is a list of independent jobs
// (the fine-mesh reference, when needed, and one per case) and an assembly of their results, so
// that the jobs can run in one process or be spread over machines (core/shards.hpp).
#include <functional>
#include <string>
#include <vector>

#include "model/scene.hpp"
#include "solver/simulation.hpp"
#include "study/sweep.hpp"

namespace shpb {

struct ParetoRow {
  ParetoCase run;
  double error = 0;           // relative L2 gauge error against the reference (NaN if unstable)
  double recorded_error = 0;  // the same as a record sees it (study/recorded_error.hpp)
  double wall_time_s = 0;
  long long node_updates = 0;
  bool stable = true;
  std::string failure;
};

struct ParetoStudy {
  std::string reference;  // which reference the errors are measured against
  bool reference_exact = false;
  double reference_wall_time_s = 0;  // 0 for an exact reference
  std::vector<ParetoRow> rows;       // in the order of the cases given
};

// One run of the sweep: a case (its row in the study), or the fine-mesh reference.
struct ParetoJob {
  ParetoCase run;
  bool reference = false;
  std::size_t row = 0;  // index of the case (unused for the reference)
};

// What a job leaves for the assembly: its cost, and its gauges (stable runs only).
struct ParetoJobResult {
  bool stable = true;
  std::string failure;
  double wall_time_s = 0;
  long long node_updates = 0;
  TimeSeries gauges;
};

// The jobs in the order they are started: the fine-mesh reference first when the scene has no
// exact one, then the cases finest first (the longest runs do not come last).
std::vector<ParetoJob> pareto_jobs(const Scene& scene, const std::vector<ParetoCase>& cases);

// Runs one job (`cancel` is polled by the run; throws Interrupted).
ParetoJobResult run_pareto_job(const Scene& scene, const ParetoJob& job,
                               const std::function<bool()>& cancel = {});

// The study from every job's result (results[i] of jobs[i]): errors against the reference.
ParetoStudy assemble_pareto(const Scene& scene, const std::vector<ParetoJob>& jobs,
                            const std::vector<ParetoJobResult>& results);

// Runs the cases on `threads` workers (≤ 0: all cores). The rows do not depend on the thread
// count except for their wall times. `cancel` is polled by every run (throws Interrupted).
ParetoStudy run_pareto_sweep(const Scene& scene, const std::vector<ParetoCase>& cases, int threads,
                             const std::function<void(std::size_t, std::size_t)>& progress = {},
                             const std::function<bool()>& cancel = {});

}  // namespace shpb
