// Bad scenes as behaviour of the real executable (docs/commands.md): exit code 2, one line
// "error: <file>: <json path>: <value>: <constraint>" on stderr, and nothing written — neither the
// output folder nor anything beside it — by every command that takes a scene.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "run_shpb.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_app_test_bad_scenes {

using nlohmann::json;
using shpb_test::run_shpb;
namespace fs = std::filesystem;

namespace {

// A valid four-bar set-up with a measurement; every case breaks one thing in it.
json base_scene() {
  return json::parse(R"({
    "name": "base",
    "bars": [
      {"name": "striker", "material": "steel", "length": "300 mm", "diameter": "19.05 mm",
       "velocity": "15 m/s"},
      {"name": "incident", "material": "steel", "length": "2 m", "diameter": "19.05 mm",
       "gauges": [{"name": "incident", "position": "1 m"}]},
      {"name": "specimen", "material": "specimen.json", "length": "5 mm", "diameter": "10 mm"},
      {"name": "transmitter", "material": "steel", "length": "2 m", "diameter": "19.05 mm",
       "gauges": [{"name": "transmitted", "position": "1 m"}]}
    ],
    "specimen": "specimen",
    "materials": {"steel": {"model": "elastic", "density": 8080, "youngs_modulus": "200 GPa",
                            "poisson_ratio": 0.29}},
    "contact": {"method": "localized-bipenalty"},
    "simulation": {"duration": "800 us", "sample_rate": "10 MHz"},
    "measurement": {"file": "signals.csv", "format": "csv",
                    "time": {"column": "time_s", "unit": "s"},
                    "channels": [{"gauge": "incident", "column": 1, "unit": "V",
                                  "bridge": {"arms": 2, "gauge_factor": 2.1,
                                             "excitation": "10 V", "gain": 100}},
                                 {"gauge": "transmitted", "column": "ch2", "unit": "strain"}]}
  })");
}

json base_specimen() {
  return json::parse(R"js({"model": "johnson-cook", "source": "Johnson & Cook 1985",
    "density": 2703, "youngs_modulus": "69 GPa", "poisson_ratio": 0.33, "A": "324 MPa",
    "B": "114 MPa", "n": 0.42, "C": 0.002, "m": 1.34, "melting_temperature": "925 K",
    "specific_heat": "885 J/(kg K)"})js");
}

struct BadScene {
  std::string what;
  std::function<void(json& scene, json& specimen)> breaks;  // edits the valid pair
  std::string where;           // the JSON path (or place) the message must name
  std::string raw_scene = {};  // when set, the scene file holds this text instead
  std::string raw_specimen = {};
};

