// Accuracy against cost: the Pareto front, equal-error interpolation, the exact
// reference of a striker on a bar, and a sweep whose results do not depend on the thread count.

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
#include "../solver/test_scenes.hpp"
#include "study/pareto_front.hpp"
#include "study/pareto_sweep.hpp"
#include "study/reference.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_study_test_pareto {

using namespace shpb;
namespace fs = std::filesystem;

namespace {
// The exact square pulse is met to a few per cent in L2 at C ≈ 1: the residual is the
// smeared front and the contact's own ringing (docs/methods.md §2), and it shrinks with h.
constexpr double kExactPulseError = 0.2;

const double kArea = 2.85e-4;

// Striker, a gauged bar and a softer gauged bar (different element steps, no exact solution).
Scene three_bars() {
  BarSpec striker = test::bar("striker", test::steel(), 0.05, kArea, 10, 10.0);
  BarSpec incident = test::bar("incident", test::steel(), 0.2, kArea, 40);
  incident.gauges.push_back({"incident", 0.1});
  BarSpec soft = test::bar("soft", test::elastic(70e9, 2700, "aluminium"), 0.2, kArea, 50);
  soft.gauges.push_back({"transmitted", 0.1});
  return test::chain({striker, incident, soft}, 80e-6, ContactMethod::kLocalizedBipenalty,
                     Stepping::kAsynchronous);
}

// A 50 mm steel striker at 10 m/s on a 200 mm gauged bar, 60 µs, `extra` keys added at the top
// level (each followed by a comma).
void write_tiny_striker_on_bar(const fs::path& file, const std::string& extra = "") {
  std::ofstream(file) << R"({ "name": "tiny striker on bar",
    "bars": [ { "name": "striker", "material": "steel", "length": "50 mm", "area": "2.85 cm2",
                "velocity": "10 m/s", "elements": 10 },
              { "name": "bar", "material": "steel", "length": "200 mm", "area": "2.85 cm2",
                "elements": 40, "gauges": [ { "name": "gauge", "position": "100 mm" } ] } ],
    "materials": { "steel": { "model": "elastic", "density": 8000, "youngs_modulus": "200 GPa",
                              "poisson_ratio": 0.29 } },)"
                      << extra << R"(
    "simulation": { "duration": "60 us" } })";
}
}  // namespace

TEST_CASE("The Pareto front keeps exactly the runs no other run beats in both error and cost",
          "[study][pareto]") {
  const double nan = std::nan("");
  const std::vector<double> error = {0.1, 0.05, 0.2, 0.05, nan, 0.01};
  const std::vector<double> cost = {1.0, 2.0, 0.5, 3.0, 0.1, 10.0};
  const std::vector<bool> expected = {true, true, true, false, false, true};
  CHECK(pareto_front(error, cost) == expected);
}

TEST_CASE("Cost at equal error interpolates a power law exactly", "[study][pareto]") {
  // cost = 1/error² on three points: the log–log interpolation is exact in between.
  const std::vector<double> errors = {0.4, 0.1, 0.2}, costs = {6.25, 100, 25};
  REQUIRE(cost_at_error(errors, costs, 0.15).has_value());
  CHECK(*cost_at_error(errors, costs, 0.15) == Approx(1 / (0.15 * 0.15)).epsilon(1e-12));
  CHECK_FALSE(cost_at_error(errors, costs, 0.05).has_value());
}

TEST_CASE("A striker on an identical bar is measured against the exact square pulse",
          "[study][pareto]") {
  BarSpec bar = test::bar("bar", test::steel(), 0.5, kArea, 250);
  bar.gauges.push_back({"gauge", 0.25});
  const Scene scene =
      test::chain({test::bar("striker", test::steel(), 0.1, kArea, 50, 10.0), bar}, 150e-6,
                  ContactMethod::kLocalizedBipenalty, Stepping::kAsynchronous);
  const auto reference = exact_reference(scene);
  REQUIRE(reference.has_value());
  const double c0 = std::sqrt(200e9 / 8000.0);
  CHECK(reference->strain(0, 0.25 / c0 + 1e-6) == Approx(-10.0 / (2 * c0)));
  CHECK(reference->strain(0, 0.25 / c0 + 2 * 0.1 / c0 + 1e-6) == 0);
  const ParetoStudy study = run_pareto_sweep(
      scene,
      pareto_cases({ContactMethod::kLocalizedBipenalty}, {Stepping::kAsynchronous}, {0.5, 1, 2}),
      1);
  REQUIRE(study.reference_exact);
  for (const ParetoRow& r : study.rows) {
    INFO("resolution " << r.run.resolution << ": error " << r.error);
    CHECK(r.stable);
    CHECK(r.error < kExactPulseError);
  }
  CHECK(study.rows[2].error < study.rows[0].error);  // finer is closer to the exact pulse
}

