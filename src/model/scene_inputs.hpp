#pragma once
#include <filesystem>
#include <vector>

#include "model/scene.hpp"

namespace shpb {

// The files a run of `scene` reads (the scene, its material files and, unless `measured_files` is
// false — simulate and study never open them — its measured signal files): the inputs each
// command declares to its output folder (core/output_folder.hpp) and records in plans and parts.
std::vector<std::filesystem::path> scene_inputs(const Scene& scene, bool measured_files = true);

}  // namespace shpb