const std::vector<BadScene>& cases() {
  static const std::vector<BadScene> table = {
      {"a negative length", [](json& s, json&) { s["bars"][1]["length"] = "-5 mm"; },
       "bars[1].length: -0.005 m: must be > 0"},
      {"a zero length", [](json& s, json&) { s["bars"][0]["length"] = 0; }, "bars[0].length"},
      {"a negative diameter", [](json& s, json&) { s["bars"][2]["diameter"] = "-10 mm"; },
       "bars[2].diameter"},
      {"a zero area",
       [](json& s, json&) {
         s["bars"][3].erase("diameter");
         s["bars"][3]["area"] = "0 mm2";
       },
       "bars[3].area"},
      {"both diameter and area", [](json& s, json&) { s["bars"][1]["area"] = "285 mm2"; },
       "bars[1].area"},
      {"no diameter or area", [](json& s, json&) { s["bars"][1].erase("diameter"); },
       "bars[1].diameter"},
      {"a negative density", [](json& s, json&) { s["materials"]["steel"]["density"] = -8080; },
       "materials.steel.density"},
      {"a zero Young's modulus",
       [](json& s, json&) { s["materials"]["steel"]["youngs_modulus"] = "0 GPa"; },
       "materials.steel.youngs_modulus"},
      {"a Poisson ratio of 0.5",
       [](json& s, json&) { s["materials"]["steel"]["poisson_ratio"] = 0.5; },
       "materials.steel.poisson_ratio"},
      {"a Poisson ratio of -1",
       [](json& s, json&) { s["materials"]["steel"]["poisson_ratio"] = -1; },
       "materials.steel.poisson_ratio"},
      {"a gauge beyond its bar's end",
       [](json& s, json&) { s["bars"][1]["gauges"][0]["position"] = "2.5 m"; },
       "bars[1].gauges[0].position"},
      {"a gauge before its bar's start",
       [](json& s, json&) { s["bars"][3]["gauges"][0]["position"] = "-1 mm"; },
       "bars[3].gauges[0].position"},
      {"two bars of one name", [](json& s, json&) { s["bars"][3]["name"] = "incident"; },
       "bars[3].name"},
      {"two gauges of one name",
       [](json& s, json&) { s["bars"][3]["gauges"][0]["name"] = "incident"; },
       "bars[3].gauges[0].name"},
      {"a gauge named like the time column",
       [](json& s, json&) { s["bars"][1]["gauges"][0]["name"] = "time_s"; },
       "bars[1].gauges[0].name"},
      {"a bar name with a comma", [](json& s, json&) { s["bars"][0]["name"] = "strik,er"; },
       "bars[0].name"},
      {"a misspelt bar key",
       [](json& s, json&) {
         s["bars"][1]["lenght"] = s["bars"][1]["length"];
         s["bars"][1].erase("length");
       },
       "bars[1].lenght: unknown key: did you mean \"length\"?"},
      {"a misspelt top-level key",
       [](json& s, json&) {
         s["simulaton"] = s["simulation"];
         s.erase("simulation");
       },
       "simulaton: unknown key: did you mean \"simulation\"?"},
      // A key of another object of the scene is refused naming where it belongs (before, the
      // keys of the object it was found in were listed).
      {"a contact key misspelt at the top level", [](json& s, json&) { s["frition"] = 0.1; },
       "frition: unknown key: did you mean \"friction\", a key of contact, contact.interfaces[], "
       "measurement.corrections or measurement.uncertainty?"},
      {"a simulation key in contact", [](json& s, json&) { s["contact"]["duration"] = "1 ms"; },
       "contact.duration: unknown key: not here; \"duration\" is a key of simulation"},
      {"a length in kilograms", [](json& s, json&) { s["bars"][1]["length"] = "2 kg"; },
       "bars[1].length: \"2 kg\": \"kg\" is a mass"},
      {"a density in gigapascals",
       [](json& s, json&) { s["materials"]["steel"]["density"] = "8 GPa"; },
       "materials.steel.density"},
      {"a velocity in metres", [](json& s, json&) { s["bars"][0]["velocity"] = "15 m"; },
       "bars[0].velocity"},
      {"a length that is not a number", [](json& s, json&) { s["bars"][1]["length"] = true; },
       "bars[1].length"},
      {"a specimen naming no bar", [](json& s, json&) { s["specimen"] = "sample"; }, "specimen"},
      {"a single bar", [](json& s, json&) { s["bars"] = json::array({s["bars"][0]}); }, "bars"},
      {"no bars at all", [](json& s, json&) { s["bars"] = json::array(); }, "bars"},
      {"no bars key", [](json& s, json&) { s.erase("bars"); }, "bars: (missing)"},
      {"a NaN given as text", [](json& s, json&) { s["bars"][0]["velocity"] = "nan m/s"; },
       "bars[0].velocity"},
      {"an infinite number", nullptr, "bars[0].velocity: number overflow",
       R"({"bars": [{"name": "s", "velocity": 1e999}]})"},
      {"a NaN literal (not JSON)", nullptr, "line 1, column",
       R"({"bars": [{"name": "s", "velocity": NaN}]})"},
      {"an empty file", nullptr, "empty file", "\n  \n"},
      {"text that is not JSON", nullptr, "line 2, column", "{\"bars\": [\n}"},
      {"a top level that is not an object", nullptr, "(top level)", "[1, 2, 3]"},
      {"bytes that are not UTF-8", nullptr, "line 1, column", "{\"name\": \"\xff\xfe\"}"},
      {"a byte-order mark and two documents", nullptr, "line 2, column 1",
       "\xef\xbb\xbf{\"bars\": []}\n{\"bars\": []}"},
      {"a duplicate key", nullptr, "bars[0].name: duplicate key",
       R"({"bars": [{"name": "a", "name": "b"}]})"},
      {"a missing material file",
       [](json& s, json&) { s["bars"][2]["material"] = "no-such-specimen.json"; },
       "bars[2].material"},
      {"a material naming nothing", [](json& s, json&) { s["bars"][1]["material"] = "stel"; },
       "bars[1].material: \"stel\": no such material in materials; did you mean \"steel\"?"},
      {"a material file that is not JSON", nullptr, "specimen.json: line 1, column", "",
       "{\"model\": \"johnson-cook\", }"},
      {"an unknown material model",
       [](json& s, json&) { s["materials"]["steel"]["model"] = "elastc"; },
       "materials.steel.model: \"elastc\": did you mean \"elastic\"?"},
      // A material file's key of another model is named there, as in a scene (before: the
      // keys of this model were listed).
      {"a key of another material model", [](json&, json& m) { m["yield_stress"] = "300 MPa"; },
       "specimen.json: yield_stress: unknown key: not here; \"yield_stress\" is a key of a "
       "bilinear material"},
      {"a Johnson-Cook n above 1", [](json&, json& m) { m["n"] = 1.5; }, "specimen.json: n: 1.5"},
      {"a negative Johnson-Cook B", [](json&, json& m) { m["B"] = "-1 MPa"; }, "specimen.json: B"},
      {"a zero Johnson-Cook m", [](json&, json& m) { m["m"] = 0; }, "specimen.json: m"},
      {"a melting point below room temperature",
       [](json&, json& m) { m["melting_temperature"] = "10 degC"; },
       "specimen.json: melting_temperature"},
      {"a Taylor-Quinney factor above 1", [](json&, json& m) { m["taylor_quinney"] = 1.2; },
       "specimen.json: taylor_quinney"},
      {"a zero specific heat", [](json&, json& m) { m["specific_heat"] = 0; },
       "specimen.json: specific_heat"},
      {"a missing Johnson-Cook constant", [](json&, json& m) { m.erase("A"); },
       "specimen.json: A: (missing)"},
      {"a bilinear tangent modulus above E",
       [](json& s, json&) {
         s["materials"]["steel"]["model"] = "bilinear";
         s["materials"]["steel"]["yield_stress"] = "1 GPa";
         s["materials"]["steel"]["tangent_modulus"] = "300 GPa";
       },
       "materials.steel.tangent_modulus"},
      {"a viscoelastic arm with zero relaxation time",
       [](json&, json& m) {
         m = {{"model", "viscoelastic"},
              {"density", 1190},
              {"poisson_ratio", 0.35},
              {"long_term_modulus", "2 GPa"},
              {"arms", {{{"modulus", "1 GPa"}, {"relaxation_time", 0}}}}};
       },
       "specimen.json: arms[0].relaxation_time"},
      {"nine viscoelastic arms",
       [](json&, json& m) {
         m = {{"model", "viscoelastic"},
              {"density", 1190},
              {"poisson_ratio", 0.35},
              {"long_term_modulus", "2 GPa"},
              {"arms", json::array()}};
         for (int k = 0; k < 9; ++k)
           m["arms"].push_back({{"modulus", "1 GPa"}, {"relaxation_time", "1 us"}});
       },
       "specimen.json: arms: 9 arms: at most 8"},
      {"an unknown contact method", [](json& s, json&) { s["contact"]["method"] = "bipenalti"; },
       "contact.method: \"bipenalti\": did you mean \"bipenalty\"?"},
      {"an interface between bars that do not touch",
       [](json& s, json&) {
         s["contact"]["interfaces"] = {{{"between", {"striker", "specimen"}}}};
       },
       "contact.interfaces[0].between"},
      {"a negative penalty stiffness",
       [](json& s, json&) { s["contact"]["stiffness"] = "-1e9 N/m"; }, "contact.stiffness"},
      {"a contact rise time in metres", [](json& s, json&) { s["contact"]["rise_time"] = "1 mm"; },
       "contact.rise_time: \"1 mm\""},
      {"a stiffness and a rise time for the same interface",
       [](json& s, json&) {
         s["contact"]["interfaces"] = {{{"between", {"striker", "incident"}},
                                        {"stiffness", "1e9 N/m"},
                                        {"rise_time", "1 us"}}};
       },
       "contact.interfaces[0].rise_time: \"1 us\": give one of stiffness_factor, stiffness and "
       "rise_time"},
      {"a Courant number above 1", [](json& s, json&) { s["simulation"]["courant"] = 1.5; },
       "simulation.courant: 1.5: must be in (0, 1]"},
      // Every bar's steps grow as 1/C: the run is beyond the budget because of the Courant
      // number, not of the 800 us duration the refusal of a costly run names otherwise.
      {"a Courant number of 1e-9", [](json& s, json&) { s["simulation"]["courant"] = 1e-9; },
       "simulation.courant: 1e-09: every bar's steps grow as 1/C"},
      // One bar stepping far finer than the others makes the run unaffordable at any duration:
      // the refusal names that bar's length (shorter than its fewest elements) or its material
      // (an absurd wave speed), not the 800 us duration.
      {"a striker of 1e-9 mm", [](json& s, json&) { s["bars"][0]["length"] = "1e-9 mm"; },
       "bars[0].length: 1e-12 m: bar \"striker\" steps every"},
      {"bars of density 1e-9 kg/m3",
       [](json& s, json&) { s["materials"]["steel"]["density"] = "1e-9 kg/m3"; },
       "bars[0].material: \"steel\": bar \"striker\" steps every"},
      {"a misspelt kinematics", [](json& s, json&) { s["simulation"]["kinematics"] = "smal"; },
       "simulation.kinematics: \"smal\": did you mean \"small\"?"},
      {"a friction coefficient of 1.5", [](json& s, json&) { s["contact"]["friction"] = 1.5; },
       "contact.friction: 1.5"},
      {"a negative interface friction",
       [](json& s, json&) {
         s["contact"]["interfaces"] = {{{"between", {"incident", "specimen"}}, {"friction", -0.1}}};
       },
       "contact.interfaces[0].friction: -0.1"},
      // Face friction is the Dharan–Hauser factor of sliding faces over the flowing specimen at
      // its current shape (docs/methods.md §8.2): a glued face does not slide, and small
      // kinematics keeps the specimen's original section. Both ran silently before.
      {"friction on a bonded specimen face",
       [](json& s, json&) {
         s["contact"]["interfaces"] = {
             {{"between", {"specimen", "transmitter"}}, {"method", "bonded"}, {"friction", 0.1}}};
       },
       "contact.interfaces[0].friction: 0.1: the face specimen|transmitter is bonded"},
      {"friction on every face of a bonded chain",
       [](json& s, json&) {
         s["contact"] = {{"method", "bonded"}, {"friction", 0.1}};
       },
       "contact.friction: 0.1: the face incident|specimen is bonded"},
      {"friction with small kinematics",
       [](json& s, json&) {
         s["contact"]["friction"] = 0.1;
         s["simulation"]["kinematics"] = "small";
       },
       "contact.friction: 0.1: face friction on incident|specimen follows the current diameter"},
      {"inertia on a bar that is not squeezed between two others",
       [](json& s, json& m) {
         s["bars"][0]["material"] = "specimen.json";
         s["bars"][0]["inertia"] = true;
         (void)m;
       },
       "bars[0].inertia: true: radial inertia is modelled for a bar squeezed between two others"},
      {"inertia on an elastic bar", [](json& s, json&) { s["bars"][1]["inertia"] = true; },
       "bars[1].inertia: true: radial inertia applies to a flowing specimen"},
      {"a correction friction of 2",
       [](json& s, json&) {
         s["measurement"]["corrections"] = {{"friction", 2}};
       },
       "measurement.corrections.friction: 2"},
      // The corrections widen the specimen between sliding faces; a tension specimen is glued
      // and narrows. `process` divided its curve by the compression φ silently before.
      {"a friction correction of a tension test",
       [](json& s, json&) {
         s["measurement"]["test"] = "tension";
         s["measurement"]["corrections"] = {{"friction", 0.1}};
       },
       "measurement.corrections.friction: 0.1: the friction and inertia corrections are those of "
       "a compression specimen"},
      {"an inertia correction of a tension test",
       [](json& s, json&) {
         s["measurement"]["test"] = "tension";
         s["measurement"]["corrections"] = {{"inertia", true}};
       },
       "measurement.corrections.inertia: true: the friction and inertia corrections"},
      {"a negative duration", [](json& s, json&) { s["simulation"]["duration"] = "-800 us"; },
       "simulation.duration"},
      {"a sample rate in seconds", [](json& s, json&) { s["simulation"]["sample_rate"] = "10 us"; },
       "simulation.sample_rate"},
      // 1 THz records 1e6 samples a microsecond, finer than any solver step: the record's size
      // is the sample rate's doing, not the 800 µs duration's.
      {"a sample rate of 1 THz", [](json& s, json&) { s["simulation"]["sample_rate"] = "1 THz"; },
       "simulation.sample_rate: 1e+12 Hz: the run would need about"},
      {"a misspelt stepping", [](json& s, json&) { s["simulation"]["stepping"] = "asynchronus"; },
       "simulation.stepping: \"asynchronus\": did you mean \"asynchronous\"?"},
      {"a fractional element count", [](json& s, json&) { s["bars"][1]["elements"] = 2.5; },
       "bars[1].elements"},
      {"a gap after the last bar", [](json& s, json&) { s["bars"][3]["gap"] = "1 mm"; },
       "bars[3].gap"},
      {"a channel naming no gauge",
       [](json& s, json&) { s["measurement"]["channels"][0]["gauge"] = "incidnet"; },
       "measurement.channels[0].gauge: \"incidnet\": no such gauge; did you mean \"incident\"?"},
      {"volts without a bridge",
       [](json& s, json&) { s["measurement"]["channels"][0].erase("bridge"); },
       "measurement.channels[0].bridge: (missing)"},
      {"a three-arm bridge",
       [](json& s, json&) { s["measurement"]["channels"][0]["bridge"]["arms"] = 3; },
       "measurement.channels[0].bridge.arms"},
      {"an unknown signal format", [](json& s, json&) { s["measurement"]["format"] = "tek"; },
       "measurement.format"},
      {"a pulse window ending before it starts",
       [](json& s, json&) {
         s["measurement"]["windows"]["incident"] = {"120 us", "20 us"};
       },
       "measurement.windows.incident"},
      {"a channel without any file", [](json& s, json&) { s["measurement"].erase("file"); },
       "measurement.channels[0].file: (missing)"},
      {"a length with a line break: the message stays one line",
       [](json& s, json&) { s["bars"][0]["length"] = "300 mm\nx"; },
       "bars[0].length: \"300 mm\\nx\": unexpected \"\\nx\""},
      {"an empty time unit (not seconds by default)",
       [](json& s, json&) { s["measurement"]["time"]["unit"] = ""; },
       "measurement.time.unit: \"\": expected a time unit"},
      // Keys accepted and then read by nothing gave a plausible number without a word: a
      // material's uncertainty (a fit's record), the keys of a record a measurement without
      // channels does not have, a bridge's uncertainty with no bridge.
      {"a standard uncertainty in a material's uncertainty",
       [](json& s, json&) {
         s["materials"]["steel"]["uncertainty"] = {{"youngs_modulus", "2 %"}};
       },
       "materials.steel.uncertainty.youngs_modulus: \"2 %\": expected {\"interval_95\""},
      {"a material's interval of a value that is no law parameter",
       [](json&, json& m) {
         m["uncertainty"] = {{"density", {{"interval_95", {2600, 2800}}}}};
       },
       "uncertainty.density: {\"interval_95\":[2600,2800]}: not a law parameter"},
      {"a striker velocity in a measurement without channels",
       [](json& s, json&) {
         s["measurement"] = {{"test", "compression"}, {"striker_velocity", "15 m/s"}};
       },
       "measurement.striker_velocity: \"15 m/s\": a key of the measured record"},
      {"a bridge excitation's uncertainty in a measurement without channels",
       [](json& s, json&) {
         s["measurement"] = {{"uncertainty", {{"excitation", "1 %"}}}};
       },
       "measurement.uncertainty.excitation: \"1 %\": a bridge's uncertainty needs"},
      // The plan block, which only `plan` uses, is read by every command with the rest of the
      // scene (before, simulate, process, compare, study and calibrate ran such a scene).
      {"a misspelt plan key",
       [](json& s, json&) {
         s["plan"] = {{"strikr", {{"velocity", {"5 m/s", "40 m/s"}}}}};
       },
       "plan.strikr: unknown key: did you mean \"striker\"?"},
      {"plan bounds out of order",
       [](json& s, json&) {
         s["plan"] = {{"striker", {{"velocity", {"40 m/s", "5 m/s"}}}}};
       },
       "plan.striker.velocity: [\"40 m/s\",\"5 m/s\"]: expected a range [lo, hi] with lo ≤ hi"},
      {"a plan shaper material not there",
       [](json& s, json&) {
         s["plan"] = {{"striker", {{"velocity", "10 m/s"}}}, {"shaper", {{"material", "brass"}}}};
       },
       "plan.shaper.material: \"brass\": neither a name from the scene's materials nor"},
      // A material listed twice was searched twice, without a word.
      {"a plan shaper material listed twice",
       [](json& s, json&) {
         s["plan"] = {{"striker", {{"velocity", "10 m/s"}}},
                      {"shaper", {{"material", {"steel", "steel"}}}}};
       },
       "plan.shaper.material[1]: \"steel\": listed twice: each shaper material once"},
  };
  return table;
}

