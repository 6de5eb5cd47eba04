// The LANL copper experiment's bridge settings against the physics of the test: once the specimen
// is in force equilibrium, the force it passes to the transmitter bar (1-wave stress) equals the
// force on its front face (2-wave stress) (docs/methods.md §6). A wrong gain or bridge factor on
// either channel breaks this balance by that factor.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "run_shpb.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_app_test_experiment_lanl_cu {

namespace fs = std::filesystem;

namespace {
// The front-face force (incident + reflected) still carries dispersion residue and the ring-up
// of the first transits; 15 % on the median over the loaded part separates a right calibration
// (≈ 1.0) from a channel off by a gain ratio (200 vs 500 gives 0.4).
constexpr double kForceBalanceTolerance = 0.15;

std::vector<std::vector<double>> read_columns(const fs::path& csv,
                                              const std::vector<std::string>& names) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::stringstream hs(line);
  for (std::string h; std::getline(hs, h, ',');) header.push_back(h);
  std::vector<std::size_t> index;
  for (const auto& n : names)
    index.push_back(
        static_cast<std::size_t>(std::find(header.begin(), header.end(), n) - header.begin()));
  std::vector<std::vector<double>> columns(names.size());
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream ls(line);
    // An empty field is an undefined number (a Monte Carlo band past the draws' reach).
    for (std::string cell; std::getline(ls, cell, ',');)
      row.push_back(cell.empty() ? std::nan("") : std::stod(cell));
    row.resize(header.size(), std::nan(""));  // a trailing empty field ends the line early
    for (std::size_t k = 0; k < names.size(); ++k) columns[k].push_back(row.at(index[k]));
  }
  return columns;
}
}  // namespace

TEST_CASE("The LANL copper test is in force balance with the scene's bridge settings",
          "[app][experiment][data]") {
  const fs::path root(SHPB_SOURCE_DIR);
  const auto dir = shpb_test::scratch_dir("lanl_cu");
  const auto r =
      shpb_test::run_shpb({"process", (root / "experiments/lanl-cu-ofe-273k/scene.json").string(),
                           "-o", (dir / "out").string(), "--quiet"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto c = read_columns(dir / "out/curve.csv",
                              {"stress_1wave_Pa", "stress_2wave_Pa", "stress_3wave_Pa"});
  const double peak = *std::max_element(c[2].begin(), c[2].end());
  std::vector<double> ratio;  // 1-wave / 2-wave where the specimen carries load
  for (std::size_t i = 0; i < c[2].size(); ++i)
    if (c[2][i] >= 0.5 * peak) ratio.push_back(c[0][i] / c[1][i]);
  REQUIRE(ratio.size() > 100);  // ≥ 10 µs of loading at 10 MS/s
  std::nth_element(ratio.begin(), ratio.begin() + ratio.size() / 2, ratio.end());
  CHECK(ratio[ratio.size() / 2] == Approx(1.0).margin(kForceBalanceTolerance));
  fs::remove_all(dir);
}

}  // namespace tests_app_test_experiment_lanl_cu
