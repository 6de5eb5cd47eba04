#include "app/commands.hpp"

namespace shpb {

void apply_overrides(const RunOverrides& overrides, Scene& scene) {
  if (overrides.contact) {
    scene.contact.method = *overrides.contact;
    for (auto& i : scene.contact.interfaces) i.method.reset();
  }
  if (overrides.stepping) scene.simulation.stepping = *overrides.stepping;
  if (overrides.courant) scene.simulation.courant = overrides.courant;
}

}  // namespace shpb
