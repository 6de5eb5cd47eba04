#include "model/scene_validation.hpp"

#include "core/csv_writer.hpp"
#include "core/error.hpp"

namespace shpb {

ChainDiscretization validate_scene(const Scene& scene, const RunOptions& options) {
  if (const auto c = scene.simulation.courant; c && !(*c > 0 && *c <= 1)) {
    const std::string what = "must be in (0, 1]: lumped central difference is stable for C <= 1";
    if (options.courant_from_command_line)
      throw input_error("--courant", "", format_double(*c), what);
    throw input_error(scene.file.string(), "simulation.courant", format_double(*c), what);
  }
  return discretize(scene);
}

}  // namespace shpb
