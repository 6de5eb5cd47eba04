// The Johnson-Cook law returns the yielding elements of a block several at once (block_return in
// johnson_cook_law.cpp, a loop the compiler vectorises), handing back to the one-element return
// mapping the cases it does not cover. Both must give the same states: a specimen-like bar of
// elements at different, ringing strain rates, loaded, unloaded and reloaded, updated by the
// block path and by the one-element path (set_block_return(false)).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "johnson_cook_tables.hpp"
#include "model/laws/johnson_cook_law.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_model_test_johnson_cook_block_return {

using namespace shpb;

namespace {
// The block path performs the one-element path's IEEE operations in the same order (no FMA on the
// x86-64 baseline nor AVX2 targets), so the states agree to the bit in the supported builds; a
// compiler contracting a·b + c into FMA in one loop and not in the other could differ by
// round-off per step (1e-16), far below this bound over the run.
constexpr double kBlockReturnRelativeTolerance = 1e-12;

double relative_gap(double a, double b) {
  const double scale = std::max(std::abs(a), std::abs(b));
  return scale > 0 ? std::abs(a - b) / scale : 0.0;
}
}  // namespace

TEST_CASE("Johnson-Cook return mappings of a block equal the one-element return mapping",
          "[material]") {
  for (const int variant : {0, 1, 2}) {
    // Adiabatic; isothermal; adiabatic with the strain-rate filter.
    const bool adiabatic = variant != 1;
    MaterialSpec spec = test::al6061(adiabatic);
    if (variant == 2) spec.johnson_cook.strain_rate_filter_s = 1e-6;
    JohnsonCookLaw block(spec), single(spec);
    single.set_block_return(false);
    // 100 elements: a full block of 64 and a partial one; a specimen step of 20 ns.
    constexpr int kElements = 100, kSteps = 4000;
    constexpr double kStep = 20e-9;
    std::vector<MaterialPointState> a(kElements), b(kElements);
    block.initialize(a);
    single.initialize(b);
    std::vector<double> strain(kElements), stress_a(kElements), stress_b(kElements);
    double worst = 0;
    long plastic = 0;
    for (int k = 0; k < kSteps; ++k) {
      for (int e = 0; e < kElements; ++e) {
        // Compression at 1000–3000/s ringing by ±20 %, an unloading and reload in the middle.
        const double base = -(1000 + 20.0 * e) * (k > 1500 && k < 1800 ? -0.5 : 1.0);
        const double rate = base * (1 + 0.2 * std::sin(0.3 * k + e));
        strain[e] += rate * kStep;
      }
      const double p_before = a[0].plastic_strain;
      block.update(strain, kStep, a, stress_a);
      single.update(strain, kStep, b, stress_b);
      if (a[0].plastic_strain != p_before) ++plastic;
      for (int e = 0; e < kElements; ++e) {
        worst = std::max({worst, relative_gap(stress_a[e], stress_b[e]),
                          relative_gap(a[e].plastic_strain, b[e].plastic_strain),
                          relative_gap(a[e].temperature_K, b[e].temperature_K),
                          relative_gap(a[e].dissipated_J_m3, b[e].dissipated_J_m3)});
      }
    }
    INFO("variant " << variant << ", plastic steps of element 0: " << plastic
                    << ", worst relative gap " << worst);
    REQUIRE(plastic > kSteps / 2);  // mostly yielding: the block path did the work
    REQUIRE(a[0].plastic_strain > 0.05);
    CHECK(worst <= kBlockReturnRelativeTolerance);
  }
}

}  // namespace tests_model_test_johnson_cook_block_return
