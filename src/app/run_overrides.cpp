#include "app/commands.hpp"

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
  return resolve_scene(scene, options);
}

std::vector<std::filesystem::path> scene_inputs(const Scene& scene, bool measured_files) {
  std::vector<std::filesystem::path> files = {scene.file};
  files.insert(files.end(), scene.material_files.begin(), scene.material_files.end());
  if (!scene.calibration_file.empty()) files.push_back(scene.calibration_file);
  if (scene.measurement && measured_files) {
    files.push_back(scene.measurement->file);
    for (const ChannelSpec& c : scene.measurement->channels) files.push_back(c.file);
  }
  return files;
}

}  // namespace shpb
