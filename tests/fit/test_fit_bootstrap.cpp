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

TEST_CASE("Residual blocks follow the noise's correlation and keep its level", "[fit][bootstrap]") {
  const std::size_t n = 1000;
  // White noise: the cube-root rule, ⌈1000^(1/3)⌉ = 10 (its autocorrelation is gone at lag 1).
  const auto white = ar1_noise(n, 0, 7);
  CHECK(shpb::residual_block_length(white) == 10);
  // Noise correlated over 20 samples (autocorrelation e^(−lag/20)): falls below 1/e at lag 20,
  // the block twice that (±3 lags of sampling scatter of the estimated autocorrelation).
  const auto coloured = ar1_noise(20000, 20, 8);
  const std::size_t block = shpb::residual_block_length(coloured);
  CHECK(block >= 34);
  CHECK(block <= 46);
  std::mt19937_64 rng(3);
  const auto drawn = shpb::block_resample(coloured, 20000, block, rng);
  REQUIRE(drawn.size() == 20000);
  CHECK(std::abs(rms(drawn) / rms(coloured) - 1) < kSpreadTolerance);
  // Lag-1 correlation kept: e^(−1/20) = 0.951 in the source; the block joins cost 1 in `block`.
  double c0 = 0, c1 = 0;
  for (std::size_t i = 1; i < drawn.size(); ++i)
    c0 += drawn[i] * drawn[i], c1 += drawn[i] * drawn[i - 1];
  CHECK(c1 / c0 > 0.9);
}
