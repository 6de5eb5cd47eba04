// libFuzzer target: `shpb simulate` on tiny scenes — the scene reader, discretize(), the solver
// and the output writers, as run_simulate calls them. Scenes whose estimated cost exceeds a tiny
// budget are skipped (the fuzzer looks for crashes, not for long runs). Contract: a scene is
// refused with an InputError, or it runs — stable or not, never throwing — and its outputs are
// written with only finite numbers (CsvWriter refuses non-finite values with a logic_error,
// which would end the fuzzer as a crash).
#include <cmath>
#include <cstdlib>

#include "core/error.hpp"
#include "fuzz_file.hpp"
#include "model/discretization.hpp"
#include "model/scene.hpp"
#include "solver/simulation.hpp"

namespace {
void require(bool ok) {
  if (!ok) std::abort();
}
// A few milliseconds per input: enough for every code path of a small chain.
constexpr double kMaxNodeUpdates = 2e6;
constexpr double kMaxMemoryBytes = 64e6;
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = shpb_fuzz::write_input(data, size, "scene.json");
  try {
    const shpb::Scene scene = shpb::read_scene(file);
    const shpb::ChainDiscretization d = shpb::discretize(scene);
    if (d.node_updates_estimate > kMaxNodeUpdates || d.memory_estimate_bytes > kMaxMemoryBytes)
      return 0;
    shpb::SimulationOptions options;
    options.field_times = 4;
    options.field_points = 8;
    const shpb::SimulationResult r = shpb::simulate(scene, options);
    require(r.stable || !r.failure.empty());
    for (const auto& column : r.gauges.values)
      for (double v : column) require(std::isfinite(v));
    const auto out = shpb_fuzz::scratch_folder() / "out";
    std::filesystem::create_directories(out);
    shpb::write_simulation_outputs(r, scene, out);
  } catch (const shpb::InputError&) {
  }
  return 0;
}
