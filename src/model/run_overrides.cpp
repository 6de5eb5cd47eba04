#include "model/run_overrides.hpp"

#include <string>

#include "core/error.hpp"
#include "core/options_check.hpp"

namespace shpb {

ChainDiscretization apply_overrides(const RunOverrides& overrides, Scene& scene) {
  // The command line refuses it as it parses (app/cli_options.hpp); Python passes any int.
  if (const std::string what = threads_problem(overrides.threads); !what.empty())
    throw InputError(what);
  if (overrides.contact) {
    scene.contact.method = *overrides.contact;
    for (auto& i : scene.contact.interfaces) i.method.reset();
  }
  if (overrides.stepping) scene.simulation.stepping = *overrides.stepping;
  if (overrides.courant) scene.simulation.courant = overrides.courant;
  if (overrides.tolerance) scene.simulation.tolerance = overrides.tolerance;
  RunOptions options;
  options.courant_from_command_line = overrides.courant.has_value();
  options.tolerance_from_command_line = overrides.tolerance.has_value();
  options.default_tolerance = overrides.default_tolerance;
  return resolve_scene(scene, options);
}

}  // namespace shpb
