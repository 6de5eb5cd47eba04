// `--tolerance` / `simulation.tolerance` (docs/scene-format.md, docs/methods.md §1.1 "Gauge error
// model"): the meshes the error model chooses for a 1 % gauge error give, measured against the
// study's reference (study/reference.hpp) as recorded (study/recorded_error.hpp), at most 1 %, and
// the prediction written to summary.json is within a factor 2 of that measurement; bad values exit
// 2 with one line.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "model/scene.hpp"
#include "polymer_bars.hpp"
#include "run_shpb.hpp"
#include "solver/simulation.hpp"
#include "study/recorded_error.hpp"
#include "study/reference.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_app_test_tolerance {

namespace fs = std::filesystem;
using shpb_test::read_text;
using shpb_test::run_shpb;
using shpb_test::scratch_dir;

namespace {

const fs::path kExperiments = fs::path(SHPB_SOURCE_DIR) / "experiments";

// The tolerance asked for, and how far the model's prediction may be from the measured error: a
// factor 2 is the accuracy the mesh choice needs (the error falls at order 1–2 with the element
// size, so a factor 2 in error is a factor 1.4–2 in elements, well inside the cost it saves).
constexpr double kTolerance = 0.01;
constexpr double kPredictionFactor = 2;

// gauges.csv as written by simulate (time_s and one column per gauge).
shpb::TimeSeries read_gauges(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  shpb::TimeSeries ts;
  std::stringstream header(line);
  std::string name;
  std::getline(header, name, ',');  // time_s
  while (std::getline(header, name, ',')) ts.columns.push_back(name);
  ts.values.resize(ts.columns.size());
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::string cell;
    std::getline(row, cell, ',');
    ts.time_s.push_back(std::stod(cell));
    for (auto& column : ts.values) {
      std::getline(row, cell, ',');
      column.push_back(std::stod(cell));
    }
  }
  return ts;
}

// `by_default`: the run without --tolerance, which is to meet the default tolerance.
void check_tolerance_met(const std::string& experiment, fs::path scene_file = {},
                         bool by_default = false) {
  if (scene_file.empty()) scene_file = kExperiments / experiment / "scene.json";
  const fs::path dir = scratch_dir("tolerance_" + experiment) / "out";
  std::vector<std::string> args = {"simulate", scene_file.string(), "-o", dir.string(), "--quiet"};
  if (!by_default) args.insert(args.end(), {"--tolerance", "1 %"});
  const auto r = run_shpb(args);
  REQUIRE(r.code == 0);
  const double tolerance = by_default ? shpb::kDefaultTolerance : kTolerance;
  const auto summary = nlohmann::json::parse(read_text(dir / "summary.json"));
  REQUIRE(summary.contains("predicted_gauge_error"));
  CHECK(summary["tolerance"].get<double>() == Approx(tolerance));
  const double predicted = summary["predicted_gauge_error"].get<double>();

  // The study's reference of the scene as written (its automatic meshes refined 8 x).
  shpb::SimulationOptions options;
  options.record_field = false;
  const shpb::Scene scene = shpb::read_scene(scene_file);
  const auto exact = shpb::exact_reference(scene);
  const shpb::GaugeReference reference =
      exact ? *exact : shpb::fine_mesh_reference(scene, shpb::kReferenceResolution, options);
  // A run with a tolerance records its gauges through the record's Gaussian already.
  const double measured =
      shpb::recorded_gauge_error(read_gauges(dir / "gauges.csv"), reference, /*filtered=*/true);
  INFO(experiment << ": measured " << 100 * measured << " %, predicted " << 100 * predicted
                  << " %");
  CHECK(measured <= tolerance);
  CHECK(predicted <= kPredictionFactor * measured);
  CHECK(measured <= kPredictionFactor * predicted);
  fs::remove_all(dir.parent_path());
}

}  // namespace

TEST_CASE("A tolerance of 1 % meets 1 % on the classic experiment, as predicted",
          "[release-only][tolerance]") {
  check_tolerance_met("classic-al6061");
}

TEST_CASE("A tolerance of 1 % meets 1 % on the LANL copper experiment, as predicted",
          "[release-only][tolerance]") {
  check_tolerance_met("lanl-cu-ofe-273k");
}

