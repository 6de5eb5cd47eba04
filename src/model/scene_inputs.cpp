#include "model/scene_inputs.hpp"

namespace shpb {

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
