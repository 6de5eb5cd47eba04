// One resolved test set-up (src/model/test_setup.hpp) seen through every command: the striker of
// a chain with a pulse shaper, a gauge's distance to the specimen across a gap, the processing
// options of a tension test in `fit`, a striker launched the way the scene moves it, relative
// fit weights, one record fitted once, one percent parser, and a striker that loads nothing.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "run_shpb.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_app_test_resolved_setup {

namespace fs = std::filesystem;
using nlohmann::json;
using shpb_test::read_text;
using shpb_test::run_shpb;
using shpb_test::scratch_dir;

namespace {

const fs::path kExperiments = fs::path(SHPB_SOURCE_DIR) / "experiments";
// Sums of a few bar lengths in double precision.
constexpr double kRoundOff = 1e-9;
// The tension scene's bilinear specimen (experiments/tension-bonded/scene.json).
constexpr double kYield_Pa = 300e6;
// The processed tension curve lies within 2 % RMS of that law where the specimen is in
// equilibrium (tests/app/test_lab_data.cpp); a yield stress fitted to it within 3 % is the law's.
constexpr double kYieldFit = 0.03;
// A compared pulse of the same 1D model launched as the scene says: only the windows' edges and
// the velocity inferred from the plateau (flat to ~1 %) differ.
constexpr double kSamePulseNrmse = 0.05;

json read_json(const fs::path& file) { return json::parse(read_text(file)); }

void write_json(const fs::path& file, const json& j) { std::ofstream(file) << j.dump(2); }

// The bonded tension experiment simulated once, and its scene with that record as its measurement.
fs::path tension_scene() {
  static const fs::path scene = [] {
    const fs::path dir = scratch_dir("setup_tension");
    const auto r = run_shpb({"simulate", (kExperiments / "tension-bonded/scene.json").string(),
                             "-o", (dir / "sim").string(), "--quiet"});
    INFO(r.err);
    REQUIRE(r.code == 0);
    json s = read_json(kExperiments / "tension-bonded/scene.json");
    s["measurement"]["file"] = (dir / "sim/gauges.csv").string();
    write_json(dir / "scene.json", s);
    return dir / "scene.json";
  }();
  return scene;
}

// A campaign fitting the bilinear yield stress to the processed curves only (no simulation).
json curve_campaign(const json& tests) {
  return {{"tests", tests},
          {"material",
           {{"model", "bilinear"},
            {"density", 2700},
            {"youngs_modulus", "70 GPa"},
            {"poisson_ratio", 0.33},
            {"yield_stress", "200 MPa"},
            {"tangent_modulus", "2 GPa"}}},
          {"free", {{"yield_stress", {"100 MPa", "600 MPa"}}}},
          {"stages", {"curve"}}};
}

shpb_test::RunResult fit(const fs::path& dir, const json& campaign) {
  fs::create_directories(dir);
  write_json(dir / "campaign.json", campaign);
  return run_shpb({"fit", (dir / "campaign.json").string(), "-o", (dir / "fit").string(), "-q",
                   "--bootstrap", "0"});
}

double fitted(const fs::path& dir, const std::string& parameter) {
  return read_json(dir / "fit/summary.json")["parameters"][parameter]["value"].get<double>();
}

}  // namespace

