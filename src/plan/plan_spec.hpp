#pragma once
// The scene's `plan` block (docs/scene-format.md#plan): what `shpb plan` may change in a set-up and
// within which bounds. Read and checked once, with the scene; every error names the JSON path.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "model/scene.hpp"

namespace shpb {

// A quantity the plan may vary within [lo, hi]; lo == hi fixes it.
struct PlanRange {
  double lo = 0, hi = 0;
  bool free() const { return hi > lo; }
};

// A pulse-shaper material the plan may use: as written (for the planned scene) and as read.
struct ShaperMaterial {
  std::string text;  // the scene's name or a path relative to the scene
  BarSpec bar;       // a shaper bar of this material (length and diameter set by the plan)
};

struct PlanSpec {
  PlanRange striker_length;    // fixed at the scene's striker length unless given
  PlanRange striker_velocity;  // required
  std::optional<PlanRange> specimen_length;
  // A pulse shaper between the striker and the incident bar: the scene's own (bars[1] when the
  // incident bar is bars[2]), or one the plan may add.
  std::vector<ShaperMaterial> shaper_materials;  // empty: no shaper block
  PlanRange shaper_diameter, shaper_thickness;
  bool scene_has_shaper = false;
};

// The scene file as JSON (for the planned scene), the scene as read, and its plan block.
struct PlanInput {
  nlohmann::json json;
  Scene scene;
  PlanSpec spec;
};

// Reads SCENE and its `plan` block; InputError (exit 2) naming the JSON path of a bad value.
PlanInput read_plan_input(const std::filesystem::path& scene_file);

}  // namespace shpb
