// The Johnson-Cook law evaluates p^n, T*^m and ln ε̇* from per-element cached pairs (binomial and
// logarithmic series near the cached point, pow/log further away). Whatever path a step takes,
// the returned stress must lie on the flow surface given by the direct formula
// (johnson_cook_flow_stress: pow and log every time).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "johnson_cook_tables.hpp"
#include "material_point.hpp"
#include "model/laws/johnson_cook_law.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_model_test_johnson_cook_caches {

using namespace shpb;

namespace {
// The return mapping ends with one Newton step from a residual ≤ 1e-6 of the trial stress
// (quadratic: ~1e-12); the series are exact to round-off. A wrong cached power or log would be
// off by far more.
constexpr double kFlowSurfaceTolerance = 1e-9;
}  // namespace

TEST_CASE(
    "A Johnson-Cook point with ringing strain rate stays on the directly evaluated flow surface",
    "[material]") {
  const MaterialSpec spec = test::ofhc_copper(true);
  test::MaterialPoint point(spec);
  // A specimen element at ~2000/s and a specimen step of 20 ns, its rate ringing by ±30 % over
  // a few steps and by 0.05 % from step to step (both the series and the log/pow paths).
  constexpr double kStep = 20e-9, kRate = 2000;
  constexpr int kSteps = 6000;
  double eps = 0, worst = 0;
  int plastic_steps = 0;
  for (int k = 0; k < kSteps; ++k) {
    const double rate = -kRate * (1 + 0.3 * std::sin(k / 5.0) * (k % 400 < 200 ? 1 : 0.0)) *
                        (1 + 5e-4 * std::sin(0.1 * k));
    const double p0 = point.state().plastic_strain, T0 = point.state().temperature_K;
    const double next = eps + rate * kStep;
    const double sigma = point.strain_to(next, kStep);
    eps = next;
    if (point.state().plastic_strain == p0) continue;
    ++plastic_steps;
    const double flow =
        johnson_cook_flow_stress(spec.johnson_cook, point.state().plastic_strain, rate, T0);
    worst = std::max(worst, std::abs(std::abs(sigma) / flow - 1));
  }
  INFO("plastic steps " << plastic_steps << ", worst relative distance " << worst);
  REQUIRE(plastic_steps > kSteps / 2);
  REQUIRE(point.state().temperature_K > 300);  // T* moved: the thermal pair was exercised
  CHECK(worst <= kFlowSurfaceTolerance);
}

}  // namespace tests_model_test_johnson_cook_caches
