// Striker and bar of different impedance (docs/methods.md §4): a heavier striker loads the bar in a
// staircase F_j = F1 q^(j−1), q = (Z_s − Z_b)/(Z_s + Z_b), steps 2L_s/c_s long; a lighter one
// separates after 2L_s/c_s and rebounds at V (Z_s − Z_b)/(Z_s + Z_b).
#include <catch2/catch.hpp>
#include <cmath>

#include "pulse_metrics.hpp"
#include "solver/simulation.hpp"
#include "test_scenes.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_solver_test_impedance_mismatch {

using namespace shpb;

namespace {
constexpr double kStepTolerance = 0.01;     // one element of front smearing on each step
constexpr double kReboundTolerance = 0.01;  // one element of front smearing
constexpr double kBarArea = 2.85e-4;

Scene striker_of_area(double striker_area, Stepping stepping) {
  BarSpec striker = test::bar("striker", test::steel(), 0.2, striker_area, 200, 10.0);
  BarSpec bar = test::bar("bar", test::steel(), 1.5, kBarArea, 1500);
  return test::chain({striker, bar}, 250e-6, ContactMethod::kLocalizedBipenalty, stepping);
}
}  // namespace

TEST_CASE("A heavier striker loads the bar in the exact staircase", "[solver][contact]") {
  const double c = std::sqrt(200e9 / 8000.0), V = 10.0, Ls = 0.2;
  const double Zb = 8000 * c * kBarArea, Zs = 2 * Zb;
  const double F1 = Zs * Zb * V / (Zs + Zb), q = (Zs - Zb) / (Zs + Zb);
  const double step = 2 * Ls / c;
  for (Stepping stepping : {Stepping::kAsynchronous, Stepping::kGlobal}) {
    DYNAMIC_SECTION(to_string(stepping)) {
      const SimulationResult r = simulate(striker_of_area(2 * kBarArea, stepping));
      REQUIRE(r.stable);
      const auto& t = r.interfaces.time_s;
      const auto& force = r.interfaces.column("striker-bar_force_N");
      for (int j = 1; j <= 3; ++j) {
        // The middle half of step j (the fronts are smeared over a few elements at C < 1).
        const double t0 = (j - 1 + 0.25) * step, t1 = (j - 1 + 0.75) * step;
        const double level = test::window_mean(t, force, t0, t1);
        const double exact = F1 * std::pow(q, j - 1);
        INFO("step " << j << ": " << level << " N, exact " << exact << " N");
        CHECK(std::abs(level / exact - 1) < kStepTolerance);
      }
    }
  }
}

TEST_CASE("A lighter striker separates and rebounds at the exact velocity", "[solver][contact]") {
  const double V = 10.0;
  const double Zs_over_Zb = 0.5;
  const double rebound = V * (Zs_over_Zb - 1) / (Zs_over_Zb + 1);
  for (Stepping stepping : {Stepping::kAsynchronous, Stepping::kGlobal}) {
    DYNAMIC_SECTION(to_string(stepping)) {
      const SimulationResult r = simulate(striker_of_area(0.5 * kBarArea, stepping));
      REQUIRE(r.stable);
      CHECK(std::abs(r.bars[0].final_velocity_m_s / rebound - 1) < kReboundTolerance);
      // Separated: the interface carries no force at the end.
      CHECK(r.interfaces.column("striker-bar_force_N").back() == 0.0);
    }
  }
}

}  // namespace tests_solver_test_impedance_mismatch
