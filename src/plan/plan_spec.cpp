#include "plan/plan_spec.hpp"

#include "core/error.hpp"
#include "core/json_document.hpp"

namespace shpb {

PlanInput read_plan_input(const std::filesystem::path& scene_file) {
  PlanInput in;
  in.scene = read_scene(scene_file);  // its plan block read with it
  if (!in.scene.plan)
    throw input_error(
        scene_file.string(), "plan", "(missing)",
        "required: what the plan may change: striker length and velocity, shaper, specimen length");
  in.json = read_json_object_file(scene_file, scene_file.string());
  in.spec = *in.scene.plan;
  return in;
}

}  // namespace shpb
