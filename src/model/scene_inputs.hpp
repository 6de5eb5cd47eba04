#pragma once
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "model/scene.hpp"

namespace shpb {

// The files a run of `scene` reads (the scene, its material files and, unless `measured_files` is
// false — simulate and study never open them — its measured signal files): the inputs each
// command declares to its output folder (core/output_folder.hpp) and records in plans and parts.
std::vector<std::filesystem::path> scene_inputs(const Scene& scene, bool measured_files = true);

// Where the user gave key `key` of bar `bar`'s material, for messages: its material file and the
// key, or the scene and materials.<name>.<key>, or the scene and bars[i].material.<key> inline.
struct InputLocation {
  std::string file, path;
};
InputLocation material_key_location(const Scene& scene, std::size_t bar, const std::string& key);

}  // namespace shpb
