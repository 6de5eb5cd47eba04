#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "dispersion/dispersion_table.hpp"
#include "dispersion/pochhammer_chree.hpp"
#include "dispersion/propagation.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_dispersion_test_pochhammer_chree {

using namespace shpb;

namespace {

// c/c0 within 2e-5 (the reference's five printed decimals) of the reference table over 0 ≤ a/Λ
// ≤ 1.6.
constexpr double kReferenceTolerance = 2e-5;
// The published ν = 0.29 values (docs/methods.md §5) are printed to five decimals.
constexpr double kPublishedTolerance = 1e-5;

struct ReferenceRow {
  double x, c;
};

// The reference tables shipped in tests/data/pochhammer-chree (README there), pc_nu<ν>.csv:
// a_over_Lambda,d_over_Lambda,c_over_c0,…
std::vector<ReferenceRow> read_reference(const std::string& name) {
  const auto file = std::filesystem::path(SHPB_SOURCE_DIR) / "tests/data/pochhammer-chree" / name;
  std::vector<ReferenceRow> rows;
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::stringstream s(line);
    std::string a, d, c;
    std::getline(s, a, ',');
    std::getline(s, d, ',');
    std::getline(s, c, ',');
    rows.push_back({std::stod(a), std::stod(c)});
  }
  return rows;
}

}  // namespace

TEST_CASE("The first mode matches the reference tables within 2e-5 up to a/Lambda = 1.6",
          "[dispersion]") {
  for (const auto& [nu, name] :
       {std::pair{0.29, "pc_nu0.29.csv"}, std::pair{0.30, "pc_nu0.30.csv"}}) {
    const auto rows = read_reference(name);
    REQUIRE(rows.size() > 10);  // the table ships with the repository (tests/data/pochhammer-chree)
    CAPTURE(nu);
    double worst = 0, previous_x = -1, previous_c = 0;
    for (const auto& r : rows) {
      const bool march = previous_x >= 0 && r.x > previous_x && r.x - previous_x <= 0.01;
      const double c = phase_velocity(nu, r.x, march ? previous_c : 0.0);
      worst = std::max(worst, std::abs(c - r.c));
      previous_x = r.x;
      previous_c = c;
    }
    CHECK(rows.back().x == Approx(1.6));
    CHECK(worst < kReferenceTolerance);
  }
}

TEST_CASE("The first mode reproduces the published nu = 0.29 values and tends to Rayleigh",
          "[dispersion]") {
  const std::vector<std::pair<double, double>> published = {{0.05, 0.99789}, {0.1, 0.99113},
                                                            {0.2, 0.95645},  {0.3, 0.87299},
                                                            {0.5, 0.68927},  {1.0, 0.58607}};
  for (const auto& [x, c] : published) {
    CAPTURE(x);
    CHECK(std::abs(phase_velocity(0.29, x) - c) < kPublishedTolerance);
  }
  // c_R/c0 = 0.57640 for ν = 0.29 (docs/methods.md §5); the mode approaches it within 1e-3 by a/Λ
  // = 20.
  constexpr double kRayleighPrinted = 5e-6;
  CHECK(std::abs(wave_speeds(0.29).rayleigh - 0.57640) < kRayleighPrinted);
  constexpr double kLargeXApproach = 1e-3;
  CHECK(std::abs(phase_velocity(0.29, 20.0) - 0.57640) < kLargeXApproach);
}

TEST_CASE("Rayleigh-Love is within 0.1 % of the exact mode up to a/Lambda = 0.1 only",
          "[dispersion]") {
  for (double nu : {0.0, 0.25, 0.33, 0.45}) {
    auto rl = [nu](double x) {
      return 1 / std::sqrt(1 + 2 * nu * nu * std::numbers::pi * std::numbers::pi * x * x);
    };
    CAPTURE(nu);
    for (double x : {0.02, 0.05, 0.1}) CHECK(std::abs(phase_velocity(nu, x) / rl(x) - 1) < 1e-3);
  }
  // ... and clearly not at a/Λ = 0.3 for a metal.
  CHECK(std::abs(phase_velocity(0.29, 0.3) / (1 / std::sqrt(1 + 2 * 0.29 * 0.29 * 9.8696 * 0.09)) -
                 1) > 1e-2);
}

