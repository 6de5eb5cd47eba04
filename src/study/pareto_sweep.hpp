#pragma once
// `shpb study --sweep pareto`: every contact method × stepping × mesh resolution run on
// the scene, each measured against one reference (exact or fine mesh, study/reference.hpp) and
// by its cost (wall time of the solve, node updates).
#include <functional>
#include <string>
#include <vector>

#include "model/scene.hpp"
#include "study/sweep.hpp"

namespace shpb {

struct ParetoRow {
  ParetoCase run;
  double error = 0;  // relative L2 gauge error against the reference (NaN if unstable)
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

// Runs the cases on `threads` workers (≤ 0: all cores). The rows do not depend on the thread
// count except for their wall times. `cancel` is polled by every run (throws Interrupted).
ParetoStudy run_pareto_sweep(const Scene& scene, const std::vector<ParetoCase>& cases, int threads,
                             const std::function<void(std::size_t, std::size_t)>& progress = {},
                             const std::function<bool()>& cancel = {});

}  // namespace shpb
