// Causal economy (docs/methods.md §7): the far end of the last bar, whose reflections cannot
// reach a gauge before the end of the recording, is cut and ended with a dashpot of impedance
// ρcA; recorded values stay identical to the full model and the dashpot's absorbed energy closes
// the balance.
#include <catch2/catch.hpp>
#include <cmath>

#include "solver/simulation.hpp"
#include "test_scenes.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_solver_test_causal_economy {

using namespace shpb;

namespace {
constexpr double kSameOutput = 1e-12;  // skipped nodes are exactly at rest: identical to round-off
constexpr double kEnergyTolerance = 0.005;  // elastic chain: lumped CD conserves energy to O(C·h²)
}  // namespace

TEST_CASE("Cutting a long bar's far end with a dashpot changes no gauge value",
          "[solver][economy]") {
  const double A = 2.85e-4;
  BarSpec striker = test::bar("striker", test::steel(), 0.3, A, 300, 10.0);
  BarSpec bar = test::bar("bar", test::steel(), 3.0, A, 3000);
  bar.gauges.push_back({"g", 0.5});
  // 400 µs: the 0.6 m pulse travels 2 m, past the cut (~1.5 m), and mostly leaves through it.
  const Scene scene = test::chain({striker, bar}, 400e-6, ContactMethod::kLocalizedBipenalty,
                                  Stepping::kAsynchronous);
  const SimulationResult economy = simulate(scene);
  SimulationOptions full_options;
  full_options.full_model = true;
  const SimulationResult full = simulate(scene, full_options);
  REQUIRE((economy.stable && full.stable));
  CHECK(economy.bars[1].simulated_elements < economy.bars[1].elements);
  CHECK(full.bars[1].simulated_elements == full.bars[1].elements);
  CHECK(economy.node_updates_full_model == full.node_updates);
  const auto& a = economy.gauges.column("g");
  const auto& b = full.gauges.column("g");
  REQUIRE(a.size() == b.size());
  double scale = 0, worst = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    scale = std::max(scale, std::abs(b[k]));
    worst = std::max(worst, std::abs(a[k] - b[k]));
  }
  CHECK(worst <= kSameOutput * scale);
  // The pulse left through the dashpot: its energy is accounted as dissipated.
  CHECK(economy.energy.column("dissipated_J").back() >
        0.25 * economy.energy.column("total_J").front());
  CHECK(economy.energy_error < kEnergyTolerance);
}

}  // namespace tests_solver_test_causal_economy
