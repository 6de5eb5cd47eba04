// `shpb study --sweep monte-carlo` (study/monte_carlo_sweep.hpp): the gauge band of a normal
// striker velocity follows the elastic impact's ε = v/(2 c0) draw by draw; the study run in shards
// through parts equals the in-process one; a bad distributions file is an exit-2 error naming it.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "../app/output_schema_check.hpp"
#include "../app/run_shpb.hpp"
#include "core/shards.hpp"
#include "study/study_report.hpp"
#include "study/study_run.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_study_test_monte_carlo {

using namespace shpb;
namespace fs = std::filesystem;

namespace {

const std::string kStrikerOnBar =
    std::string(SHPB_SOURCE_DIR) + "/experiments/striker-on-bar/scene.json";
const std::string kClassic =
    std::string(SHPB_SOURCE_DIR) + "/experiments/classic-al6061/scene.json";

// A CSV as rows of cells (header first).
std::vector<std::vector<std::string>> read_csv(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string c; std::getline(s, c, ',');) cells.push_back(c);
    rows.push_back(cells);
  }
  return rows;
}

std::size_t column(const std::vector<std::string>& header, const std::string& name) {
  const auto it = std::find(header.begin(), header.end(), name);
  REQUIRE(it != header.end());
  return static_cast<std::size_t>(it - header.begin());
}

