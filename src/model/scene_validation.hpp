#pragma once
// The checks of a scene as it will be run, after the command line's overrides (--contact,
// --stepping, --courant, --tolerance): one function shared by every command that runs or describes
// a scene (validate, simulate, compare, study), so that `validate` refuses exactly what `simulate`
// refuses. read_scene() checks each JSON value on its own; these are the checks of the settings
// a run resolves from the scene and the command line together. Finite localized-bipenalty links
// need no stepping rule any more: they run at any step ratio (contact_localized_finite.cpp).
#include <string>

#include "model/discretization.hpp"
#include "model/scene.hpp"

namespace shpb {

// Where the overridable settings came from, so that an error names the option or the JSON path.
struct RunOptions {
  bool courant_from_command_line = false;
  bool tolerance_from_command_line = false;
  // Neither the scene nor the command line gives a tolerance: kDefaultTolerance applies (false:
  // the automatic meshes, as the study's sweep and validate's cost comparison take them).
  bool default_tolerance = true;
};

// Empty if `c` is an acceptable Courant number, else what is expected: lumped central difference
// is stable for 0 < C <= 1 (docs/methods.md §1). The one rule for `simulation.courant` and
// --courant.
std::string courant_problem(double c);

// Empty if `fraction` is an acceptable gauge-error tolerance (0 < it < 1, i.e. below 100 %),
// else what is expected (the one rule for the scene's `simulation.tolerance` and --tolerance).
std::string tolerance_problem(double fraction);
// The line refusing `fraction` given to the gauge-error option `option` ("--tolerance: 150 %:
// expected ..."), empty when tolerance_problem finds none.
std::string tolerance_option_problem(const std::string& option, double fraction);

// Throws InputError (exit 2) for what a run would refuse: a Courant number outside (0, 1]
// (docs/methods.md §1: lumped central difference is stable for C ≤ 1), a tolerance outside
// (0 %, 100 %), a run too large for this machine (discretize()). Returns the discretization the
// run will use.
ChainDiscretization validate_scene(const Scene& scene, const RunOptions& options = {});

// validate_scene(), then, with a tolerance, every bar without an `elements` of its own meshed as
// the error model chooses (model/mesh_choice.hpp: choose_meshes) — written into the scene's
// bars so that every later discretize() sees it — and the result checked again. A tolerance no
// affordable mesh is predicted to meet, or a scene without a striker, is refused (InputError
// naming --tolerance or simulation.tolerance, with the best predicted error).
// Without a tolerance (and options.default_tolerance): kDefaultTolerance, for the bars without an
// `elements` of their own (an explicit mesh is the user's choice and wins for that bar), recorded
// as simulation.tolerance with tolerance_is_default set. It is never refused: a scene whose every
// bar is meshed by the user, or that sets a Courant number (scene or --courant), or without a
// striker (nothing to predict), or with a material-law bar
// besides the specimen (a pulse shaper: outside the model's calibration), or whose own meshes
// leave the default out of reach, keeps the automatic meshes and point-sampled gauges.
ChainDiscretization resolve_scene(Scene& scene, const RunOptions& options = {});

}  // namespace shpb
