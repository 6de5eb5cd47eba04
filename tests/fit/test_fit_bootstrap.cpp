// The parametric bootstrap's pieces (fit/fit_bootstrap.hpp): Student's t quantile against the
// published table, the residual block length against the noise's correlation, and the block
// resampling keeping the residuals' level.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "fit/fit_bootstrap.hpp"

namespace {

// Table values of t(0.975, ν) (Abramowitz & Stegun, Table 26.10) are given to 3 decimals.
constexpr double kTableRounding = 1.5e-3;
// A standard deviation estimated from n = 20 000 samples is uncertain by 1/√(2n) = 0.5 %: 3 %
// allows for the blocks' correlation too (fewer independent blocks than samples).
constexpr double kSpreadTolerance = 0.03;

std::vector<double> ar1_noise(std::size_t n, double correlation_samples, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0, 1);
  const double phi = correlation_samples > 0 ? std::exp(-1 / correlation_samples) : 0.0;
  std::vector<double> e(n);
  double x = normal(rng);
  for (double& v : e) {
    v = x;
    x = phi * x + std::sqrt(1 - phi * phi) * normal(rng);
  }
  return e;
}

double rms(const std::vector<double>& x) {
  double s = 0;
  for (double v : x) s += v * v;
  return std::sqrt(s / static_cast<double>(x.size()));
}

}  // namespace

TEST_CASE("Student's t 95 % quantile matches the published table", "[fit][bootstrap]") {
  CHECK(std::abs(shpb::student_t95(5) - 2.571) < kTableRounding);
  CHECK(std::abs(shpb::student_t95(9) - 2.262) < kTableRounding);
  CHECK(std::abs(shpb::student_t95(29) - 2.045) < kTableRounding);
  CHECK(std::abs(shpb::student_t95(1e9) - 1.960) < kTableRounding);
}

TEST_CASE("Noise draws keep the record noise's level and the spread of its long sums",
          "[fit][bootstrap]") {
  // White residuals: order 0 (no correlation to model), the draws are the residuals resampled.
  const auto white = ar1_noise(2000, 0, 7);
  CHECK(shpb::fit_noise_model(white).ar.empty());
  // Residuals correlated over τ = 10 samples (autocorrelation φ^lag, φ = e^(−1/10)): a fitted
  // parameter is a weighted sum over many samples, so the draws must keep the variance of a sum of
  // L = 400 consecutive samples, σ²[L(1+φ)/(1−φ) − 2φ(1−φ^L)/(1−φ)²] for AR(1), not only the
  // level. Blocks of 2τ would lose about τ/block of it at their joins (a third here).
  const double tau = 10, phi = std::exp(-1 / tau);
  const std::size_t n = 20000, length = 400, draws = 2000;
  const auto coloured = ar1_noise(n, tau, 8);
  const shpb::NoiseModel model = shpb::fit_noise_model(coloured);
  REQUIRE_FALSE(model.ar.empty());
  std::mt19937_64 rng(3);
  const auto drawn = shpb::draw_noise(model, n, rng);
  REQUIRE(drawn.size() == n);
  CHECK(std::abs(rms(drawn) / rms(coloured) - 1) < kSpreadTolerance);
  double var_sum = 0;
  for (std::size_t d = 0; d < draws; ++d) {
    const auto x = shpb::draw_noise(model, length, rng);
    double s = 0;
    for (double v : x) s += v;
    var_sum += s * s / static_cast<double>(draws);
  }
  const auto L = static_cast<double>(length);
  const double exact =
      L * (1 + phi) / (1 - phi) - 2 * phi * (1 - std::pow(phi, L)) / ((1 - phi) * (1 - phi));
  // The variance from 2000 sums is uncertain by √(2/2000) = 3.2 %, the long-run factor
  // (1+φ)/(1−φ) from φ fitted on 20 000 samples by about 3 %: 15 % is three of their combined
  // standard deviations.
  constexpr double kSumVarianceTolerance = 0.15;
  CHECK(std::abs(var_sum / exact - 1) < kSumVarianceTolerance);
}
