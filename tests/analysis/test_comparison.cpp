#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "analysis/comparison.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_analysis_test_comparison {

using namespace shpb;

namespace {

constexpr double kDt = 1e-7;  // 10 MHz, as the scenes record
// Round-off of sums over a thousand samples.
constexpr double kRoundOff = 1e-12;

// A trapezoidal pulse with smooth (raised-cosine) ramps of `ramp` samples, starting at `start`.
std::vector<double> pulse(std::size_t n, double start, double ramp, double flat, double amp) {
  std::vector<double> x(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) - start;
    double v = 0;
    if (t > 0 && t < ramp)
      v = 0.5 * (1 - std::cos(M_PI * t / ramp));
    else if (t >= ramp && t <= ramp + flat)
      v = 1;
    else if (t > ramp + flat && t < 2 * ramp + flat)
      v = 0.5 * (1 + std::cos(M_PI * (t - ramp - flat) / ramp));
    x[i] = amp * v;
  }
  return x;
}

}  // namespace

TEST_CASE("A pulse compared with itself has no shift, unit ratios and no error",
          "[analysis][comparison]") {
  const auto x = pulse(1200, 200, 40, 500, -2e-3);
  const PulseComparison c = compare_pulse(x, x, kDt, 100, 1000);
  CHECK(std::abs(c.arrival_shift_s) < kRoundOff * kDt);
  CHECK(c.peak_ratio == Approx(1.0).epsilon(kRoundOff));
  CHECK(c.plateau_ratio == Approx(1.0).epsilon(kRoundOff));
  CHECK(c.duration_ratio == Approx(1.0).epsilon(kRoundOff));
  CHECK(c.rise_time_measured_s == c.rise_time_simulated_s);
  CHECK(c.nrmse == 0.0);
  CHECK(c.correlation == Approx(1.0).epsilon(kRoundOff));
}

TEST_CASE("A delayed, scaled and stretched pulse gives its delay, scale and stretch back",
          "[analysis][comparison]") {
  const auto measured = pulse(1500, 200, 40, 500, -2e-3);
  SECTION("delay of 7.3 samples, amplitude 1.1") {
    const auto simulated = pulse(1500, 207.3, 40, 500, -2.2e-3);
    const PulseComparison c = compare_pulse(measured, simulated, kDt, 100, 1000);
    // Parabolic refinement of the correlation peak of smooth ramps: within 0.05 sample.
    CHECK(c.arrival_shift_s == Approx(7.3 * kDt).margin(0.05 * kDt));
    CHECK(c.peak_ratio == Approx(1.1).epsilon(1e-9));
    CHECK(c.plateau_ratio == Approx(1.1).epsilon(1e-9));
    CHECK(c.duration_ratio == Approx(1.0).margin(1e-3));
    CHECK(c.correlation > 0.99);
    CHECK(c.nrmse > 0.05);
  }
  SECTION("flat top 20 % longer") {
    const auto simulated = pulse(1500, 200, 40, 600, -2e-3);
    const PulseComparison c = compare_pulse(measured, simulated, kDt, 100, 1200);
    // Half-peak width is flat + ramp: (600 + 40) / (500 + 40).
    CHECK(c.duration_ratio == Approx(640.0 / 540.0).epsilon(1e-3));
  }
}

TEST_CASE("NRMSE and correlation are scale-free: a record off by 1e300 keeps them finite",
          "[analysis][comparison]") {
  // A bridge factor mistyped by hundreds of orders of magnitude is a warning (an implausible
  // strain scale), not an error: the comparison must still be finite numbers.
  const auto measured = pulse(1500, 200, 40, 500, -2e-3);
  const auto simulated = pulse(1500, 207.3, 40, 500, -2.2e-3);
  const PulseComparison c = compare_pulse(measured, simulated, kDt, 100, 1000);
  const auto scaled = [](std::vector<double> x, double f) {
    for (double& v : x) v *= f;
    return x;
  };
  for (const double f : {1e300, 1e-300}) {
    INFO("both signals times " << f);
    const PulseComparison b =
        compare_pulse(scaled(measured, f), scaled(simulated, f), kDt, 100, 1000);
    CHECK(b.nrmse == Approx(c.nrmse).epsilon(kRoundOff));
    CHECK(b.correlation == Approx(c.correlation).epsilon(kRoundOff));
  }
  // The measured record alone 1e300 times too large: the simulated pulse is nothing beside it.
  const PulseComparison m = compare_pulse(scaled(measured, 1e300), simulated, kDt, 100, 1000);
  CHECK(std::isfinite(m.nrmse));
  CHECK(m.correlation == Approx(c.correlation).epsilon(kRoundOff));
}

TEST_CASE("The rise time of a raised-cosine ramp is its 10-90 % span", "[analysis][comparison]") {
  const double ramp = 100;
  const auto x = pulse(800, 100, ramp, 300, 1.0);
  // 0.5 (1 − cos(π t/T)) = p  ⇒  t = T acos(1 − 2p)/π.
  const double expected = ramp * (std::acos(1 - 2 * 0.9) - std::acos(1 - 2 * 0.1)) / M_PI;
  CHECK(rise_time_samples(x, 0, 800) == Approx(expected).margin(0.02));
}

}  // namespace tests_analysis_test_comparison
