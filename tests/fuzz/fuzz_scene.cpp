// libFuzzer target: the scene reader (model/scene_reader.cpp with core/json_*, units, materials,
// measurement) followed by discretize(), as `shpb validate` runs them. Contract: a scene is read
// and discretized, or an InputError is thrown; then every resolved number is finite and positive.
#include <cmath>
#include <cstdlib>

#include "core/error.hpp"
#include "fuzz_file.hpp"
#include "model/discretization.hpp"
#include "model/scene.hpp"

namespace {
void require(bool ok) {
  if (!ok) std::abort();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = shpb_fuzz::write_input(data, size, "scene.json");
  try {
    const shpb::Scene scene = shpb::read_scene(file);
    require(scene.bars.size() >= 2);
    for (const auto& bar : scene.bars) {
      require(std::isfinite(bar.length_m) && bar.length_m > 0);
      require(std::isfinite(bar.material.wave_speed_m_s()) && bar.material.wave_speed_m_s() > 0);
    }
    const shpb::ChainDiscretization d = shpb::discretize(scene);
    require(std::isfinite(d.duration_s) && d.duration_s > 0);
    for (const auto& b : d.bars) {
      require(b.elements > 0);
      require(std::isfinite(b.time_step_s) && b.time_step_s > 0);
      require(b.steps > 0);
    }
  } catch (const shpb::InputError&) {
  }
  return 0;
}