std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

// Writes case `index` into its own folder and returns the scene file.
fs::path prepare(const fs::path& root, std::size_t index) {
  const auto& c = cases()[index];
  const auto dir = root / ("case" + std::to_string(index));
  fs::remove_all(dir);
  fs::create_directories(dir);
  json scene = base_scene(), specimen = base_specimen();
  if (c.breaks) c.breaks(scene, specimen);
  std::ofstream(dir / "scene.json") << (c.raw_scene.empty() ? scene.dump(2) : c.raw_scene);
  std::ofstream(dir / "specimen.json")
      << (c.raw_specimen.empty() ? specimen.dump(2) : c.raw_specimen);
  return dir / "scene.json";
}

// A command that writes an output folder must refuse a bad scene before creating anything.
void check_writes_nothing(const std::string& command) {
  const auto root = shpb_test::scratch_dir("bad_scenes_" + command);
  for (std::size_t i = 0; i < cases().size(); ++i) {
    INFO("bad scene: " << cases()[i].what << "; command: " << command);
    const auto scene_file = prepare(root, i);
    const auto dir = scene_file.parent_path();
    const auto before = listing(dir);
    const auto output = dir / "out";
    CHECK(run_shpb({command, scene_file.string(), "-o", output.string()}).code == 2);
    CHECK_FALSE(fs::exists(output));
    CHECK(listing(dir) == before);  // no temporary folder left beside the output either
  }
  fs::remove_all(root);
}

}  // namespace

