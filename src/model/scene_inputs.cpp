#include "model/scene_inputs.hpp"

#include <algorithm>

#include "core/json_value.hpp"

namespace shpb {

std::vector<std::filesystem::path> scene_inputs(const Scene& scene, bool measured_files) {
  std::vector<std::filesystem::path> files = {scene.file};
  files.insert(files.end(), scene.material_files.begin(), scene.material_files.end());
  if (!scene.calibration_file.empty()) files.push_back(scene.calibration_file);
  if (scene.measurement && measured_files) {
    files.push_back(scene.measurement->file);
    for (const ChannelSpec& c : scene.measurement->channels) files.push_back(c.file);
  }
  // A record read from the measurement's file names none of its own (and the reverse): no empty
  // path, which Python's pathlib turns into "." (a result's save(dir) under the current folder
  // was refused as lying inside an input).
  std::erase_if(files, [](const std::filesystem::path& f) { return f.empty(); });
  return files;
}

InputLocation material_key_location(const Scene& scene, std::size_t bar, const std::string& key) {
  const std::string& name = scene.bars[bar].material.name;
  if (std::find(scene.material_files.begin(), scene.material_files.end(),
                std::filesystem::path(name)) != scene.material_files.end())
    return {name, key};
  if (name == "inline")
    return {scene.file.string(),
            json_child_path(json_element_path("bars", bar) + ".material", key)};
  return {scene.file.string(), json_child_path(json_child_path("materials", name), key)};
}

}  // namespace shpb