TEST_CASE("A tolerance of 1 % meets 1 % on the striker-on-bar's exact solution, as predicted",
          "[tolerance]") {
  check_tolerance_met("striker-on-bar");
}

TEST_CASE("A tolerance of 1 % meets 1 % on the bonded tension test, as predicted",
          "[release-only][tolerance]") {
  // The experiment pins the Courant number (its shipped record is that mesh's run); the tolerance
  // model is checked where it chooses the Courant number too, as on the other experiments.
  nlohmann::json scene =
      nlohmann::json::parse(read_text(kExperiments / "tension-bonded/scene.json"));
  scene["simulation"].erase("courant");
  scene.erase("measurement");
  const fs::path copy = scratch_dir("tolerance_tension_scene") / "scene.json";
  std::ofstream(copy) << scene.dump(1);
  check_tolerance_met("tension-bonded", copy);
}

TEST_CASE("A tolerance of 1 % meets 1 % on the LANL PMMA mini-Kolsky test, as predicted",
          "[release-only][tolerance]") {
  // Its 10 us pulse is 100 samples: point samples would alias its fronts (a floor of about
  // 0.85 %, docs/methods.md §1.1); a run with a tolerance records through the anti-alias filter.
  check_tolerance_met("lanl-pmma13-mini-kolsky");
}

TEST_CASE("A tolerance of 1 % meets 1 % on the pulse shaper, as predicted",
          "[release-only][tolerance]") {
  // Its disc's plastic front is first order in the disc's element, as the specimen's, and its ties
  // converge with the mesh through the end segments (docs/methods.md §1.1, §3.6).
  check_tolerance_met("pulse-shaper");
}

// The classic experiment edited (scene.json's keys), in a scratch folder, its specimen's law
// named by its full path.
fs::path classic_variant(const std::string& name,
                         const std::function<void(nlohmann::json&)>& edit) {
  nlohmann::json scene =
      nlohmann::json::parse(read_text(kExperiments / "classic-al6061/scene.json"));
  scene["bars"][2]["material"] = (kExperiments.parent_path() / "specimens/al6061-t6.json").string();
  edit(scene);
  const fs::path copy = scratch_dir("tolerance_scene_" + name) / "scene.json";
  std::ofstream(copy) << scene.dump(1);
  return copy;
}

TEST_CASE("The default run meets the default tolerance on a record that holds later passes",
          "[release-only][tolerance]") {
  // A lab records past the pulses: the classic set-up for 2 ms holds the reflected pulse again off
  // the struck end and the transmitted one off the far end, twice each; main measured 3.9 % for a
  // predicted 2.3 %. On 0.5 m bars under the 0.3 m striker (a 120 µs pulse, a 100 µs round trip to
  // the specimen) its default record holds them too: 4.4 % for 2.3 %. Both at C ≈ 1, where the
  // model has no term for what the specimen's faces do to a front (docs/methods.md §1.1).
  const fs::path long_record = classic_variant(
      "long-record", [](nlohmann::json& s) { s["simulation"]["duration"] = "2 ms"; });
  check_tolerance_met("classic-long-record", long_record, true);
  const fs::path short_bars = classic_variant("short-bars", [](nlohmann::json& s) {
    for (int b : {1, 3}) {
      s["bars"][b]["length"] = "0.5 m";
      s["bars"][b]["gauges"][0]["position"] = "0.25 m";
    }
    s["simulation"].erase("duration");
  });
  check_tolerance_met("classic-short-bars", short_bars, true);
}

TEST_CASE(
    "The default run meets the default tolerance where the reflected pulse overlaps the incident "
    "one at its gauge",
    "[release-only][tolerance]") {
  // Gauges 0.1 m from the specimen under the 0.3 m striker: the pulses overlap for two thirds of
  // the pulse and, of opposite sign, cancel there; main measured 3.9 % for a predicted 2.3 %
  // (docs/methods.md §1.1, "Overlapping pulses").
  const fs::path near = classic_variant("gauges-near", [](nlohmann::json& s) {
    s["bars"][1]["gauges"][0]["position"] = "1.9 m";
    s["bars"][3]["gauges"][0]["position"] = "0.1 m";
  });
  check_tolerance_met("classic-gauges-near", near, true);
}

