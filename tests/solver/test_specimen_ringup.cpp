// Elastic specimen between identical bars (docs/methods.md §4): a step incident force F_I rings the
// specimen up; after n transits the face just reached carries F_I (1 − r^(n+1)), r = (1−α)/(1+α),
// α = Z_spec/Z_bar. The transmitted (back) face is reached after odd transits.
#include <catch2/catch.hpp>
#include <cmath>

#include "pulse_metrics.hpp"
#include "solver/simulation.hpp"
#include "test_scenes.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_solver_test_specimen_ringup {

using namespace shpb;

namespace {
constexpr double kLevelTolerance = 0.02;  // a 10-element specimen resolves the steps to ~1 %
}

TEST_CASE("An elastic specimen rings up in the exact staircase", "[solver][specimen]") {
  const double E = 200e9, rho = 8000, A = 2.85e-4, V = 10.0, c = std::sqrt(E / rho);
  const double Lb = 1.0, Ls = 5e-3;
  for (double alpha : {0.1, 0.5}) {
    DYNAMIC_SECTION("alpha = " << alpha) {
      // Same density and area, modulus α² E: impedance ratio α, wave speed α c.
      const MaterialSpec soft = test::elastic(alpha * alpha * E, rho, "specimen");
      const double cs = alpha * c, transit = Ls / cs;
      // 57 elements: a specimen step that is a non-integer fraction of the bars' step.
      BarSpec striker = test::bar("striker", test::steel(), 0.6, A, 600, V);
      BarSpec incident = test::bar("incident", test::steel(), Lb, A, 1000);
      BarSpec specimen = test::bar("specimen", soft, Ls, A, 57);
      BarSpec transmitter = test::bar("transmitter", test::steel(), Lb, A, 1000);
      Scene scene = test::chain({striker, incident, specimen, transmitter}, Lb / c + 8 * transit,
                                ContactMethod::kLocalizedBipenalty, Stepping::kAsynchronous, 100e6);
      scene.specimen = 2;
      const SimulationResult r = simulate(scene);
      REQUIRE(r.stable);
      const double FI = 0.5 * rho * c * A * V;  // incident step force Z V / 2
      const double rr = (1 - alpha) / (1 + alpha);
      const double t0 = Lb / c;  // the incident front reaches the specimen
      const auto& t = r.interfaces.time_s;
      const auto& back = r.interfaces.column("specimen-transmitter_force_N");
      for (int n = 1; n <= 5; n += 2) {
        // Level after transit n holds from t0 + n·transit to t0 + (n+2)·transit.
        const double a = t0 + (n + 0.5) * transit, b = t0 + (n + 1.5) * transit;
        const double level = test::window_mean(t, back, a, b);
        const double exact = FI * (1 - std::pow(rr, n + 1));
        INFO("after " << n << " transits: " << level << " N, exact " << exact << " N");
        CHECK(std::abs(level / exact - 1) < kLevelTolerance);
      }
    }
  }
}

}  // namespace tests_solver_test_specimen_ringup
