#pragma once
// The scene `shpb plan` plans: the scene with its `plan` block (model/plan_reader.hpp reads the
// block with the scene, for every command; docs/scene-format.md#plan), which plan requires.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "model/scene.hpp"

namespace shpb {

// The scene file as JSON (for the planned scene), the scene as read, and its plan block.
struct PlanInput {
  nlohmann::json json;
  Scene scene;
  PlanSpec spec;
};

// Reads SCENE, which must have a `plan` block; InputError (exit 2) naming the JSON path of a bad
// value.
PlanInput read_plan_input(const std::filesystem::path& scene_file);

}  // namespace shpb
