#include "model/scene_validation.hpp"

#include "core/csv_writer.hpp"
#include "core/error.hpp"
#include "model/mesh_error_model.hpp"

namespace shpb {

std::string tolerance_problem(double fraction) {
  if (fraction > 0 && fraction < 1) return {};
  return "expected a gauge error above 0 % and below 100 %, such as \"1 %\"";
}

ChainDiscretization validate_scene(const Scene& scene, const RunOptions& options) {
  if (const auto c = scene.simulation.courant; c && !(*c > 0 && *c <= 1)) {
    const std::string what = "must be in (0, 1]: lumped central difference is stable for C <= 1";
    if (options.courant_from_command_line)
      throw input_error("--courant", "", format_double(*c), what);
    throw input_error(scene.file.string(), "simulation.courant", format_double(*c), what);
  }
  if (const auto t = scene.simulation.tolerance) {
    if (const std::string what = tolerance_problem(*t); !what.empty()) {
      const std::string value = format_double(*t * 100) + " %";
      if (options.tolerance_from_command_line) throw input_error("--tolerance", "", value, what);
      throw input_error(scene.file.string(), "simulation.tolerance", value, what);
    }
  }
  return discretize(scene);
}

ChainDiscretization resolve_scene(Scene& scene, const RunOptions& options) {
  const ChainDiscretization automatic = validate_scene(scene, options);
  if (!scene.simulation.tolerance) return automatic;
  choose_meshes(scene);
  return validate_scene(scene, options);
}

}  // namespace shpb