double quantile7(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  const double h = p * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (h - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

}  // namespace

TEST_CASE("A normal striker velocity gives the incident plateau band of eps = v/(2 c0)",
          "[study][monte-carlo][app]") {
  const fs::path dir = shpb_test::scratch_dir("study_monte_carlo");
  const fs::path dist = dir / "distributions.json";
  std::ofstream(dist) << R"({"values": {"striker.velocity": {"normal": "5 %"}}})";
  const std::size_t draws = 40;
  const auto r = shpb_test::run_shpb({"study", kStrikerOnBar, "-o", (dir / "out").string(),
                                      "--sweep", "monte-carlo", "--distributions", dist.string(),
                                      "--draws", std::to_string(draws), "--seed", "7", "-q"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  shpb_test::check_schema_columns(dir / "out" / "draws.csv", "draws");
  shpb_test::check_schema_columns(dir / "out" / "gauge_bands.csv", "gauge_bands");
  // The drawn velocities (m/s): N(10 m/s, 0.5 m/s).
  const auto drawn = read_csv(dir / "out" / "draws.csv");
  REQUIRE(drawn.size() == draws + 1);
  const std::size_t vc = column(drawn[0], "striker.velocity_m_s");
  std::vector<double> v;
  for (std::size_t i = 1; i < drawn.size(); ++i) v.push_back(std::stod(drawn[i][vc]));
  double mean = 0, var = 0;
  for (double x : v) mean += x / static_cast<double>(draws);
  for (double x : v) var += (x - mean) * (x - mean) / static_cast<double>(draws - 1);
  // The draws are the declared normal: mean within 3 standard errors σ/√N, standard deviation
  // within 3 of its standard errors σ/√(2(N−1)).
  const double sigma = 0.5, n = static_cast<double>(draws);
  CHECK(std::abs(mean - 10) < 3 * sigma / std::sqrt(n));
  CHECK(std::abs(std::sqrt(var) - sigma) < 3 * sigma / std::sqrt(2 * (n - 1)));

  // Identical steel striker and bar: the gauge sees the square pulse ε = −v/(2 c0) from 0.75 m/c0
  // for 2 · 0.3 m/c0 (docs/methods.md §4). The bars are linear elastic and the meshes do not depend
  // on v, so each draw's plateau strain is its own v/(2 c0): the band's quantiles are those of the
  // drawn v over 2 c0, and the spread of the peak strain that of v over 2 c0.
  const double c0 = std::sqrt(200e9 / 7850), t_mid = 0.75 / c0 + 0.3 / c0;
  // The meshed plateau ripples about V/(2 c0) by well under 1 % at mid-pulse (the pareto study's
  // exact square pulse); sampling error does not enter (both sides are the same draws).
  constexpr double kPlateauRipple = 0.01;
  const auto bands = read_csv(dir / "out" / "gauge_bands.csv");
  const std::size_t tc = column(bands[0], "time_s"), lo = column(bands[0], "gauge_p2.5"),
                    mid = column(bands[0], "gauge_p50"), hi = column(bands[0], "gauge_p97.5");
  std::size_t row = 1;
  for (std::size_t i = 1; i < bands.size(); ++i)
    if (std::abs(std::stod(bands[i][tc]) - t_mid) < std::abs(std::stod(bands[row][tc]) - t_mid))
      row = i;
  // Compression is negative: the 2.5 % strain is the 97.5 % velocity.
  CHECK(std::stod(bands[row][lo]) ==
        Approx(-quantile7(v, 0.975) / (2 * c0)).epsilon(kPlateauRipple));
  CHECK(std::stod(bands[row][mid]) ==
        Approx(-quantile7(v, 0.5) / (2 * c0)).epsilon(kPlateauRipple));
  CHECK(std::stod(bands[row][hi]) ==
        Approx(-quantile7(v, 0.025) / (2 * c0)).epsilon(kPlateauRipple));
  const auto summary = nlohmann::json::parse(shpb_test::read_text(dir / "out" / "summary.json"));
  const auto& peak = summary.at("quantities").at("gauge_peak_strain");
  // The peak includes the meshed front's overshoot, the same factor in every draw: linear elastic
  // bars and a contact that only closes make each draw's record the nominal one times v/v0, so
  // the peak's spread is v's times the nominal peak over v0 = 10 m/s (to rounding).
  constexpr double kLinearScaling = 1e-6;
  CHECK(peak.at("standard_deviation").get<double>() ==
        Approx(std::sqrt(var) / 10 * peak.at("nominal").get<double>()).epsilon(kLinearScaling));
  CHECK(peak.at("contributions").at(0).at("value") == "striker.velocity");
  CHECK(summary.at("failed_draws") == 0);

  SECTION("A bad distributions file is an exit-2 error naming it, with nothing written") {
    for (const auto& [text, says] :
         {std::pair{R"({"values": {"striker.velocty": {"normal": "1 %"}}})", "striker.velocity"},
          std::pair{R"({"values": {"striker.velocity": {"normal": "-1 m/s"}}})", "normal"},
          std::pair{R"({"values": {"bar.length": {"uniform": ["2 m", "1 m"]}}})", "low < high"},
          // A striker at 10 m/s drawn with s.d. 12 m/s (or from [-1, 20] m/s) goes backwards in
          // many draws: the spread must keep the sign (s.d. below a sixth of the value).
          std::pair{R"({"values": {"striker.velocity": {"normal": "12 m/s"}}})", "must stay > 0"},
          std::pair{R"({"values": {"striker.velocity": {"uniform": ["-1 m/s", "20 m/s"]}}})",
                    "must keep its sign"},
          // A key of the file's other object is named there (before: the top level's were listed).
          std::pair{R"({"values": {"striker.velocity": {"normal": "1 %"}}, "normal": "1 %"})",
                    "normal: unknown key: not here; \"normal\" is a key of values.<scene value>"},
          // JSON lets the second "values" silently win; every input of shpb refuses it.
          std::pair{R"({"values": {"striker.velocity": {"normal": "1 %"}}, "values": {}})",
                    "values: duplicate key"}}) {
      std::ofstream(dist) << text;
      const auto bad =
          shpb_test::run_shpb({"study", kStrikerOnBar, "-o", (dir / "bad").string(), "--sweep",
                               "monte-carlo", "--distributions", dist.string(), "-q"});
      INFO(bad.err);
      CHECK(bad.code == 2);
      CHECK(bad.err.find(dist.string()) != std::string::npos);
      CHECK(bad.err.find(says) != std::string::npos);
      CHECK(std::count(bad.err.begin(), bad.err.end(), '\n') == 1);
      CHECK_FALSE(fs::exists(dir / "bad"));
    }
  }
}

// A draw whose Poisson's ratio reaches 0.5 is refused by the scene (an incompressible solid has
// no finite bulk modulus) and fails alone: a third of the draws of [0.3, 0.6], all of [0.5, 0.6].
TEST_CASE("A Monte Carlo study warns of its failed draws, and fails when every draw fails",
          "[study][monte-carlo]") {
  const fs::path dir = shpb_test::scratch_dir("study_failed_draws");
  const fs::path dist = dir / "distributions.json";
  const auto study = [&](const char* range) {
    std::ofstream(dist) << std::string(R"({"values": {"bar.poisson_ratio": {"uniform": )") + range +
                               "}}}";
    fs::remove_all(dir / "out");
    return shpb_test::run_shpb({"study", kStrikerOnBar, "-o", (dir / "out").string(), "--sweep",
                                "monte-carlo", "--distributions", dist.string(), "--draws", "6",
                                "-q"});
  };
  const auto some = study("[0.3, 0.6]");
  INFO(some.err);
  REQUIRE(some.code == 0);
  const auto summary = nlohmann::json::parse(shpb_test::read_text(dir / "out" / "summary.json"));
  const auto failed = summary.at("failed_draws").get<std::size_t>();
  REQUIRE(failed > 0);
  REQUIRE(failed < 6);
  CHECK(some.err.rfind(
            "warning: study monte-carlo: " + std::to_string(failed) + " of 6 draws failed", 0) ==
        0);
  CHECK(some.err.find("the first: bar.poisson_ratio drawn") != std::string::npos);
  CHECK(std::count(some.err.begin(), some.err.end(), '\n') == 1);

  const auto all = study("[0.5, 0.6]");
  INFO(all.err);
  CHECK(all.code == 3);
  CHECK(all.err.rfind("error: study monte-carlo: 6 of 6 draws failed: bar.poisson_ratio drawn",
                      0) == 0);
  CHECK(std::count(all.err.begin(), all.err.end(), '\n') == 1);
  // Nothing written: neither the output folder nor a temporary one beside it.
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(dir)) left.push_back(e.path().filename().string());
  CHECK(left == std::vector<std::string>{"distributions.json"});
  fs::remove_all(dir);
}

// docs/commands.md: progress is a plain line every 10 % and at the end. The end is every run done:
// 199 of 200 runs (99.5 %) rounded to 100 % and ended the lines at "199/200" (the stability
// sweep's at 16829/16913).
TEST_CASE("A study's progress reaches its total", "[study][monte-carlo][app]") {
  const fs::path dir = shpb_test::scratch_dir("study_progress");
  const fs::path dist = dir / "distributions.json";
  std::ofstream(dist) << R"({"values": {"striker.velocity": {"normal": "5 %"}}})";
  const auto r = shpb_test::run_shpb({"study", kStrikerOnBar, "-o", (dir / "out").string(),
                                      "--sweep", "monte-carlo", "--distributions", dist.string(),
                                      "--draws", "199", "--threads", "1"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  std::vector<std::string> progress;  // the lines "study monte-carlo: P% D/T runs"
  std::istringstream lines(r.err);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("study monte-carlo: ", 0) == 0) progress.push_back(line);
  REQUIRE_FALSE(progress.empty());
  CHECK(progress.back() == "study monte-carlo: 100% 200/200 runs");
  CHECK(std::count_if(progress.begin(), progress.end(), [](const std::string& line) {
          return line.find(" 100% ") != std::string::npos;
        }) == 1);
  fs::remove_all(dir);
}

TEST_CASE("A Monte Carlo study run in shards through parts equals the in-process study",
          "[study][monte-carlo][shards]") {
  const fs::path dir = shpb_test::scratch_dir("study_monte_carlo_shards");
  const fs::path dist = dir / "distributions.json";
  std::ofstream(dist) << R"({"values": {"striker.velocity": {"normal": "3 %"},
      "specimen.A": {"uniform": "5 %"}, "specimen.length": {"normal": "0.02 mm"}}})";
  const Scene scene = read_scene(kClassic);
  StudyOptions options;
  options.sweep = Sweep::kMonteCarlo;
  options.distributions = dist;
  options.draws = 3;
  StudyPlan plan = make_study_plan(options, scene);
  plan.id = new_plan_id();
  // In process.
  StudyResults whole;
  run_plan(plan, scene, all_runs(plan.runs()), 2, {}, whole);
  fs::create_directories(dir / "whole");
  write_study(plan, scene, whole, 2, 1.0, dir / "whole");
  // In two shards, each through its part's text as between machines, and the plan's text.
  const StudyPlan read = [&] {
    std::ofstream(dir / "plan.json") << plan_text(plan);
    return read_study_plan(dir / "plan.json");
  }();
  StudyResults merged;
  merged.monte_carlo.resize(read.runs());
  for (std::size_t k = 0; k < 2; ++k) {
    const auto runs = shard_runs(read.runs(), {k, 2});
    StudyResults own;
    run_plan(read, scene, runs, 1, {}, own);
    const auto text = part_json(read, own, runs).dump();
    read_part(nlohmann::json::parse(text), "part", read, runs, merged);
  }
  fs::create_directories(dir / "sharded");
  write_study(read, scene, merged, 1, 2.0, dir / "sharded");
  REQUIRE(fs::exists(dir / "whole" / "curve_bands.csv"));
  shpb_test::check_schema_columns(dir / "whole" / "curve_bands.csv", "curve_bands");
  for (const char* file : {"draws.csv", "gauge_bands.csv", "curve_bands.csv"})
    CHECK(shpb_test::read_text(dir / "whole" / file) ==
          shpb_test::read_text(dir / "sharded" / file));
  auto summary = [&](const char* which) {
    auto j = nlohmann::json::parse(shpb_test::read_text(dir / which / "summary.json"));
    j.erase("threads");
    j.erase("wall_time_s");
    return j;
  };
  CHECK(summary("whole") == summary("sharded"));
  CHECK(summary("whole").at("failed_draws") == 0);
}

}  // namespace tests_study_test_monte_carlo