TEST_CASE("The valid base scene of the bad-scene table validates", "[app][bad-scenes]") {
  const auto dir = shpb_test::scratch_dir("bad_scenes_base");
  std::ofstream(dir / "scene.json") << base_scene().dump(2);
  std::ofstream(dir / "specimen.json") << base_specimen().dump(2);
  const auto r = run_shpb({"validate", (dir / "scene.json").string()});
  INFO(r.err);
  REQUIRE(r.code == 0);
}

TEST_CASE("Every bad scene exits 2 with one line naming the file and the JSON path",
          "[app][bad-scenes]") {
  REQUIRE(cases().size() >= 30);
  const auto root = shpb_test::scratch_dir("bad_scenes_validate");
  for (std::size_t i = 0; i < cases().size(); ++i) {
    const auto& c = cases()[i];
    INFO("bad scene: " << c.what);
    const auto scene_file = prepare(root, i);
    const auto dir = scene_file.parent_path();
    const auto before = listing(dir);
    const auto r = run_shpb({"validate", scene_file.string()});
    const std::string& message = r.err;
    INFO("stderr: " << message);
    CHECK(r.code == 2);
    CHECK(message.rfind("error: " + scene_file.parent_path().string(), 0) == 0);
    CHECK(message.find(c.where) != std::string::npos);
    CHECK(std::count(message.begin(), message.end(), '\n') == 1);  // one line
    CHECK(std::none_of(message.begin(), message.end(),             // printable: no raw bytes echoed
                       [](char ch) { return static_cast<unsigned char>(ch) >= 0xF8; }));
    CHECK(r.out.empty());
    CHECK(listing(dir) == before);
  }
  fs::remove_all(root);
}

