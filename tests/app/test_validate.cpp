// `shpb validate --json` prints the resolved set-up: the same mesh and steps as discretize()
// (what simulate uses), wave speeds and impedances from the materials (docs/methods.md notation:
// c0 = sqrt(E/ρ), Z = ρ c0 A, C = c0 Δt / h) and gauge distances to the specimen faces.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "model/discretization.hpp"
#include "model/scene_validation.hpp"
#include "run_shpb.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_app_test_validate {

using nlohmann::json;
namespace fs = std::filesystem;
using namespace shpb;

namespace {
// Values pass through JSON text as shortest round-trip doubles: agreement to round-off.
constexpr double kRoundOff = 1e-12;

json validate_json(const fs::path& scene, std::vector<std::string> options = {}) {
  options.insert(options.begin(), {"validate", "--json"});
  options.push_back(scene.string());
  const auto r = shpb_test::run_shpb(options);
  INFO(r.err);
  REQUIRE(r.code == 0);
  return json::parse(r.out);
}
}  // namespace

TEST_CASE("validate --json reports what discretize() gives simulate", "[app][validate]") {
  const auto file = fs::path(SHPB_SOURCE_DIR) / "experiments/classic-al6061/scene.json";
  const json v = validate_json(file);
  Scene scene = read_scene(file);
  const ChainDiscretization d =
      resolve_scene(scene);  // as simulate meshes it (the default tolerance)
  REQUIRE(v["bars"].size() == scene.bars.size());
  for (std::size_t i = 0; i < scene.bars.size(); ++i) {
    const auto& b = v["bars"][i];
    INFO(b["name"]);
    CHECK(b["elements"] == d.bars[i].elements);
    CHECK(b["time_step_s"].get<double>() == Approx(d.bars[i].time_step_s).epsilon(kRoundOff));
    CHECK(b["courant"].get<double>() == Approx(d.bars[i].courant).epsilon(kRoundOff));
    // C = c0 Δt / h, with c0 = sqrt(E/ρ) and Z = ρ c0 A.
    const double c0 =
        std::sqrt(b["youngs_modulus_Pa"].get<double>() / b["density_kg_m3"].get<double>());
    CHECK(b["wave_speed_m_s"].get<double>() == Approx(c0).epsilon(kRoundOff));
    CHECK(b["impedance_kg_s"].get<double>() ==
          Approx(b["density_kg_m3"].get<double>() * c0 * b["area_m2"].get<double>())
              .epsilon(kRoundOff));
    CHECK(b["courant"].get<double>() ==
          Approx(c0 * b["time_step_s"].get<double>() / b["element_length_m"].get<double>())
              .epsilon(kRoundOff));
    CHECK(b["elements"].get<int>() * b["element_length_m"].get<double>() ==
          Approx(b["length_m"].get<double>()).epsilon(kRoundOff));
  }
  // Maraging steel: c0 = sqrt(200e9 / 8080) = 4975.2 m/s.
  CHECK(v["bars"][1]["wave_speed_m_s"].get<double>() == Approx(4975.2).epsilon(1e-5));
  CHECK(v["specimen"] == "specimen");
  CHECK(v["duration_s"].get<double>() == Approx(800e-6).epsilon(kRoundOff));
  CHECK(v["sample_rate_Hz"].get<double>() == 10e6);
  REQUIRE(v["gauges"].size() == 2);
  CHECK(v["gauges"][0]["distance_to_specimen_m"].get<double>() == Approx(1.0).epsilon(kRoundOff));
  CHECK(v["gauges"][1]["distance_to_specimen_m"].get<double>() == Approx(1.0).epsilon(kRoundOff));
  REQUIRE(v["interfaces"].size() == 3);
  CHECK(v["interfaces"][0]["method"] == "localized-bipenalty");
}