TEST_CASE("The group velocity is consistent with the phase curve", "[dispersion]") {
  // c_g = d(ω)/dk = c + x dc/dx; central differences of the solved phase curve with h = 1e-4
  // carry a truncation error ~h² c''' ≈ 1e-7.
  constexpr double kFiniteDifferenceTolerance = 2e-6;
  constexpr double h = 1e-4;
  for (double nu : {0.1, 0.29, 0.3, 0.49}) {
    for (double x : {0.05, 0.2, 0.35, 0.6, 1.0, 1.5}) {
      CAPTURE(nu, x);
      const double c = phase_velocity(nu, x);
      const double dc = (phase_velocity(nu, x + h) - phase_velocity(nu, x - h)) / (2 * h);
      CHECK(std::abs(group_velocity(nu, x, c) - (c + x * dc)) < kFiniteDifferenceTolerance);
    }
  }
}

TEST_CASE("The amplitude factor m1 is 1 for long waves and has its pole at a/Lambda = 0.37675",
          "[dispersion]") {
  constexpr double kLongWaveTolerance = 1e-3;  // m1 − 1 = O((a/Λ)²) ≈ 3e-4 at a/Λ = 0.01
  const double c_small = phase_velocity(0.29, 0.01);
  CHECK(std::abs(amplitude_factors(0.29, 0.01, c_small).m1 - 1) < kLongWaveTolerance);
  CHECK(std::abs(amplitude_factors(0.29, 0.01, c_small).m1_m2 - 1) < kLongWaveTolerance);
  // Bisection of the surface strain's zero; docs/methods.md §5 quotes 0.37675.
  auto s = [](double x) { return surface_over_mean_strain(0.29, x, phase_velocity(0.29, x)); };
  double lo = 0.3, hi = 0.45;
  REQUIRE((s(lo) > 0) != (s(hi) > 0));
  for (int i = 0; i < 40; ++i)
    ((s(0.5 * (lo + hi)) > 0) == (s(lo) > 0) ? lo : hi) = 0.5 * (lo + hi);
  constexpr double kPolePrinted = 5e-6;
  CHECK(std::abs(0.5 * (lo + hi) - 0.37675) < kPolePrinted);
  // The table finds the same pole in f·a/c0.
  const DispersionTable table(0.29);
  CHECK(table.m1_pole_normalized_frequency() ==
        Approx(0.37675 * phase_velocity(0.29, 0.37675)).epsilon(1e-3));
}

TEST_CASE("The table interpolates the mode by normalised frequency", "[dispersion]") {
  const DispersionTable table(0.3);
  constexpr double kInterpolationTolerance = 1e-6;  // linear on a 5e-4 grid: h²|c''|/8 ≈ 1e-7
  for (double x : {0.013, 0.21, 0.377, 0.8, 1.3}) {
    const double c = phase_velocity(0.3, x);
    CAPTURE(x);
    CHECK(std::abs(table.phase_velocity(x * c) - c) < kInterpolationTolerance);
  }
}

TEST_CASE("The table up to a cut-off is the whole table's grid, cut past the cut-off and the pole",
          "[dispersion]") {
  const DispersionTable whole(0.29);
  const DispersionTable needed = DispersionTable::up_to(0.29, kDefaultCutoffFaOverC0);
  CHECK(needed.max_normalized_frequency() >= kDefaultCutoffFaOverC0);
  CHECK(needed.max_normalized_frequency() < whole.max_normalized_frequency());
  // Same grid, same roots: the pole and every value agree to the root tolerance (1e-14 in c/c0).
  constexpr double kSameRoot = 1e-12;
  CHECK(std::abs(needed.m1_pole_normalized_frequency() - whole.m1_pole_normalized_frequency()) <
        kSameRoot);
  for (double fa = 0.01; fa < kDefaultCutoffFaOverC0; fa += 0.01) {
    CAPTURE(fa);
    CHECK(std::abs(needed.phase_velocity(fa) - whole.phase_velocity(fa)) < kSameRoot);
    CHECK(std::abs(needed.m1(fa) - whole.m1(fa)) < kSameRoot * std::abs(whole.m1(fa)));
  }
}

}  // namespace tests_dispersion_test_pochhammer_chree
