#pragma once
// The reader of a scene's `plan` block (docs/scene-format.md#plan), called by the scene reader:
// every command that reads a scene checks its plan block as `plan` reads it.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/json_value.hpp"
#include "model/scene.hpp"

namespace shpb {

// The block `plan` of the scene `scene` (read from `scene_json`, the file `file`, everything but
// the plan block already read); InputError (exit 2) naming the JSON path of a bad value.
PlanSpec read_plan_block(const JsonValue& plan, const Scene& scene,
                         const nlohmann::json& scene_json, const std::filesystem::path& file);

}  // namespace shpb