TEST_CASE("validate says why a scene keeps the automatic meshes instead of the default tolerance",
          "[app][validate][tolerance]") {
  const fs::path experiments = fs::path(SHPB_SOURCE_DIR) / "experiments";
  // Each reason the default tolerance is withheld, on the experiment that has it; the classic
  // test, where it applies, has none.
  const std::pair<const char*, const char*> cases[] = {
      {"pulse-shaper", "a pulse shaper"},                // a material-law bar besides the specimen
      {"tension-bonded", "a Courant number is set"},     // the scene's own numerics
      {"epoxy-resin-sample01", "no pulse to predict"}};  // a measured record: no striker
  for (const auto& [experiment, reason] : cases) {
    const json v = validate_json(experiments / experiment / "scene.json");
    INFO(experiment);
    REQUIRE(!v.contains("tolerance"));
    REQUIRE(v["tolerance_withheld"].get<std::string>().find(reason) != std::string::npos);
  }
  const json classic = validate_json(experiments / "classic-al6061" / "scene.json");
  REQUIRE(classic.contains("tolerance"));
  REQUIRE(!classic.contains("tolerance_withheld"));
}

TEST_CASE("A scene without a gauge keeps the automatic meshes and closes its energy balance",
          "[app][validate][tolerance]") {
  // The default tolerance bounds a gauge error: without a gauge there is none to bound, and the
  // error model's coarsest mesh (10 elements over the pulse) would leave the interface force and
  // the field that coarse. The striker-on-bar without its gauge: identical bars on one step, so
  // the energy balance closes to round-off (docs/methods.md §3.3); the documented warning
  // threshold is 1 % (docs/outputs.md, summary.json warnings).
  constexpr double kPlausibleEnergyError = 0.01;
  const auto dir = shpb_test::scratch_dir("validate_no_gauge");
  json scene = json::parse(
      shpb_test::read_text(fs::path(SHPB_SOURCE_DIR) / "experiments/striker-on-bar/scene.json"));
  scene["bars"][1].erase("gauges");
  const fs::path file = dir / "scene.json";
  std::ofstream(file) << scene.dump();
  const json v = validate_json(file);
  CHECK(!v.contains("tolerance"));
  CHECK(v["tolerance_withheld"].get<std::string>().find("no gauge") != std::string::npos);
  // The automatic meshes: ~1 mm elements (docs/scene-format.md, bars.elements).
  CHECK(v["bars"][0]["elements"].get<int>() == 300);
  CHECK(v["bars"][1]["elements"].get<int>() == 1500);
  const auto r =
      shpb_test::run_shpb({"simulate", file.string(), "-o", (dir / "out").string(), "--quiet"});
  REQUIRE(r.code == 0);
  const json summary = json::parse(shpb_test::read_text(dir / "out" / "summary.json"));
  CHECK(summary["energy_error"].get<double>() < kPlausibleEnergyError);
  CHECK(summary["warnings"].empty());
  // A gauge on the striker alone: the model predicts only gauges right of the striker, so the
  // default is withheld there too (it had meshed the striker at 5 elements).
  scene["bars"][0]["gauges"] = {{{"name", "striker"}, {"position", "0.1 m"}}};
  std::ofstream(file) << scene.dump();
  const json on_striker = validate_json(file);
  CHECK(!on_striker.contains("tolerance"));
  CHECK(on_striker["bars"][0]["elements"].get<int>() == 300);
  fs::remove_all(dir);
}

TEST_CASE("validate applies --contact, --stepping and --courant as simulate would",
          "[app][validate]") {
  const auto file = fs::path(SHPB_SOURCE_DIR) / "experiments/striker-on-bar/scene.json";
  const json v =
      validate_json(file, {"--contact", "penalty", "--stepping", "global", "--courant", "0.5"});
  CHECK(v["stepping"] == "global");
  CHECK(v["interfaces"][0]["method"] == "penalty");
  // Global stepping: every bar takes the same (smallest) step.
  const double dt = v["bars"][0]["time_step_s"].get<double>();
  for (const auto& b : v["bars"]) CHECK(b["time_step_s"].get<double>() == dt);
  CHECK(v["warnings"].empty());
}

