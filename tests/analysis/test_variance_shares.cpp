// Each input's share of a Monte Carlo figure's variance (analysis/monte_carlo.hpp, docs/methods.md
// §10): the squared correlation of the figure with the input's draws, adjusted for the number of
// draws. A figure that is one input's draw exactly: that input's share is 1, and an input it does
// not depend on has share 0 on average, where the raw squared correlation is 1/(M − 1) by chance
// (14 % at 8 draws, which a study's contributions once showed for a friction it did not draw).
#include <catch2/catch.hpp>
#include <random>
#include <vector>

#include "analysis/monte_carlo.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_analysis_test_variance_shares {

using namespace shpb;

TEST_CASE("An input a figure does not depend on has no share of its variance on average",
          "[analysis][uncertainty]") {
  constexpr std::size_t kDraws = 8, kInputs = 2, kTrials = 4000;
  // The share of an unrelated input: the adjustment is unbiased, and the clamp at 0 keeps about 7 %
  // on average at 8 draws, half the raw squared correlation's 1/(M − 1) = 14 %. Over 4000 trials
  // the mean's standard error is 0.2 %.
  constexpr double kUnrelatedShare = 0.1;
  constexpr double kRoundOff = 1e-12;
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;
  std::vector<std::size_t> all(kDraws);
  for (std::size_t d = 0; d < kDraws; ++d) all[d] = d;
  double unrelated = 0;
  for (std::size_t trial = 0; trial < kTrials; ++trial) {
    std::vector<double> inputs(kDraws * kInputs), figure(kDraws);
    for (std::size_t d = 0; d < kDraws; ++d) {
      for (std::size_t i = 0; i < kInputs; ++i) inputs[d * kInputs + i] = normal(rng);
      figure[d] = 3 + 2 * inputs[d * kInputs];  // input 0 alone, any affine scale
    }
    const auto stated = figure_statistics("f", "", 3, figure, all, inputs, kInputs);
    REQUIRE(stated);
    const FigureUncertainty& f = *stated;
    REQUIRE(f.shares.size() == kInputs);
    REQUIRE(f.shares[0].first == 0);
    CHECK(f.shares[0].second == Approx(1).margin(kRoundOff));
    unrelated += f.shares[1].second;
  }
  CHECK(unrelated / kTrials < kUnrelatedShare);
}

}  // namespace tests_analysis_test_variance_shares
