#pragma once
// The command-line overrides of a scene's run options (docs/commands.md), applied before the one
// validation every command shares.
#include <optional>

#include "model/discretization.hpp"
#include "model/scene.hpp"
#include "model/scene_validation.hpp"

namespace shpb {

// Options shared by simulate, compare and study (docs/commands.md); unset means "as the scene
// says".
struct RunOverrides {
  std::optional<ContactMethod> contact;
  std::optional<Stepping> stepping;
  std::optional<double> courant;
  std::optional<double> tolerance;  // --tolerance: the gauge error accepted (a fraction)
  int threads = 0;                  // 0: all cores
  bool quiet = false;
  // The run's warnings on stderr (even with quiet, which silences progress only); the Python
  // module returns them instead (result.warnings, and Python's warnings module).
  bool warnings_on_stderr = true;
  // Without a tolerance, kDefaultTolerance meshes the scene (false: the automatic meshes, as the
  // study sweeps them and validate compares against them).
  bool default_tolerance = true;
};

// Applies --contact/--stepping/--courant/--tolerance to a scene read from file, then checks the
// result with resolve_scene() (model/scene_validation.hpp), the one validation every command
// shares (with a tolerance it also meshes the scene); returns the discretization the run will use.
// Throws InputError (exit 2).
ChainDiscretization apply_overrides(const RunOverrides& overrides, Scene& scene);

}  // namespace shpb