TEST_CASE("A pareto sweep gives the same results on one thread and on two", "[study][pareto]") {
  const Scene scene = three_bars();
  REQUIRE_FALSE(exact_reference(scene).has_value());
  const auto cases = pareto_cases({}, {}, {0.5, 1});
  const ParetoStudy one = run_pareto_sweep(scene, cases, 1);
  const ParetoStudy two = run_pareto_sweep(scene, cases, 2);
  REQUIRE(one.rows.size() == cases.size());
  REQUIRE(two.rows.size() == cases.size());
  CHECK(one.reference == two.reference);
  for (std::size_t i = 0; i < cases.size(); ++i) {
    INFO("case " << i);
    CHECK(one.rows[i].stable == two.rows[i].stable);
    CHECK(one.rows[i].node_updates == two.rows[i].node_updates);
    // Bit for bit (NaN for unstable runs on both).
    CHECK((one.rows[i].error == two.rows[i].error ||
           (std::isnan(one.rows[i].error) && std::isnan(two.rows[i].error))));
  }
}

TEST_CASE("A pareto sweep of a scene whose every interface is bonded says it compares no method",
          "[study][app]") {
  // A bonded interface stays bonded in every run (docs/commands.md, study): the four methods'
  // rows of a chain glued throughout (a tension bar's striker and specimen) are the same run.
  const shpb_test::ScratchDir scratch("study_bonded");
  const fs::path& dir = scratch.path();
  const fs::path scene = dir / "scene.json";
  write_tiny_striker_on_bar(scene, R"("contact": { "method": "bonded" },)");
  const auto r = shpb_test::run_shpb(
      {"study", scene.string(), "-o", (dir / "out").string(), "--threads", "1", "--quiet"});
  REQUIRE(r.code == 0);
  CHECK(r.err.find("every interface of the scene is bonded") != std::string::npos);
  std::ifstream summary(dir / "out" / "summary.json");
  const auto j = nlohmann::json::parse(summary);
  REQUIRE(j.contains("warnings"));
  REQUIRE(j["warnings"].size() == 1);
}

TEST_CASE("shpb study writes pareto.csv with the documented columns, and exits 2 on a bad scene",
          "[study][app]") {
  const shpb_test::ScratchDir scratch("study");
  const fs::path& dir = scratch.path();
  const fs::path scene = dir / "scene.json";
  write_tiny_striker_on_bar(scene);
  const auto ok = shpb_test::run_shpb({"study", scene.string(), "-o", (dir / "out").string(),
                                       "--sweep", "pareto", "--threads", "2", "--quiet"});
  REQUIRE(ok.code == 0);
  shpb_test::check_schema_columns(dir / "out" / "pareto.csv", "pareto");
  std::ifstream csv(dir / "out" / "pareto.csv");
  std::string header;
  std::getline(csv, header);
  CHECK(header ==
        "method,stepping,resolution,error,wall_time_s,node_updates,stable,"
        "pareto_front_wall_time,pareto_front_node_updates,recorded_error");
  struct Row {
    double error, wall, updates;
    bool front_wall, front_updates;
  };
  std::vector<Row> rows;
  for (std::string line; std::getline(csv, line);) {
    std::vector<std::string> c;
    std::stringstream cells(line);
    for (std::string x; std::getline(cells, x, ',');) c.push_back(x);
    if (!line.empty() && line.back() == ',') c.push_back("");  // an empty last field
    REQUIRE(c.size() == 10);
    for (int k : {6, 7, 8}) CHECK((c[k] == "0" || c[k] == "1"));  // flags as numbers (report)
    CHECK(c[9].empty() == c[3].empty());  // the recorded error exactly where the error is
    rows.push_back({c[3].empty() ? std::nan("") : std::stod(c[3]), std::stod(c[4]), std::stod(c[5]),
                    c[7] == "1", c[8] == "1"});
  }
  // 3 methods × 2 steppings × 5 resolutions, and finite localized links asynchronous × 5.
  CHECK(rows.size() == 3 * 2 * 5 + 5);
  // The front columns mean what docs/outputs.md says: a run is on the front by a cost exactly
  // when it has an error (an unstable run has none) and no other run is at most as bad in error
  // and cost and better in one.
  auto dominated = [&](std::size_t i, double Row::*cost) {
    for (std::size_t j = 0; j < rows.size(); ++j)
      if (j != i && rows[j].error <= rows[i].error && rows[j].*cost <= rows[i].*cost &&
          (rows[j].error < rows[i].error || rows[j].*cost < rows[i].*cost))
        return true;
    return false;
  };
  int on_front = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    INFO("row " << i + 1);
    const bool measured = std::isfinite(rows[i].error);
    CHECK(rows[i].front_wall == (measured && !dominated(i, &Row::wall)));
    CHECK(rows[i].front_updates == (measured && !dominated(i, &Row::updates)));
    on_front += rows[i].front_wall;
  }
  CHECK(on_front >= 1);
  CHECK(shpb_test::read_text(dir / "out" / "summary.json").find("\"reference_exact\": true") !=
        std::string::npos);

  std::ofstream(dir / "bad.json") << R"({ "name": "bad", "bars": [] })";
  const auto bad = shpb_test::run_shpb(
      {"study", (dir / "bad.json").string(), "-o", (dir / "bad_out").string(), "--quiet"});
  CHECK(bad.code == 2);
  CHECK(bad.err.rfind("error: ", 0) == 0);
  CHECK_FALSE(fs::exists(dir / "bad_out"));
}

}  // namespace tests_study_test_pareto
