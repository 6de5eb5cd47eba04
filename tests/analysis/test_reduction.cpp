#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "analysis/reduction.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_analysis_test_reduction {

using namespace shpb;

TEST_CASE("Constant pulses in equilibrium give equal 1-, 2- and 3-wave stresses and rates",
          "[analysis][reduction]") {
  // Steel bars (E 200 GPa, c0 5000 m/s, A 2.85e-4 m²), specimen 5 mm long, A_s 7.85e-5 m².
  const BarSide bar{200e9, 2.85e-4, 5000};
  const SpecimenGeometry spec{5e-3, 7.85e-5};
  const std::size_t n = 101;
  const double dt = 1e-7;
  // Tension positive: incident −1e-3, reflected +0.6e-3, transmitted −0.4e-3 (ε_I + ε_R = ε_T).
  const std::vector<double> ei(n, -1e-3), er(n, 0.6e-3), et(n, -0.4e-3);
  const Curve c = reduce_pulses(ei, er, et, ei, er, et, dt, bar, bar, spec);
  // docs/methods.md §6 in magnitudes: rate (c0/L)(|ε_I| + |ε_R| … ) → (5000/0.005)·1.2e-3 = 1200
  // 1/s.
  for (std::size_t i = 0; i < n; ++i) {
    REQUIRE(c.strain_rate_1_s[i] == Approx(1200));
    REQUIRE(c.strain_rate_1wave_1_s[i] == Approx(1200));
    const double sigma = 200e9 * 2.85e-4 * 0.4e-3 / 7.85e-5;  // compression positive
    REQUIRE(c.stress_1wave_Pa[i] == Approx(sigma));
    REQUIRE(c.stress_2wave_Pa[i] == Approx(sigma));
    REQUIRE(c.stress_3wave_Pa[i] == Approx(sigma));
    REQUIRE(c.equilibrium_ratio[i] == Approx(0).margin(1e-12));
  }
  // Strain is the time integral of the rate: 1200 1/s × 10 µs.
  CHECK(c.strain.back() == Approx(1200 * 100 * dt));
  // True values for compression (constant volume).
  const double e = c.strain.back();
  CHECK(c.true_strain.back() == Approx(-std::log(1 - e)));
  CHECK(c.true_stress_Pa.back() == Approx(c.stress_3wave_Pa.back() * (1 - e)));
}

TEST_CASE("Out of equilibrium the ratio R measures the force difference", "[analysis][reduction]") {
  const BarSide bar{200e9, 1e-4, 5000};
  const SpecimenGeometry spec{5e-3, 5e-5};
  // Front force from ε_I + ε_R = −0.6e-3, back from ε_T = −0.2e-3: R = 2·0.4/0.8 = 1.
  const std::vector<double> ei(3, -1e-3), er(3, 0.4e-3), et(3, -0.2e-3);
  const Curve c = reduce_pulses(ei, er, et, ei, er, et, 1e-7, bar, bar, spec);
  CHECK(c.equilibrium_ratio[1] == Approx(1.0));
  CHECK(c.stress_2wave_Pa[1] == Approx(3 * c.stress_1wave_Pa[1]));
  CHECK(c.stress_3wave_Pa[1] == Approx(2 * c.stress_1wave_Pa[1]));
}

}  // namespace tests_analysis_test_reduction