TEST_CASE("Bad tolerances exit 2 with one line naming the option or the JSON path", "[tolerance]") {
  const std::string scene = (kExperiments / "classic-al6061" / "scene.json").string();
  for (const std::string bad : {"0", "-1 %", "abc", "200 %", "100 %", "1 mm"}) {
    for (const std::string command : {"validate", "simulate"}) {
      const fs::path dir = scratch_dir("tolerance_bad") / "out";
      std::vector<std::string> args = {command, scene, "--tolerance", bad, "--quiet"};
      if (command == "simulate") args.insert(args.end(), {"-o", dir.string()});
      const auto r = run_shpb(args);
      INFO(command << " --tolerance " << bad << ": " << r.err);
      CHECK(r.code == 2);
      CHECK(r.err.rfind("error: --tolerance: ", 0) == 0);
      CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
      CHECK_FALSE(fs::exists(dir));
    }
  }
  // In the scene: the same rule, named by its JSON path (a self-contained scene, copied).
  const fs::path dir = scratch_dir("tolerance_bad_scene");
  const std::string original = read_text(kExperiments / "striker-on-bar" / "scene.json");
  for (const std::string bad : {"0", "\"-1 %\"", "\"abc\"", "\"200 %\""}) {
    std::string text = original;
    const std::string key = "\"simulation\": {";
    REQUIRE(text.find(key) != std::string::npos);
    text.replace(text.find(key), key.size(), key + " \"tolerance\": " + bad + ",");
    const fs::path file = dir / "scene.json";
    std::ofstream(file) << text;
    const auto r = run_shpb({"validate", file.string()});
    INFO(bad << ": " << r.err);
    CHECK(r.code == 2);
    CHECK(r.err.find("simulation.tolerance") != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
  fs::remove_all(dir);
}

TEST_CASE("A tolerance no affordable mesh meets, or a scene without a striker, is refused",
          "[tolerance]") {
  // 0.001 % on the classic experiment: below the record's aliasing of the striker's fronts (a point
  // sample every 0.1 us misses where a front falls within it by up to half a sample, about 0.5 % of
  // a 120 us pulse); the epoxy scene gives no striker velocity.
  const auto r = run_shpb({"validate", (kExperiments / "classic-al6061" / "scene.json").string(),
                           "--tolerance", "0.001 %"});
  CHECK(r.code == 2);
  CHECK(r.err.rfind("error: --tolerance: 0.001 %: not reachable", 0) == 0);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  // The value as the user wrote it: 3.5 % is 0.035 × 100 = 3.5000000000000004 in a double.
  const auto e =
      run_shpb({"validate", (kExperiments / "epoxy-resin-sample01" / "scene.json").string(),
                "--tolerance", "3.5 %"});
  CHECK(e.code == 2);
  CHECK(e.err.rfind("error: --tolerance: 3.5 %: needs a striker", 0) == 0);
  CHECK(std::count(e.err.begin(), e.err.end(), '\n') == 1);
  // A chain struck from the right: a bar moves, but none loads the bar on its right, which is
  // what a striker is (docs/scene-format.md, Roles); the refusal says so, not "a bar with a
  // velocity" of a scene that has one.
  const fs::path dir = scratch_dir("tolerance_struck_from_right");
  nlohmann::json scene =
      nlohmann::json::parse(read_text(kExperiments / "striker-on-bar" / "scene.json"));
  std::swap(scene["bars"][0], scene["bars"][1]);
  scene["bars"][1]["velocity"] = "-10 m/s";
  std::ofstream(dir / "scene.json") << scene.dump();
  const auto right = run_shpb({"validate", (dir / "scene.json").string(), "--tolerance", "1 %"});
  INFO(right.err);
  CHECK(right.code == 2);
  CHECK(right.err.find("needs a striker (a moving bar that loads the bar on its right") !=
        std::string::npos);
  CHECK(std::count(right.err.begin(), right.err.end(), '\n') == 1);
  // A gauge on the striker only: the model predicts the gauges right of the striker, none here
  // (it said 0 % and meshed at its coarsest, 60 mm elements).
  scene = nlohmann::json::parse(read_text(kExperiments / "striker-on-bar" / "scene.json"));
  scene["bars"][0]["gauges"] = scene["bars"][1]["gauges"];
  scene["bars"][0]["gauges"][0]["position"] = "0.15 m";
  scene["bars"][1].erase("gauges");
  std::ofstream(dir / "scene.json") << scene.dump();
  const auto g = run_shpb({"validate", (dir / "scene.json").string(), "--tolerance", "1 %"});
  INFO(g.err);
  CHECK(g.code == 2);
  CHECK(g.err.rfind("error: --tolerance: 1 %: needs a gauge on a bar right of the striker", 0) ==
        0);
  CHECK(std::count(g.err.begin(), g.err.end(), '\n') == 1);
  // Polymer bars: the model, calibrated on elastic bars, does not predict their attenuation, and
  // meshed a 2 m PMMA bar with 98 802 elements for 3 % (simulate --tolerance 0.5 % had not ended
  // after an hour). Refused at once, naming the bar, as the default run withholds its tolerance.
  std::ofstream(dir / "scene.json") << shpb_test::polymer_bar_scene().dump();
  const auto p = run_shpb({"simulate", (dir / "scene.json").string(), "--tolerance", "0.5 %", "-o",
                           (dir / "out").string()});
  INFO(p.err);
  CHECK(p.code == 2);
  CHECK(p.err.rfind("error: --tolerance: 0.5 %: bar \"striker\" has a material law besides the "
                    "specimen's: a polymer bar",
                    0) == 0);
  CHECK(std::count(p.err.begin(), p.err.end(), '\n') == 1);
  CHECK_FALSE(fs::exists(dir / "out"));
  fs::remove_all(dir);
}

TEST_CASE("validate prints the meshes chosen for a tolerance and their predicted error",
          "[tolerance]") {
  const std::string scene = (kExperiments / "classic-al6061" / "scene.json").string();
  const auto plain = run_shpb({"validate", scene, "--json"});
  REQUIRE(plain.code == 0);
  // Without one, the default the README states (3.5 %), said to be the default.
  constexpr double kStatedDefault = 0.035;
  const auto by_default = nlohmann::json::parse(plain.out);
  CHECK(by_default["tolerance"].get<double>() == Approx(kStatedDefault));
  CHECK(by_default["tolerance_is_default"].get<bool>());
  CHECK(by_default["predicted_gauge_error"].get<double>() <= kStatedDefault);
  const auto r = run_shpb({"validate", scene, "--json", "--tolerance", "1%"});
  REQUIRE(r.code == 0);
  const auto setup = nlohmann::json::parse(r.out);
  CHECK_FALSE(setup["tolerance_is_default"].get<bool>());
  CHECK(setup["predicted_gauge_error"].get<double>() <= kTolerance);
  CHECK(setup["cost_against_automatic"].get<double>() > 0);
  const auto table = run_shpb({"validate", scene, "--tolerance", "1%"});
  CHECK(table.out.find("predicted gauge error") != std::string::npos);
}

TEST_CASE("A soft striker link leaves every bar a few elements over the loading pulse",
          "[tolerance]") {
  // A rise time of 1 s: the model then weighs the fronts by nothing, and counts the pulse as
  // resolved at any mesh. The floor docs/methods.md §1.1 states: whatever the tolerance, every
  // bar carries the loading pulse (2 L_s/c0, the shortest wave the striker sends) over at least
  // ten elements, a plateau between its two fronts.
  constexpr double kElementsOverPulse = 10;
  auto scene = nlohmann::json::parse(read_text(kExperiments / "striker-on-bar" / "scene.json"));
  scene["contact"]["rise_time"] = "1 s";
  const fs::path file = scratch_dir("tolerance_soft_link") / "scene.json";
  std::ofstream(file) << scene.dump();
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{}, std::vector<std::string>{"--tolerance", "10%"}}) {
    std::vector<std::string> args = {"validate", file.string(), "--json"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = run_shpb(args);
    REQUIRE(r.code == 0);
    const auto setup = nlohmann::json::parse(r.out);
    const auto& bars = setup["bars"];
    const double pulse_s =
        2 * bars[0]["length_m"].get<double>() / bars[0]["wave_speed_m_s"].get<double>();
    for (const auto& b : bars) {
      INFO(b["name"].get<std::string>() << " " << (extra.empty() ? "default" : "10 %"));
      CHECK(b["elements"].get<int>() > 1);
      const double transit_s =
          b["element_length_m"].get<double>() / b["wave_speed_m_s"].get<double>();
      CHECK(pulse_s / transit_s >= kElementsOverPulse * (1 - 1e-9));
    }
  }
}

TEST_CASE(
    "A run repeated at global steps on meshes chosen for asynchronous ones says it misses "
    "the tolerance",
    "[release-only][tolerance]") {
  // An outside set-up of the survey against exact solutions (docs/validation.md "Elastic chains
  // against their exact solution"): a tungsten-carbide striker through a 1 mm brass disc on steel
  // bars, a tungsten-carbide specimen. The asynchronous run fails at the stiff elastic specimen's
  // faces and is repeated at global steps on the meshes chosen for asynchronous ones, where every
  // bar steps at the disc's step, far below its Courant number 1: it misses the default tolerance,
  // and says so; `--stepping global` meshes for global steps and meets it.
  const nlohmann::json scene = nlohmann::json::parse(R"({
    "bars": [
      { "name": "striker", "material": "wc", "length": "240 mm", "diameter": "16 mm", "velocity": "20 m/s" },
      { "name": "shaper", "material": "brass", "length": "1 mm", "diameter": "12.8 mm" },
      { "name": "incident", "material": "steel", "length": "0.8 m", "diameter": "16 mm",
        "gauges": [ { "name": "incident", "position": "0.4 m" } ] },
      { "name": "specimen", "material": "wc", "length": "10 mm", "diameter": "11.2 mm" },
      { "name": "transmitter", "material": "steel", "length": "1 m", "diameter": "16 mm",
        "gauges": [ { "name": "transmitted", "position": "0.1 m" } ] }
    ],
    "materials": {
      "wc": { "model": "elastic", "density": 15000, "youngs_modulus": "600 GPa", "poisson_ratio": 0.22 },
      "brass": { "model": "elastic", "density": 8500, "youngs_modulus": "105 GPa", "poisson_ratio": 0.34 },
      "steel": { "model": "elastic", "density": 7850, "youngs_modulus": "200 GPa", "poisson_ratio": 0.29 }
    },
    "simulation": { "duration": "1189 us", "sample_rate": "10 MHz" },
    "specimen": "specimen"
  })");
  const fs::path dir = scratch_dir("tolerance_global_repeat");
  std::ofstream(dir / "scene.json") << scene.dump(1);
  shpb::SimulationOptions options;
  options.record_field = false;
  const shpb::Scene read = shpb::read_scene(dir / "scene.json");
  const auto exact = shpb::exact_reference(read);
  const shpb::GaugeReference reference =
      exact ? *exact : shpb::fine_mesh_reference(read, shpb::kReferenceResolution, options);
  auto measured = [&](const std::string& out, std::vector<std::string> extra) {
    std::vector<std::string> args = {"simulate", (dir / "scene.json").string(), "-o",
                                     (dir / out).string(), "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = run_shpb(args);
    INFO(r.err);
    REQUIRE(r.code == 0);
    return std::pair{r.err, shpb::recorded_gauge_error(read_gauges(dir / out / "gauges.csv"),
                                                       reference, /*filtered=*/true)};
  };
  const auto [said, repeated] = measured("default", {});
  const auto [said_global, global] = measured("global", {"--stepping", "global"});
  CHECK(said.find("the run was repeated at global steps") != std::string::npos);
  CHECK(said.find("beyond the 3.5 % asked (--stepping global chooses meshes for global steps)") !=
        std::string::npos);
  WARN("repeated at global steps: " << 100 * repeated << " %; --stepping global: " << 100 * global
                                    << " %");
  CHECK(repeated > shpb::kDefaultTolerance);  // the warning is warranted
  CHECK(global <= shpb::kDefaultTolerance);   // and its advice meets the tolerance
  CHECK(said_global.find("beyond the") == std::string::npos);
}

}  // namespace tests_app_test_tolerance
