#pragma once
// What `shpb validate` prints (docs/commands.md): the resolved set-up of a scene as JSON, and the
// same document as the command's table.
#include <nlohmann/json.hpp>

#include "model/discretization.hpp"
#include "model/scene.hpp"

namespace shpb {

// The bars, gauges (with their distances to the specimen), roles and striker velocity as read;
// with the mesh and steps of `d` when the scene simulates.
nlohmann::json scene_setup_json(const Scene& scene, const ChainDiscretization* d);
// scene_setup_json with `d`, plus the estimates, duration, sampling, kinematics, measurement,
// warnings and, with a tolerance, the gauge-error model's prediction (the interfaces are added by
// the caller, who knows the solver's links).
nlohmann::json resolved_setup_json(const Scene& scene, const ChainDiscretization& d);
// The document as validate's table on stdout (its "process" part as analysis/process_setup.hpp
// writes it).
void print_setup_table(const nlohmann::json& setup);

}  // namespace shpb
