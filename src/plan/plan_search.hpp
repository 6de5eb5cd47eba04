#pragma once
// The search of `shpb plan` (docs/methods.md §12): the set-up a lab should fire for a target
// specimen strain rate and strain, found by simulating candidates (docs/commands.md#plan).
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "plan/loading_metrics.hpp"
#include "plan/plan_spec.hpp"
#include "solver/simulation.hpp"

namespace shpb {

// The striker whose pulse lasts strain/rate: 2L/c = E/R (docs/methods.md §12).
inline double striker_length_for(double strain, double rate_1_s, double wave_speed_m_s) {
  return strain * wave_speed_m_s / (2 * rate_1_s);
}
// Beyond this multiple of the target strain a pulse is longer than the target needs.
inline constexpr double kStrainOvershoot = 1.2;

// One set-up: what the plan may change.
struct PlanCandidate {
  double striker_length_m = 0, striker_velocity_m_s = 0;
  int shaper = -1;  // index into PlanSpec::shaper_materials; −1: none
  double shaper_thickness_m = 0, shaper_diameter_m = 0;
  double specimen_length_m = 0;
};

struct PlanStep {  // one evaluated candidate, in the order of the search
  PlanCandidate candidate;
  LoadingMetrics metrics;
  int changes = 0;  // values that differ from the scene's
  bool meets = false;
};

struct PlanResult {
  PlanCandidate chosen;
  Scene scene;  // the planned scene, as verified
  SimulationResult verified;
  LoadingMetrics metrics;  // of the verification run
  int changes = 0;
  bool feasible = false;
  std::string binding;  // when not feasible: the constraint that binds and what would be needed
  std::vector<PlanStep> path;
  // The best set-up without a shaper and the best with one, verified as the chosen one (the
  // chosen one itself on its side): the shaper's gain. Empty when the plan searched none of that
  // kind or is not feasible.
  std::optional<PlanStep> unshaped, shaped;
  double wall_time_s = 0;
  long simulations = 0;
};

struct PlanOptions {
  double search_tolerance = 0.03;   // gauge error of the search runs (coarse meshes)
  double verify_tolerance = 0.005;  // of the chosen set-up's verification run
  int threads = 0;
  std::function<void(double)> progress;
  // The tolerances in (0 %, 100 %), threads >= 0: the lines of --search-tolerance, --tolerance
  // and --threads (the command's and the Python module's one check).
  bool IsValid(std::string* error) const;
};

// The set-up closest to the scene that meets the targets; InputError for a target out of range.
PlanResult plan_test(const PlanInput& input, const PlanTargets& targets,
                     const PlanOptions& options);

// The scene with a candidate's values (a shaper inserted after the striker when it has none).
Scene planned_scene(const PlanInput& input, const PlanCandidate& c);

}  // namespace shpb
