#pragma once
// The checks of a scene as it will be run, after the command line's overrides (--contact,
// --stepping, --courant): one function shared by every command that runs or describes a scene
// (validate, simulate, compare, study), so that `validate` refuses exactly what `simulate`
// refuses. read_scene() checks each JSON value on its own; these are the checks of the settings
// a run resolves from the scene and the command line together. Finite localized-bipenalty links
// need no stepping rule any more: they run at any step ratio (contact_localized_finite.cpp).
#include "model/discretization.hpp"
#include "model/scene.hpp"

namespace shpb {

// Where the overridable settings came from, so that an error names the option or the JSON path.
struct RunOptions {
  bool courant_from_command_line = false;
};

// Throws InputError (exit 2) for what a run would refuse: a Courant number outside (0, 1]
// (docs/methods.md §1: lumped central difference is stable for C ≤ 1), a run too large for this
// machine (discretize()). Returns the discretization the run will use.
ChainDiscretization validate_scene(const Scene& scene, const RunOptions& options = {});

}  // namespace shpb