TEST_CASE("validate and simulate refuse a --courant outside 0 < C <= 1 alike", "[app][validate]") {
  // Lumped central difference is unstable above C = 1 (docs/methods.md §1); the scene's own
  // simulation.courant has the same range.
  const auto file = fs::path(SHPB_SOURCE_DIR) / "experiments/striker-on-bar/scene.json";
  const auto dir = shpb_test::scratch_dir("validate_courant");
  for (const char* c : {"1.2", "0"}) {
    for (const char* command : {"validate", "simulate"}) {
      std::vector<std::string> args{command, file.string(), "--courant", c};
      if (std::string(command) == "simulate")
        args.insert(args.end(), {"-o", (dir / "out").string(), "--quiet"});
      const auto r = shpb_test::run_shpb(args);
      INFO(command << " --courant " << c << ": " << r.err);
      CHECK(r.code == 2);
      CHECK(r.err == std::string("error: --courant: ") + c +
                         ": must be in (0, 1]: lumped central difference is stable for C <= 1\n");
      CHECK_FALSE(fs::exists(dir / "out"));
    }
  }
  // A tiny one is in range but multiplies every bar's steps (1/C) beyond the machine's budget:
  // the refusal names the option, not the scene's duration or bars.
  const auto r = shpb_test::run_shpb({"validate", file.string(), "--courant", "1e-9"});
  INFO(r.err);
  CHECK(r.code == 2);
  CHECK(r.err.rfind("error: --courant: 1e-09: every bar's steps grow as 1/C", 0) == 0);
  fs::remove_all(dir);
}

TEST_CASE(
    "The option --courant is read as the scene's simulation.courant: a number or a percentage",
    "[app][validate]") {
  // docs/commands.md: --courant is checked with the scene, by the scene's own rules, and a
  // dimensionless quantity may be written in percent (docs/scene-format.md, Quantities).
  const auto file = fs::path(SHPB_SOURCE_DIR) / "experiments/striker-on-bar/scene.json";
  const json half = validate_json(file, {"--courant", "0.5"});
  for (const char* percent : {"50 %", "50%"}) {
    INFO(percent);
    const json v = validate_json(file, {"--courant", percent});
    for (std::size_t i = 0; i < v["bars"].size(); ++i)
      CHECK(v["bars"][i]["time_step_s"].get<double>() ==
            Approx(half["bars"][i]["time_step_s"].get<double>()).epsilon(kRoundOff));
  }
  // Not a number, or a quantity with a unit: one line naming the option and the text given.
  for (const std::string bad : {"abc", "1 mm"}) {
    const auto r = shpb_test::run_shpb({"validate", file.string(), "--courant", bad});
    INFO(bad << ": " << r.err);
    CHECK(r.code == 2);
    CHECK(r.err.rfind("error: --courant: \"" + bad + "\": ", 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
}

TEST_CASE("validate warns when pulses overlap at a gauge or the duration is too short",
          "[app][validate]") {
  // Identical steel bars, 0.3 m striker: the incident pulse is 2 × 0.3 m long, so a gauge closer
  // than 0.3 m to the specimen sees incident and reflected pulses overlap (docs/methods.md §4).
  auto scene = [](const std::string& gauge_to_face, const std::string& duration) {
    return R"({"bars": [
      {"name": "s", "material": "steel", "length": "0.3 m", "diameter": 0.02, "velocity": 10},
      {"name": "i", "material": "steel", "length": "2 m", "diameter": 0.02,
       "gauges": [{"name": "g1", "position": ")" +
           gauge_to_face + R"("}]},
      {"name": "x", "material": "steel", "length": "5 mm", "diameter": 0.01},
      {"name": "t", "material": "steel", "length": "2 m", "diameter": 0.02,
       "gauges": [{"name": "g2", "position": "1 m"}]}],
      "specimen": "x",
      "materials": {"steel": {"model": "elastic", "density": 7850, "youngs_modulus": 2e11,
                              "poisson_ratio": 0.29}},
      "simulation": {"duration": ")" +
           duration + R"("}})";
  };
  const auto dir = shpb_test::scratch_dir("validate_warnings");
  auto warnings = [&](const std::string& text) {
    std::ofstream(dir / "scene.json") << text;
    return validate_json(dir / "scene.json")["warnings"];
  };
  // Gauge 0.35 m from the specimen (position 1.65 m): 0.7 m round trip > 0.6 m pulse.
  CHECK(warnings(scene("1.65 m", "1 ms")).empty());
  // Gauge 0.25 m from the specimen: 0.5 m round trip < 0.6 m pulse.
  const json overlap = warnings(scene("1.75 m", "1 ms"));
  REQUIRE(overlap.size() == 1);
  CHECK(overlap[0].get<std::string>().find("gauge g1: incident and reflected pulses overlap") == 0);
  // The transmitted pulse passes g2 at about (2 + 0.005 + 1) m / c0 + 119 us = 714 us.
  const json short_run = warnings(scene("1 m", "600 us"));
  REQUIRE(short_run.size() == 1);
  CHECK(short_run[0].get<std::string>().find("duration 600.0 us ends before") == 0);
  fs::remove_all(dir);
}

