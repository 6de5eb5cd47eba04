#include "model/run_overrides.hpp"

namespace shpb {

ChainDiscretization apply_overrides(const RunOverrides& overrides, Scene& scene) {
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