// Every command reads a scene through the same reader, which the sanitized suite runs over the
// whole table above and through simulate here; what differs between the commands is their output
// folder, which the optimised suite checks for each.
TEST_CASE("simulate writes nothing for a bad scene", "[app][bad-scenes]") {
  check_writes_nothing("simulate");
}
TEST_CASE("process writes nothing for a bad scene", "[release-only][app][bad-scenes]") {
  check_writes_nothing("process");
}
TEST_CASE("compare writes nothing for a bad scene", "[release-only][app][bad-scenes]") {
  check_writes_nothing("compare");
}
TEST_CASE("study writes nothing for a bad scene", "[release-only][app][bad-scenes]") {
  check_writes_nothing("study");
}

TEST_CASE("Every command that takes a scene refuses a bad scene with the same line",
          "[release-only][app][bad-scenes]") {
  // One validation (model/scene_validation.hpp after read_scene): whatever the command, the same
  // bad scene gives exit 2, the same one-line message and nothing written. `process --campaign`
  // and `fit` reach the scene through a campaign file naming it. The scene's plan block, which
  // only `plan` uses, is judged by all of them: a scene is one file.
  const std::vector<std::string> chosen = {"a length in kilograms",
                                           "a negative length",
                                           "a misspelt bar key",
                                           "an unknown contact method",
                                           "a Poisson ratio of 0.5",
                                           "a Poisson ratio of -1",
                                           "a Courant number above 1",
                                           "a missing material file",
                                           "a Johnson-Cook n above 1",
                                           "a misspelt plan key",
                                           "plan bounds out of order",
                                           "a plan shaper material not there",
                                           "a contact key misspelt at the top level"};
  const std::string copper =
      (fs::path(SHPB_SOURCE_DIR) / "specimens/ofhc-copper.json").lexically_normal().string();
  const auto root = shpb_test::scratch_dir("bad_scenes_commands");
  for (const std::string& what : chosen) {
    const auto it = std::find_if(cases().begin(), cases().end(),
                                 [&](const BadScene& c) { return c.what == what; });
    REQUIRE(it != cases().end());
    const auto scene = prepare(root, static_cast<std::size_t>(it - cases().begin()));
    const auto dir = scene.parent_path();
    std::ofstream(dir / "campaign.json")
        << json{{"tests", {{{"scene", "scene.json"}, {"name", "test"}}}}}.dump();
    std::ofstream(dir / "fit.json") << json{
        {"tests", {{{"scene", "scene.json"}}}},
        {"material", copper},
        {"free",
         {{"A", {"50 MPa", "150 MPa"}}}}}.dump();
    const auto before = listing(dir);
    const auto reference = run_shpb({"validate", scene.string()});
    INFO("bad scene: " << what << "; validate: " << reference.err);
    REQUIRE(reference.code == 2);
    REQUIRE(std::count(reference.err.begin(), reference.err.end(), '\n') == 1);
    const std::string out = (dir / "out").string();
    const std::vector<std::vector<std::string>> commands = {
        {"simulate", scene.string(), "-o", out},
        {"process", scene.string(), "-o", out},
        {"process", "--campaign", (dir / "campaign.json").string(), "-o", out},
        {"compare", scene.string(), "-o", out},
        {"study", scene.string(), "-o", out},
        {"calibrate", scene.string(), "-o", out},
        {"fit", (dir / "fit.json").string(), "-o", out}};
    for (const auto& args : commands) {
      INFO("shpb " << args[0] << " " << args[1]);
      const auto r = run_shpb(args);
      CHECK(r.code == 2);
      CHECK(r.err == reference.err);
      CHECK(r.out.empty());
      CHECK_FALSE(fs::exists(out));
      CHECK(listing(dir) == before);
    }
  }
  fs::remove_all(root);
}

