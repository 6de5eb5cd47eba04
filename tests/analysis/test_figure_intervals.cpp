// The 95 % interval of a Monte Carlo figure (analysis/monte_carlo.hpp, docs/methods.md §10) must
// hold the truth in 95 % of the tests where it is stated. A figure some draws do not give (the
// flow stress at a strain that the nominal curve reaches but a draw's loading ends short of) has
// no 2.5 % quantile over all the draws: the quantiles of the draws that give it are of a selection,
// and were stated all the same. A known answer: a figure read off a linear reduction, the truth 0,
// the lab's nominal off by one standard normal draw, each Monte Carlo draw off the nominal by
// another. A draw gives the figure only where it reaches the strain; in the tests at the end of
// the loading, the draws that reach it are those drawn to the high side of the figure.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "analysis/monte_carlo.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_analysis_test_figure_intervals {

using namespace shpb;

TEST_CASE("A figure's 95 % interval is stated only where it holds the truth at 95 %",
          "[analysis][uncertainty]") {
  // Half the tests: every draw gives the figure. The other half: a draw gives it only beyond its
  // own standard normal's 30 % quantile (−0.5244), so that the draws that give it are its upper
  // 70 %: their 2.5 % quantile is the whole distribution's 31.75 %, and an interval over them
  // holds the truth in P(−1.96 < z < 0.475) = 66 % of those tests.
  constexpr std::size_t kTests = 2000, kDraws = 200;
  constexpr double kReachThreshold = -0.5244;  // Φ⁻¹(0.30): 30 % of the draws end short
  // The tests where an interval is stated cover at 95 %: over the 1000 tests where every draw gives
  // the figure the binomial standard error is 0.7 %, so 93–97 % is three of them either way.
  constexpr double kCoverageLow = 0.93, kCoverageHigh = 0.97;
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal;
  std::vector<std::size_t> all(kDraws);
  for (std::size_t d = 0; d < kDraws; ++d) all[d] = d;
  std::size_t stated = 0, covered = 0, stated_short = 0;
  for (std::size_t test = 0; test < kTests; ++test) {
    const bool ends_short = test % 2 == 1;
    const double nominal = normal(rng);  // the truth is 0
    std::vector<double> inputs(kDraws), figure(kDraws);
    for (std::size_t d = 0; d < kDraws; ++d) {
      inputs[d] = normal(rng);
      figure[d] = ends_short && inputs[d] < kReachThreshold ? std::nan("") : nominal + inputs[d];
    }
    const auto f = figure_statistics("flow stress", "Pa", nominal, figure, all, inputs, 1);
    if (!f) continue;
    ++stated;
    stated_short += ends_short;
    covered += f->low95 <= 0 && 0 <= f->high95;
  }
  INFO("stated in " << stated << " tests (" << stated_short
                    << " where 30 % of the draws end short), " << covered
                    << " of them cover the truth");
  REQUIRE(stated >= kTests / 2);
  const double coverage = static_cast<double>(covered) / static_cast<double>(stated);
  CHECK(coverage >= kCoverageLow);
  CHECK(coverage <= kCoverageHigh);
  CHECK(stated_short == 0);
}

}  // namespace tests_analysis_test_figure_intervals