TEST_CASE("With a pulse shaper, process reports the striker velocity the scene gives",
          "[app][setup]") {
  // The striker is the moving bar, not the bar two before the specimen (the copper disc).
  const fs::path dir = scratch_dir("setup_shaper");
  const std::string scene = (kExperiments / "pulse-shaper/scene.json").string();
  auto r = run_shpb({"simulate", scene, "-o", (dir / "sim").string(), "--quiet"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  r = run_shpb({"process", scene, "--signals", (dir / "sim/gauges.csv").string(), "-o",
                (dir / "out").string(), "--quiet"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json v = read_json(dir / "out/summary.json")["striker_velocity_m_s"];
  REQUIRE(v["scene"].is_number());
  CHECK(v["scene"].get<double>() == Approx(10.0).epsilon(kRoundOff));
  const auto shown = json::parse(run_shpb({"validate", scene, "--json"}).out);
  CHECK(shown["roles"]["striker"] == "striker");
  CHECK(shown["roles"]["shapers"] == json::array({"shaper"}));
  CHECK(shown["roles"]["incident"] == "incident");
}

TEST_CASE("validate and process agree on a gauge's distance to the specimen across a gap",
          "[app][setup]") {
  // The pulse travels the bar, not the gap: a gauge given 1 m from the specimen is 1 m from it
  // for validate (which prints it) and for process (which moves the pulses by it).
  const fs::path dir = scratch_dir("setup_gap");
  json s = read_json(kExperiments / "classic-al6061/scene.json");
  s["bars"][1]["gauges"][0] = {{"name", "incident"}, {"distance_to_specimen", "1 m"}};
  s["bars"][1]["gap"] = "0.02 mm";  // closed by the incident pulse's particle velocity in ~3 us
  s["bars"][2]["material"] = (fs::path(SHPB_SOURCE_DIR) / "specimens/al6061-t6.json").string();
  write_json(dir / "scene.json", s);
  auto r = run_shpb({"validate", (dir / "scene.json").string(), "--json"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json shown = json::parse(r.out);
  CHECK(shown["gauges"][0]["distance_to_specimen_m"].get<double>() ==
        Approx(1.0).epsilon(kRoundOff));
  r = run_shpb(
      {"simulate", (dir / "scene.json").string(), "-o", (dir / "sim").string(), "--quiet"});
  REQUIRE(r.code == 0);
  r = run_shpb({"process", (dir / "scene.json").string(), "--signals",
                (dir / "sim/gauges.csv").string(), "-o", (dir / "out").string(), "--quiet"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json used = read_json(dir / "out/summary.json")["gauge_distances_m"];
  CHECK(used["incident"].get<double>() ==
        Approx(shown["gauges"][0]["distance_to_specimen_m"].get<double>()).epsilon(kRoundOff));
  CHECK(used["transmitted"].get<double>() ==
        Approx(shown["gauges"][1]["distance_to_specimen_m"].get<double>()).epsilon(kRoundOff));
}

TEST_CASE("fit's curve stage reduces a tension test as process does", "[app][setup][fit]") {
  const fs::path dir = scratch_dir("setup_fit_tension");
  const auto r = fit(dir, curve_campaign({{{"scene", tension_scene().string()}}}));
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json summary = read_json(dir / "fit/summary.json");
  // Read as tension, the record's first pulses are tensile as they should be: nothing inverted.
  for (const auto& w : summary["warnings"]) {
    INFO(w);
    CHECK(w.get<std::string>().find("inverted") == std::string::npos);
  }
  CHECK(fitted(dir, "yield_stress") == Approx(kYield_Pa).epsilon(kYieldFit));
}

TEST_CASE("fit's signals stage pulls a tension striker and recovers the law", "[app][setup][fit]") {
  // Simulated at the scene's −10 m/s (a tensile pulse), the record matches the measured one only
  // for the specimen's own yield stress; launched at +10 m/s it matches none and runs to a bound.
  const fs::path dir = scratch_dir("setup_fit_tension_signals");
  json c = curve_campaign({{{"scene", tension_scene().string()}}});
  c["stages"] = {"curve", "signals"};
  const auto r = fit(dir, c);
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(fitted(dir, "yield_stress") == Approx(kYield_Pa).epsilon(kYieldFit));
}

TEST_CASE("compare launches a tension striker the way the scene moves it", "[app][setup]") {
  const fs::path dir = scratch_dir("setup_compare_tension");
  const auto r = run_shpb({"compare", tension_scene().string(), "-o", (dir / "out").string(),
                           "--no-dispersion", "--quiet"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json summary = read_json(dir / "out/summary.json");
  CHECK(summary["striker_velocity_m_s"].get<double>() < 0);  // pulled left, as the scene's −10
  std::istringstream lines(read_text(dir / "out/comparison.csv"));
  std::string line;
  std::getline(lines, line);  // header: ..., nrmse, correlation
  int rows = 0;
  while (std::getline(lines, line)) {
    INFO(line);
    std::vector<std::string> fields;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) fields.push_back(cell);
    REQUIRE(fields.size() == 12);
    CHECK(std::stod(fields[10]) < kSamePulseNrmse);
    ++rows;
  }
  CHECK(rows == 3);
}

TEST_CASE("fit weights are relative: scaling every weight changes nothing", "[app][setup][fit]") {
  const fs::path dir = scratch_dir("setup_fit_weights");
  REQUIRE(fit(dir / "one", curve_campaign({{{"scene", tension_scene().string()}}})).code == 0);
  REQUIRE(
      fit(dir / "tiny", curve_campaign({{{"scene", tension_scene().string()}, {"weight", 1e-10}}}))
          .code == 0);
  CHECK(fitted(dir / "tiny", "yield_stress") ==
        Approx(fitted(dir / "one", "yield_stress")).epsilon(kRoundOff));
}

TEST_CASE("fit refuses one scene listed as two tests", "[app][setup][fit]") {
  // One record fitted as two independent tests would halve its variance (standard errors / √2).
  const fs::path dir = scratch_dir("setup_fit_twice");
  const auto r = fit(dir, curve_campaign({{{"scene", tension_scene().string()}, {"name", "a"}},
                                          {{"scene", tension_scene().string()}, {"name", "b"}}}));
  CHECK(r.code == 2);
  CHECK(r.err.find("tests[1].scene") != std::string::npos);
  CHECK(!fs::exists(dir / "fit"));
}

TEST_CASE("A percentage is read by one parser: \"0x10 %\" is refused everywhere",
          "[app][setup][fit]") {
  const fs::path dir = scratch_dir("setup_percent");
  json c = curve_campaign({{{"scene", tension_scene().string()}}});
  c["nuisance"] = {{"striker_velocity", "0x10 %"}};
  auto r = fit(dir, c);
  CHECK(r.code == 2);
  CHECK(r.err.find("nuisance.striker_velocity") != std::string::npos);
  json s = read_json(tension_scene());
  s["simulation"]["tolerance"] = "0x10 %";
  write_json(dir / "scene.json", s);
  r = run_shpb({"validate", (dir / "scene.json").string()});
  CHECK(r.code == 2);
  CHECK(r.err.find("simulation.tolerance") != std::string::npos);
}

TEST_CASE("A striker moving away from the chain is refused: nothing would be recorded",
          "[app][setup]") {
  const fs::path dir = scratch_dir("setup_away");
  json s = read_json(kExperiments / "classic-al6061/scene.json");
  s["bars"][0]["velocity"] = "-15 m/s";
  s["bars"][2]["material"] = (fs::path(SHPB_SOURCE_DIR) / "specimens/al6061-t6.json").string();
  write_json(dir / "scene.json", s);
  for (const std::string command : {"validate", "simulate"}) {
    std::vector<std::string> args = {command, (dir / "scene.json").string()};
    if (command == "simulate") args.insert(args.end(), {"-o", (dir / "out").string(), "--quiet"});
    const auto r = run_shpb(args);
    INFO(command << ": " << r.err);
    CHECK(r.code == 2);
    CHECK(r.err.find("bars[0].velocity") != std::string::npos);
  }
  CHECK(!fs::exists(dir / "out"));
}

TEST_CASE("A striker pulling away from a bonded joint with a gap is refused, naming the gap",
          "[app][setup]") {
  // docs/scene-format.md, Roles: a striker loads the chain when it pulls it through a bonded
  // interface without a gap; with a gap it moves away rigidly for ever.
  const fs::path dir = scratch_dir("setup_bonded_gap");
  json s = read_json(kExperiments / "striker-on-bar/scene.json");
  s["contact"] = {{"method", "bonded"}};
  s["bars"][0]["velocity"] = "-10 m/s";
  s["bars"][0]["gap"] = "1 mm";
  write_json(dir / "scene.json", s);
  const auto r = run_shpb({"validate", (dir / "scene.json").string()});
  INFO(r.err);
  CHECK(r.code == 2);
  CHECK(r.err.find("bars[0].velocity") != std::string::npos);
  CHECK(r.err.find("bonded without a gap") != std::string::npos);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
}

}  // namespace tests_app_test_resolved_setup