// Values each within what the reader accepts on its own but beyond double precision in what a run
// derives from them (model/computable.hpp): refused before the first step, naming the input.
TEST_CASE("A scene whose derived quantities overflow or underflow a double is refused, not run",
          "[app][bad-scenes][computable]") {
  struct Case {
    std::string what;
    std::function<void(json&)> breaks;
    std::string where;
  };
  const std::vector<Case> table = {
      {"a striker 1e300 mm across: its area overflows",
       [](json& s) { s["bars"][0]["diameter"] = "1e300 mm"; }, "bars[0].diameter: 1e+297 m: "},
      {"a specimen 1e-200 mm across: its area underflows to 0",
       [](json& s) { s["bars"][2]["diameter"] = "1e-200 mm"; }, "bars[2].diameter: 1e-203 m: "},
      {"a contact rise time of 1e-300 us: its penalty stiffness overflows",
       [](json& s) { s["contact"]["rise_time"] = "1e-300 us"; }, "contact.rise_time: 1e-306 s: "},
      {"an interface's stiffness factor of 1e300",
       [](json& s) {
         s["contact"]["interfaces"] = {
             {{"between", {"striker", "incident"}}, {"stiffness_factor", 1e300}}};
       },
       "contact.interfaces[0].stiffness_factor: 1e+300: "},
      {"a striker at 1e300 m/s: its kinetic energy overflows",
       [](json& s) { s["bars"][0]["velocity"] = "1e300 m/s"; }, "bars[0].velocity: 1e+300 m/s: "},
  };
  const auto root = shpb_test::scratch_dir("bad_scenes_computable");
  for (std::size_t i = 0; i < table.size(); ++i) {
    INFO(table[i].what);
    const auto dir = root / ("case" + std::to_string(i));
    fs::create_directories(dir);
    json scene = base_scene();
    scene.erase("measurement");
    table[i].breaks(scene);
    std::ofstream(dir / "scene.json") << scene.dump(2);
    std::ofstream(dir / "specimen.json") << base_specimen().dump(2);
    const auto r = run_shpb({"validate", (dir / "scene.json").string()});
    INFO("stderr: " << r.err);
    CHECK(r.code == 2);
    CHECK(r.err.rfind("error: " + (dir / "scene.json").string() + ": " + table[i].where, 0) == 0);
    CHECK(r.err.find("double precision") != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    if (i == 0) {  // simulate refuses it alike, before writing anything
      const auto before = listing(dir);
      const auto sim =
          run_shpb({"simulate", (dir / "scene.json").string(), "-o", (dir / "out").string()});
      CHECK(sim.code == 2);
      CHECK(sim.err == r.err);
      CHECK(listing(dir) == before);
    }
  }
  fs::remove_all(root);
}

// The reduction's own derived quantities (model/computable.hpp, check_reduction_computable):
// `process` needs no simulation, so a specimen whose area underflows, or a bar whose area or
// stress per unit strain overflows, must be refused by the reduction itself (before this check:
// exit 3, "the reduction produced a non-finite value", with pulses.csv written).
TEST_CASE("process refuses a test whose reduction quantities overflow or underflow a double",
          "[app][bad-scenes][computable]") {
  struct Case {
    std::string what;
    std::function<void(json&)> breaks;
    std::string where;
  };
  const std::vector<Case> table = {
      {"a specimen 1e-300 mm across: its area underflows to 0",
       [](json& s) { s["bars"][2]["diameter"] = "1e-300 mm"; }, "bars[2].diameter: 1e-303 m: "},
      {"an incident bar 1e300 mm across: its area overflows",
       [](json& s) { s["bars"][1]["diameter"] = "1e300 mm"; }, "bars[1].diameter: 1e+297 m: "},
      {"a specimen of 1e-300 mm2: the bars' stress per unit strain E A/A_s overflows",
       [](json& s) {
         s["bars"][2].erase("diameter");
         s["bars"][2]["area"] = "1e-300 mm2";
       },
       "bars[2].area: 1e-306 m^2: "},
  };
  const auto root = shpb_test::scratch_dir("bad_scenes_reduction_computable");
  json valid = base_scene();
  valid.erase("measurement");
  std::ofstream(root / "scene.json") << valid.dump(2);
  std::ofstream(root / "specimen.json") << base_specimen().dump(2);
  const auto sim = run_shpb(
      {"simulate", "-q", (root / "scene.json").string(), "-o", (root / "simulated").string()});
  REQUIRE(sim.code == 0);
  const std::string signals = (root / "simulated" / "gauges.csv").string();
  for (std::size_t i = 0; i < table.size(); ++i) {
    INFO(table[i].what);
    const auto dir = root / ("case" + std::to_string(i));
    fs::create_directories(dir);
    json scene = valid;
    table[i].breaks(scene);
    std::ofstream(dir / "scene.json") << scene.dump(2);
    std::ofstream(dir / "specimen.json") << base_specimen().dump(2);
    const auto before = listing(dir);
    const auto r = run_shpb({"process", (dir / "scene.json").string(), "--signals", signals, "-o",
                             (dir / "out").string()});
    INFO("stderr: " << r.err);
    CHECK(r.code == 2);
    CHECK(r.err.rfind("error: " + (dir / "scene.json").string() + ": " + table[i].where, 0) == 0);
    CHECK(r.err.find("double precision") != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(listing(dir) == before);  // no output folder, not even pulses.csv
  }
  fs::remove_all(root);
}

}  // namespace tests_app_test_bad_scenes
