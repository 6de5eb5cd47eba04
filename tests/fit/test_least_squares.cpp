// The least-squares core of `shpb fit` on a problem with a closed-form answer: a straight line
// y = a + b x through noisy points. Ordinary least squares gives the estimates, their standard
// errors s/√Sxx·… and the correlation −x̄/√(mean x²) exactly (any regression text, e.g. Draper &
// Smith, Applied Regression Analysis, ch. 1), and central differences of a linear model are exact.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "fit/least_squares.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_fit_test_least_squares {

using namespace shpb;

namespace {
// Central differences of a linear residual are exact up to round-off; Ceres stops on its own
// tolerances (function 1e-7 relative): agreement to 1e-5 of each quantity.
constexpr double kAgreement = 1e-5;
}  // namespace

TEST_CASE("Least squares: a straight line, estimates, standard errors, correlation", "[fit]") {
  const int n = 40;
  std::vector<double> x(n), y(n);
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.05);
  for (int i = 0; i < n; ++i) {
    x[i] = 1.0 + 0.1 * i;
    y[i] = 2.0 + 0.5 * x[i] + noise(rng);
  }
  // Closed form.
  double mx = 0, my = 0;
  for (int i = 0; i < n; ++i) mx += x[i] / n, my += y[i] / n;
  double sxx = 0, sxy = 0, mxx = 0;
  for (int i = 0; i < n; ++i)
    sxx += (x[i] - mx) * (x[i] - mx), sxy += (x[i] - mx) * (y[i] - my), mxx += x[i] * x[i] / n;
  const double b = sxy / sxx, a = my - b * mx;
  double ss = 0;
  for (int i = 0; i < n; ++i) ss += std::pow(y[i] - a - b * x[i], 2);
  const double s2 = ss / (n - 2);
  const double se_b = std::sqrt(s2 / sxx), se_a = std::sqrt(s2 * mxx / sxx);
  const double corr = -mx / std::sqrt(mxx);

  std::vector<LsParameter> p = {{"a", 1.0, -10, 10, 1.0}, {"b", 1.0, -10, 10, 1.0}};
  LsGroup g;
  g.parameters = {0, 1};
  g.loss_scale.assign(n, 1.0);
  g.residuals = [&](const std::vector<double>& t) {
    std::vector<double> r(n);
    for (int i = 0; i < n; ++i) r[i] = t[0] + t[1] * x[i] - y[i];
    return r;
  };
  LsOptions o;
  o.threads = 2;
  o.relative_step = 1e-4;
  const LsResult r = solve_least_squares(p, {g}, o);
  REQUIRE(r.std_error.size() == 2);
  CHECK(r.value[0] == Approx(a).epsilon(kAgreement));
  CHECK(r.value[1] == Approx(b).epsilon(kAgreement));
  CHECK(r.std_error[0] == Approx(se_a).epsilon(kAgreement));
  CHECK(r.std_error[1] == Approx(se_b).epsilon(kAgreement));
  CHECK(r.correlation(0, 1) == Approx(corr).epsilon(kAgreement));
  // A linear model's Jacobian does not change when the step is halved.
  for (double c : r.step_check) CHECK(c < kAgreement);
}

TEST_CASE("Least squares: a bound holds; a parameter without effect stays put", "[fit]") {
  // y = a + 0·c: c has no effect on the residuals (a zero Jacobian column).
  std::vector<LsParameter> p = {{"a", 0.5, 0.0, 0.8, 1.0}, {"c", 1.0, 0.0, 2.0, 1.0}};
  LsGroup g;
  g.parameters = {0, 1};
  g.loss_scale.assign(3, 1.0);
  g.residuals = [](const std::vector<double>& t) {
    return std::vector<double>{t[0] - 1.0, t[0] - 1.1, t[0] - 0.9};  // best a = 1, above the bound
  };
  const LsResult r = solve_least_squares(p, {g}, LsOptions{});
  CHECK(r.value[0] == Approx(0.8));  // held at its upper bound
  CHECK(r.value[1] == Approx(1.0));  // never moved
}

// Two blocks of residuals with different noise (a test's reflected and transmitted windows, each
// over its own peak), and an offset common to the second block (a record's removed rest level):
// over many noise draws the estimates' errors over their stated standard errors must have a root
// mean square of 1 (the sandwich with each block's own variance and the common error counted).
TEST_CASE("Least squares: standard errors hold with blocks of unequal noise and a common offset",
          "[fit]") {
  // 1000 draws: the RMS of 1000 unit normals is 1 within ±1/√2000 = 2.2 % (one s.d.); the
  // per-block variance's own sampling (40 residuals a block) adds a few per cent: ±8 %.
  constexpr int kDraws = 1000;
  constexpr double kRmsTolerance = 0.08;
  const int per_block = 40;
  const double sd1 = 0.2, sd2 = 0.01, offset_sd = 0.004;  // offset_sd: √2.5 of sd2's mean's sd
  std::vector<double> x(2 * per_block);
  for (int i = 0; i < 2 * per_block; ++i) x[i] = i < per_block ? 0.02 * i : 1.0 + 0.02 * i;
  std::mt19937 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double truth[2] = {2.0, 0.5};
  double z2[2] = {0, 0};
  for (int d = 0; d < kDraws; ++d) {
    std::vector<double> y(x.size());
    const double offset = offset_sd * normal(rng);
    for (std::size_t i = 0; i < x.size(); ++i)
      y[i] = truth[0] + truth[1] * x[i] +
             (i < static_cast<std::size_t>(per_block) ? sd1 * normal(rng)
                                                      : sd2 * normal(rng) + offset);
    std::vector<LsParameter> p = {{"a", 1.0, -10, 10, 1.0}, {"b", 1.0, -10, 10, 1.0}};
    LsGroup g;
    g.parameters = {0, 1};
    g.loss_scale.assign(x.size(), 1.0);
    g.blocks = {static_cast<std::size_t>(per_block), static_cast<std::size_t>(per_block)};
    LsCommonError e;
    e.sd = offset_sd;
    for (std::size_t i = 0; i < x.size(); ++i)
      e.sensitivity.push_back(i < static_cast<std::size_t>(per_block) ? 0.0 : -1.0);
    g.common_errors = {e};
    g.residuals = [&](const std::vector<double>& t) {
      std::vector<double> r(x.size());
      for (std::size_t i = 0; i < x.size(); ++i) r[i] = t[0] + t[1] * x[i] - y[i];
      return r;
    };
    const LsResult r = solve_least_squares(p, {g}, LsOptions{});
    REQUIRE(r.std_error.size() == 2);
    for (int k = 0; k < 2; ++k) z2[k] += std::pow((r.value[k] - truth[k]) / r.std_error[k], 2);
  }
  for (int k = 0; k < 2; ++k) {
    INFO("parameter " << k << ": RMS z " << std::sqrt(z2[k] / kDraws));
    CHECK(std::abs(std::sqrt(z2[k] / kDraws) - 1) <= kRmsTolerance);
  }
}

}  // namespace tests_fit_test_least_squares