TEST_CASE(
    "validate reports the links simulate uses: the rigid-link limit, or finite links that "
    "keep every bar's own time step",
    "[app][validate][finite]") {
  const auto classic = fs::path(SHPB_SOURCE_DIR) / "experiments/classic-al6061/scene.json";
  // No penalty value given: the rigid-link limit, which ignores them.
  const json rigid = validate_json(classic);  // kept: a range over a temporary's member dangles
  for (const auto& i : rigid["interfaces"]) CHECK(i["links"] == "rigid-link limit");
  // Finite links: bipenalty with R = ε_s/ε_m ≤ R_crit = (2 c0/h)² leaves the bar's critical step
  // unchanged for any ε_s (docs/methods.md §2): each link must respect its bar's.
  const auto dir = shpb_test::scratch_dir("validate_finite");
  json scene = json::parse(std::ifstream(classic));
  scene["contact"] = {
      {"method", "localized-bipenalty"}, {"stiffness_factor", 1e4}, {"mass_ratio", 0.9}};
  scene["bars"][2]["material"] =
      (classic.parent_path() / "../../specimens/al6061-t6.json").string();
  std::ofstream(dir / "scene.json") << scene.dump();
  const json v = validate_json(dir / "scene.json");
  for (std::size_t k = 0; k < v["interfaces"].size(); ++k) {
    const auto& links = v["interfaces"][k]["links"];
    INFO(v["interfaces"][k]["left"] << " | " << v["interfaces"][k]["right"]);
    REQUIRE(links["stiffness_N_m"].size() == 2);
    for (std::size_t side = 0; side < 2; ++side) {
      const auto& bar = v["bars"][k + side];
      const double r_crit = std::pow(
          2 * bar["wave_speed_m_s"].get<double>() / bar["element_length_m"].get<double>(), 2);
      const double r =
          links["stiffness_N_m"][side].get<double>() / links["mass_penalty_kg"][side].get<double>();
      CHECK(r > 0);
      CHECK(r <= r_crit * (1 + kRoundOff));
    }
  }
  fs::remove_all(dir);
}

TEST_CASE("validate reports a penalty stiffness given per interface as is", "[app][validate]") {
  const auto dir = shpb_test::scratch_dir("validate_stiffness");
  std::ofstream(dir / "scene.json") << R"({"bars": [
      {"name": "s", "material": "steel", "length": 0.3, "diameter": 0.02, "velocity": 10},
      {"name": "b", "material": "steel", "length": 1.5, "diameter": 0.02}],
    "materials": {"steel": {"model": "elastic", "density": 7850, "youngs_modulus": 2e11,
                            "poisson_ratio": 0.29}},
    "contact": {"method": "penalty",
                "interfaces": [{"between": ["s", "b"], "stiffness": "3e9 N/m"}]}})";
  const json v = validate_json(dir / "scene.json");
  CHECK(v["interfaces"][0]["method"] == "penalty");
  CHECK(v["interfaces"][0]["links"]["stiffness_N_m"][0].get<double>() == 3e9);
  CHECK_FALSE(v["interfaces"][0]["links"].contains("mass_penalty_kg"));  // no mass penalty
  fs::remove_all(dir);
}

