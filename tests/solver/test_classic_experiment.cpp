// The classic metal SHPB experiment (experiments/classic-al6061): asynchronous stepping does at
// least 10× fewer node updates than global stepping with no worse incident pulse, and
// the causal economy changes no recorded value while skipping nodes no wave has reached
// (docs/methods.md §7).
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>

#include "pulse_metrics.hpp"
#include "solver/simulation.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_solver_test_classic_experiment {

using namespace shpb;

namespace {
constexpr double kMinUpdateRatio = 10;  // the bars' step is ~10× the specimen's
constexpr double kEnergyTolerance =
    0.005;  // closing losses are booked; what is left is interpolation at unmatched instants
constexpr double kSameOutput = 1e-12;  // skipped nodes are exactly at rest
constexpr double kMinEconomy = 0.3;    // a wave front covers ~half the bars on average

Scene classic() {
  return read_scene(std::filesystem::path(SHPB_SOURCE_DIR) /
                    "experiments/classic-al6061/scene.json");
}

// Relative error of the incident plateau against V/(2c0) over the middle of the pulse.
double incident_error(const SimulationResult& r, const Scene& scene) {
  const BarSpec& striker = scene.bars.front();
  const double c0 = striker.material.wave_speed_m_s();
  const double expected = -striker.velocity_m_s / (2 * c0);
  const auto p = test::square_pulse(r.gauges.time_s, r.gauges.column("incident"), expected);
  REQUIRE(p.found);
  return std::abs(p.mean / expected - 1);
}
}  // namespace

TEST_CASE("On the classic experiment asynchronous stepping needs ten times fewer node updates",
          "[solver][asynchronous][classic]") {
  Scene scene = classic();
  const SimulationResult async = simulate(scene);
  scene.simulation.stepping = Stepping::kGlobal;
  const SimulationResult global = simulate(scene);
  REQUIRE((async.stable && global.stable));
  CHECK(global.node_updates >= kMinUpdateRatio * async.node_updates);
  CHECK(incident_error(async, scene) <= incident_error(global, scene));
  CHECK(async.energy_error < kEnergyTolerance);
}

TEST_CASE("Causal economy skips nodes no wave has reached and changes no recorded value",
          "[solver][economy][classic]") {
  const Scene scene = classic();
  const SimulationResult economy = simulate(scene);
  SimulationOptions full_options;
  full_options.full_model = true;
  const SimulationResult full = simulate(scene, full_options);
  CHECK(economy.node_updates <= (1 - kMinEconomy) * full.node_updates);
  CHECK(economy.node_updates_full_model == full.node_updates);
  for (const TimeSeries* pair : {&economy.gauges, &economy.interfaces, &economy.specimen}) {
    const TimeSeries& other = pair == &economy.gauges       ? full.gauges
                              : pair == &economy.interfaces ? full.interfaces
                                                            : full.specimen;
    REQUIRE(pair->samples() == other.samples());
    for (std::size_t c = 0; c < pair->values.size(); ++c) {
      double scale = 0, worst = 0;
      for (double x : other.values[c]) scale = std::max(scale, std::abs(x));
      for (std::size_t k = 0; k < pair->samples(); ++k)
        worst = std::max(worst, std::abs(pair->values[c][k] - other.values[c][k]));
      INFO(pair->columns[c]);
      CHECK(worst <= kSameOutput * scale);
    }
  }
}

}  // namespace tests_solver_test_classic_experiment
