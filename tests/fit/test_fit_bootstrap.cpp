// The parametric bootstrap's pieces (fit/fit_bootstrap.hpp): Student's t quantile against the
// published table, the residual block length against the noise's correlation, and the block
// resampling keeping the residuals' level.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "fit/fit_bootstrap.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_fit_test_fit_bootstrap {

namespace {

// Table values of t(0.975, ν) (Abramowitz & Stegun, Table 26.10) are given to 3 decimals.
constexpr double kTableRounding = 1.5e-3;
// The model keeps the residuals' variance (Yule–Walker); the level of 100 000 drawn samples
// correlated over 10 is then known to 1/√(2 · 100 000/19) = 1 %: 3 % is three of it.
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

namespace {

// Variance of the sum of `length` consecutive samples over `draws` noise draws of the model.
double variance_of_sums(const shpb::NoiseModel& model, std::size_t length, std::size_t draws,
                        std::mt19937_64& rng) {
  double var = 0;
  for (std::size_t d = 0; d < draws; ++d) {
    double s = 0;
    for (double v : shpb::draw_noise(model, length, rng)) s += v;
    var += s * s / static_cast<double>(draws);
  }
  return var;
}

// The variance from 2000 sums is uncertain by √(2/2000) = 3.2 %, the long-run factor (1+φ)/(1−φ)
// of a model fitted on 5000 samples by about 5 %: 20 % is more than three of their combined
// standard deviations. Moving blocks of twice the correlation time miss by about a half.
constexpr double kSumVarianceTolerance = 0.2;
constexpr std::size_t kSumLength = 400, kSums = 2000;

}  // namespace

TEST_CASE("Noise draws keep the record noise's level and the spread of its long sums",
          "[fit][bootstrap]") {
  std::mt19937_64 rng(3);
  // White residuals (unit variance): a sum of L samples has variance L.
  const auto white = ar1_noise(5000, 0, 7);
  const shpb::NoiseModel white_model = shpb::fit_noise_model(white);
  CHECK(variance_of_sums(white_model, kSumLength, kSums, rng) / kSumLength ==
        Approx(1).epsilon(kSumVarianceTolerance));
  // Residuals correlated over τ = 10 samples (autocorrelation φ^lag, φ = e^(−1/10)): a fitted
  // parameter is a weighted sum over many samples, so the draws must keep the variance of a sum of
  // L consecutive samples, σ²[L(1+φ)/(1−φ) − 2φ(1−φ^L)/(1−φ)²] for AR(1), not only the level.
  const double tau = 10, phi = std::exp(-1 / tau);
  const std::size_t n = 5000;
  const auto coloured = ar1_noise(n, tau, 8);
  const shpb::NoiseModel model = shpb::fit_noise_model(coloured);
  const auto drawn = shpb::draw_noise(model, 20 * n, rng);
  REQUIRE(drawn.size() == 20 * n);
  CHECK(std::abs(rms(drawn) / rms(coloured) - 1) < kSpreadTolerance);
  const auto L = static_cast<double>(kSumLength);
  const double exact =
      L * (1 + phi) / (1 - phi) - 2 * phi * (1 - std::pow(phi, L)) / ((1 - phi) * (1 - phi));
  CHECK(variance_of_sums(model, kSumLength, kSums, rng) ==
        Approx(exact).epsilon(kSumVarianceTolerance));
}

}  // namespace tests_fit_test_fit_bootstrap