TEST_CASE(
    "The CLI options --contact and --stepping take every name of their enum's table, bonded "
    "excepted",
    "[app][validate][cli]") {
  // One spelling (core/enum_names.hpp): a method or stepping added to a table is an option value
  // at once. `bonded` glues two faces; on every interface it would glue the striker too.
  const std::string scene =
      (fs::path(SHPB_SOURCE_DIR) / "experiments/striker-on-bar/scene.json").string();
  for (const auto& [name, method] : kContactMethodNames) {
    INFO("--contact " << name);
    const auto r = shpb_test::run_shpb({"validate", scene, "--contact", std::string(name)});
    CHECK(r.code == (method == ContactMethod::kBonded ? 2 : 0));
  }
  for (const auto& entry : kSteppingNames) {
    INFO("--stepping " << entry.first);
    CHECK(shpb_test::run_shpb({"validate", scene, "--stepping", std::string(entry.first)}).code ==
          0);
  }
}

TEST_CASE("validate checks a scene that only processes: what process will read and use",
          "[app][validate][process]") {
  // The simulated tension test without its specimen's material: process runs on it, simulate
  // cannot.
  const fs::path source = fs::path(SHPB_SOURCE_DIR) / "experiments/tension-bonded";
  const auto d = shpb_test::scratch_dir("validate_process_only");
  json scene = json::parse(shpb_test::read_text(source / "scene.json"));
  scene["bars"][2].erase("material");
  scene["measurement"]["file"] = (source / "data/gauges.csv").string();
  std::ofstream(d / "scene.json") << scene.dump(2);
  const json v = validate_json(d / "scene.json");
  CHECK(v["simulation"].get<std::string>().find("no material") != std::string::npos);
  const json& p = v["process"];
  // The shipped record: 900 us at 10 MHz, the first sample at 0.
  CHECK(p["samples"] == 9001);
  CHECK(p["sample_interval_s"].get<double>() == Approx(1e-7).epsilon(kRoundOff));
  CHECK(p["record_s"][1].get<double>() == Approx(900e-6).epsilon(kRoundOff));
  CHECK(p["test"] == "tension");
  REQUIRE(p["channels"].size() == 2);
  CHECK(p["channels"][1]["column"] == "transmitted");
  CHECK(p["channels"][1]["strain_per_unit"].get<double>() == 1.0);
  CHECK(p["incident_gauge"]["distance_to_specimen_m"].get<double>() == Approx(1.0));
  CHECK(p["transmitted_gauge"]["distance_to_specimen_m"].get<double>() == Approx(0.5));
  // Steel bars, c0 = sqrt(200 GPa / 8000 kg/m3) = 5000 m/s: the reflected pulse is back at the
  // incident gauge 2 x 1 m / c0 = 400 us after the incident pulse passed it.
  CHECK(p["timing"]["reflected_after_incident_s"].get<double>() ==
        Approx(400e-6).epsilon(kRoundOff));
  CHECK(p["windows"]["incident"] == "detected");
  // The table says the same.
  auto r = shpb_test::run_shpb({"validate", (d / "scene.json").string()});
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("simulation   not possible") != std::string::npos);
  CHECK(r.out.find("reflected 400 us after the incident") != std::string::npos);
  // A column the file does not have is found by validate, as process would find it.
  scene["measurement"]["channels"][1]["column"] = "transmited";
  std::ofstream(d / "scene.json") << scene.dump(2);
  r = shpb_test::run_shpb({"validate", (d / "scene.json").string()});
  CHECK(r.code == 2);
  CHECK(r.err.find("column \"transmited\": no such column") != std::string::npos);
}

TEST_CASE("validate's text table ends no line in a blank", "[app][validate]") {
  // A table is read in a terminal, pasted into a lab book and diffed against the last shot's:
  // padding after a line's last column is invisible there and makes every diff noisy.
  for (const auto& dir : fs::directory_iterator(fs::path(SHPB_SOURCE_DIR) / "experiments")) {
    const fs::path scene = dir.path() / "scene.json";
    if (!fs::exists(scene)) continue;
    const auto r = shpb_test::run_shpb({"validate", scene.string()});
    INFO(scene << "\n" << r.out);
    REQUIRE(r.code == 0);
    std::istringstream lines(r.out);
    std::string line;
    while (std::getline(lines, line)) CHECK((line.empty() || line.back() != ' '));
  }
}

}  // namespace tests_app_test_validate
