
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "../scratch.hpp"
#include "core/error.hpp"
#include "model/calibration.hpp"
#include "model/input_keys.hpp"
#include "model/scene.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_model_test_scene_reader {

using namespace shpb;
namespace fs = std::filesystem;

namespace {
// Unit conversions multiply exact decimal factors: equal to a few ulps.
constexpr double kUlps = 1e-14;

// A fresh folder per test case (and per process: tests run in parallel) for scenes and material
// files, removed at the end.
struct Scratch {
  explicit Scratch(const std::string& name) : folder("scene_reader_" + name), dir(folder.path()) {}
  shpb_test::ScratchDir folder;
  fs::path dir;
};

void write(const fs::path& file, const std::string& text) {
  fs::create_directories(file.parent_path());
  std::ofstream(file) << text;
}

std::string error_of(const fs::path& file) {
  try {
    read_scene(file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

const char* kSteel = R"("steel": {"model": "elastic", "density": "7.85 g/cm3",
                                  "youngs_modulus": "200 GPa", "poisson_ratio": 0.29})";
}  // namespace

TEST_CASE("The classic experiment reads with every value in SI", "[model][scene]") {
  const Scene s = read_scene(fs::path(SHPB_SOURCE_DIR) / "experiments/classic-al6061/scene.json");
  REQUIRE(s.bars.size() == 4);
  CHECK(s.name == "Al 6061-T6 at about 2000/s");
  CHECK(s.bars[0].name == "striker");
  CHECK(s.bars[0].velocity_m_s == 15);
  CHECK(s.bars[0].length_m == Approx(0.3).epsilon(kUlps));
  CHECK(s.bars[1].diameter_m == Approx(0.01905).epsilon(kUlps));
  CHECK(s.bars[1].area_m2 == Approx(M_PI * 0.01905 * 0.01905 / 4).epsilon(kUlps));
  CHECK(s.bars[1].material.youngs_modulus_Pa == 200e9);
  CHECK(s.bars[1].material.density_kg_m3 == 8080);
  CHECK(s.bars[1].material.poisson_ratio == 0.29);
  REQUIRE(s.bars[1].gauges.size() == 1);
  CHECK(s.bars[1].gauges[0].name == "incident");
  CHECK(s.bars[1].gauges[0].position_m == 1);
  REQUIRE(s.specimen == 2u);
  CHECK(s.incident_bar() == 1u);
  CHECK(s.transmitter_bar() == 3u);

  // The specimen file: Johnson & Cook 1985 constants for Al 6061-T6 (docs/scene-format.md).
  const auto& al = s.bars[2].material;
  CHECK(al.model == MaterialModel::kJohnsonCook);
  CHECK_FALSE(al.source.empty());
  CHECK(al.density_kg_m3 == 2703);
  CHECK(al.johnson_cook.A_Pa == Approx(324e6).epsilon(kUlps));
  CHECK(al.johnson_cook.B_Pa == Approx(114e6).epsilon(kUlps));
  CHECK(al.johnson_cook.n == 0.42);
  CHECK(al.johnson_cook.C == 0.002);
  CHECK(al.johnson_cook.m == 1.34);
  CHECK(al.johnson_cook.melting_temperature_K == 925);
  CHECK(al.johnson_cook.specific_heat_J_kgK == 885);
  CHECK(al.johnson_cook.initial_temperature_K == al.johnson_cook.room_temperature_K);

  CHECK(s.contact.method == ContactMethod::kLocalizedBipenalty);
  CHECK(s.simulation.duration_s == Approx(800e-6).epsilon(kUlps));
  CHECK(s.simulation.sample_rate_Hz == 10e6);
  CHECK_FALSE(s.measurement);
}

TEST_CASE("The LANL copper experiment reads its measurement block", "[model][scene]") {
  const Scene s = read_scene(fs::path(SHPB_SOURCE_DIR) / "experiments/lanl-cu-ofe-273k/scene.json");
  REQUIRE(s.measurement);
  const auto& m = *s.measurement;
  CHECK(m.format == SignalFormat::kLanlRaw);
  CHECK(m.file.filename() == "20061201_1148HE_CuOFE_273K.raw");
  REQUIRE(m.channels.size() == 2);
  CHECK(m.channels[0].gauge == "incident");
  CHECK(m.channels[0].column.name == "Incident/Reflected Waveform");
  CHECK(m.channels[0].unit == SignalUnit::kVolt);
  REQUIRE(m.channels[0].bridge);
  CHECK(m.channels[0].bridge->arms == 2);
  CHECK(m.channels[0].bridge->gauge_factor == 2.061);
  CHECK(m.channels[0].bridge->excitation_V == 8);
  CHECK(m.channels[0].bridge->gain == 200);
  CHECK(m.channels[1].bridge->gain == 200);  // the "Transmitted Bar Gain" (see the README)
  CHECK(m.channels[1].invert);
  CHECK(m.dispersion.correction);
  CHECK_FALSE(m.striker_velocity_m_s);  // not measured: processing infers it
  // Gauges 381 mm from the specimen faces (README of the measured data).
  const auto& inc = s.bars[1];
  CHECK(inc.length_m - inc.gauges[0].position_m == Approx(0.381).epsilon(1e-12));
  CHECK(s.bars[3].gauges[0].position_m == Approx(0.381).epsilon(kUlps));
  // Test temperature 0 °C given in Celsius.
  CHECK(s.bars[2].material.johnson_cook.initial_temperature_K == Approx(273.15).epsilon(kUlps));
}

TEST_CASE("Materials come by name, by file relative to the scene, or inline", "[model][scene]") {
  const Scratch scratch("materials");
  const auto& dir = scratch.dir;
  write(dir / "mats/soft.json",
        R"({"model": "bilinear", "density": 2700, "youngs_modulus": "70 GPa",
      "poisson_ratio": 0.33, "yield_stress": "300 MPa", "tangent_modulus": "1 GPa"})");
  write(dir / "scenes/scene.json", std::string(R"({
    "bars": [
      {"name": "a", "material": "steel", "length": 1, "area": "2 cm2", "velocity": "-3 m/s",
       "gap": "1 mm", "elements": 50},
      {"name": "b", "material": "../mats/soft.json", "length": "5 mm", "diameter": "10 mm"},
      {"name": "c", "material": {"model": "viscoelastic", "density": 1190, "poisson_ratio": 0.35,
                                 "long_term_modulus": "2 GPa",
                                 "arms": [{"modulus": "1 GPa", "relaxation_time": "10 us"},
                                          {"modulus": "0.5 GPa", "relaxation_time": "1 ms"}]},
       "length": 1, "diameter": 0.02}
    ],
    "materials": {)") + kSteel + "}}");
  const Scene s = read_scene(dir / "scenes/scene.json");
  CHECK(s.name == "scenes");  // scene.json is named by its folder
  CHECK(s.bars[0].material.name == "steel");
  CHECK(s.bars[0].area_m2 == Approx(2e-4).epsilon(kUlps));
  CHECK(s.bars[0].diameter_m == Approx(std::sqrt(4 * 2e-4 / M_PI)).epsilon(kUlps));
  CHECK(s.bars[0].velocity_m_s == -3);
  CHECK(s.bars[0].gap_m == Approx(1e-3).epsilon(kUlps));
  CHECK(s.bars[0].elements == 50);
  CHECK(s.bars[1].material.model == MaterialModel::kBilinear);
  CHECK(s.bars[1].material.bilinear.yield_stress_Pa == 300e6);
  CHECK(s.bars[1].material.bilinear.tangent_modulus_Pa == 1e9);
  const auto& ve = s.bars[2].material;
  CHECK(ve.name == "inline");
  REQUIRE(ve.viscoelastic.arms.size() == 2);
  CHECK(ve.viscoelastic.arms[0].relaxation_time_s == Approx(10e-6).epsilon(kUlps));
  // The instantaneous modulus of a generalized Maxwell solid is E_inf + ΣE_k.
  CHECK(ve.youngs_modulus_Pa == Approx(3.5e9).epsilon(kUlps));
  CHECK_FALSE(s.specimen);
  CHECK_FALSE(s.incident_bar());
}

TEST_CASE("Defaults fill what a scene leaves out", "[model][scene]") {
  const Scratch scratch("defaults");
  const auto& dir = scratch.dir;
  write(dir / "minimal.json", std::string(R"({"bars": [
      {"name": "s", "material": "steel", "length": 0.3, "diameter": 0.02, "velocity": 10},
      {"name": "b", "material": "steel", "length": 1.5, "diameter": 0.02}],
    "materials": {)") + kSteel + "}}");
  const Scene s = read_scene(dir / "minimal.json");
  CHECK(s.name == "minimal");
  CHECK(s.bars[1].elements == 0);  // automatic meshing
  CHECK(s.bars[1].gap_m == 0);
  CHECK(s.contact.method == ContactMethod::kLocalizedBipenalty);
  CHECK_FALSE(s.contact.penalty.stiffness_factor);
  CHECK_FALSE(s.simulation.duration_s);
  CHECK(s.simulation.sample_rate_Hz == 10e6);
  CHECK(s.simulation.stepping == Stepping::kAsynchronous);
  CHECK_FALSE(s.simulation.courant);
}

TEST_CASE("Contact settings apply to all interfaces with overrides per interface",
          "[model][scene]") {
  const Scratch scratch("contact");
  const auto& dir = scratch.dir;
  write(dir / "scene.json", std::string(R"({"bars": [
      {"name": "s", "material": "steel", "length": 0.3, "diameter": 0.02, "velocity": 10},
      {"name": "i", "material": "steel", "length": 1.5, "diameter": 0.02},
      {"name": "t", "material": "steel", "length": 1.5, "diameter": 0.02}],
    "materials": {)") + kSteel + R"(},
    "contact": {"method": "bipenalty", "stiffness_factor": 1e4, "mass_ratio": 0.9,
                "interfaces": [{"between": ["t", "i"], "method": "penalty", "stiffness": "1e9 N/m"}]},
    "simulation": {"duration": "0.4 ms", "sample_rate": "5 MHz", "stepping": "global",
                   "courant": 0.98}})");
  const Scene s = read_scene(dir / "scene.json");
  CHECK(s.contact.method == ContactMethod::kBipenalty);
  CHECK(s.contact.penalty.stiffness_factor == 1e4);
  CHECK(s.contact.penalty.mass_ratio == 0.9);
  REQUIRE(s.contact.interfaces.size() == 1);
  CHECK(s.contact.interfaces[0].left_bar == 1);  // order in "between" does not matter
  CHECK(s.contact.interfaces[0].method == ContactMethod::kPenalty);
  CHECK(s.contact.interfaces[0].penalty.stiffness_N_m == 1e9);
  // The override's stiffness replaces the scene-wide factor; the scene-wide mass ratio stays.
  const PenaltyParams merged = interface_penalty(s.contact, 1);
  CHECK_FALSE(merged.stiffness_factor);
  CHECK(merged.stiffness_N_m == 1e9);
  CHECK(merged.mass_ratio == 0.9);
  CHECK(interface_method(s.contact, 1) == ContactMethod::kPenalty);
  CHECK(interface_method(s.contact, 0) == ContactMethod::kBipenalty);
  CHECK(interface_penalty(s.contact, 0).stiffness_factor == 1e4);
  CHECK(s.simulation.duration_s == Approx(4e-4).epsilon(kUlps));
  CHECK(s.simulation.sample_rate_Hz == 5e6);
  CHECK(s.simulation.stepping == Stepping::kGlobal);
  CHECK(s.simulation.courant == 0.98);
}

TEST_CASE("Errors name the file, the JSON path, the value and the constraint", "[model][scene]") {
  const Scratch scratch("errors");
  const auto& dir = scratch.dir;
  const auto file = dir / "scene.json";
  write(file, std::string(R"({"bars": [
      {"name": "s", "material": "steel", "length": "-5 mm", "diameter": 0.02},
      {"name": "b", "material": "steel", "length": 1.5, "diameter": 0.02}],
    "materials": {)") +
                  kSteel + "}}");
  CHECK(error_of(file) == file.string() + ": bars[0].length: -0.005 m: must be > 0");

  write(file, std::string(R"({"bars": [
      {"name": "s", "material": "stel", "length": 1, "diameter": 0.02},
      {"name": "b", "material": "steel", "length": 1.5, "diameter": 0.02}],
    "materials": {)") +
                  kSteel + "}}");
  CHECK(error_of(file) == file.string() +
                              ": bars[0].material: \"stel\": no such material in materials; did "
                              "you mean \"steel\"?");

  write(file, R"({"bars": [], "materails": {}})");
  CHECK(error_of(file) == file.string() + ": materails: unknown key: did you mean \"materials\"?");
}

TEST_CASE("A calibration file holds exactly the keys shpb calibrate writes", "[model][scene]") {
  // One format, its writer and its reader (model/calibration.hpp): a key the writer never writes
  // would be accepted and silently ignored, where a scene's unknown key is refused.
  Calibration c;
  c.bars.push_back({"incident", {4975, 1}, {0.29, 0.01}, 8080});
  c.gauges.push_back({"inc", "incident", {1, 1e-3}, {1, 0.01}, {0, 1e-7}});
  const nlohmann::json written = calibration_to_json(c);
  std::vector<std::string> keys;
  for (const auto& [key, value] : written.items()) keys.push_back(key);
  std::vector<std::string> accepted = input_keys::kCalibration;
  std::sort(keys.begin(), keys.end());
  std::sort(accepted.begin(), accepted.end());
  CHECK(keys == accepted);

  const Scratch s("calibration_keys");
  const fs::path file = s.dir / "calibration.json";
  nlohmann::json with_version = written;
  with_version["version"] = "1.0";
  write(file, with_version.dump());
  try {
    read_calibration_file(file);
    FAIL("a calibration file with a top-level \"version\" was read");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find(file.string() + ": version: unknown key") == 0);
  }
  // A key of the file's other object is named there (before: the keys of bars[] were listed).
  nlohmann::json misplaced = written;
  misplaced["bars"][0]["position_m"] = written["gauges"][0]["position_m"];
  write(file, misplaced.dump());
  try {
    read_calibration_file(file);
    FAIL("a gauge's key in bars[0] was read");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()) == file.string() +
                                       ": bars[0].position_m: unknown key: not here; "
                                       "\"position_m\" is a key of gauges[]");
  }
  write(file, written.dump());
  CHECK(read_calibration_file(file).bars.at(0).wave_speed_m_s.value == 4975);
}

// A calibration's density_kg_m3 and youngs_modulus_Pa are the scene's density and ρ c0², written
// for reading, and its reference gauge the channel the gains are relative to: an edit of any of
// them changed nothing the scene reads (the modulus stayed ρ_scene c0²). Each is checked to be
// what it records.
TEST_CASE("A calibration's recorded density modulus and reference gauge are checked not ignored",
          "[model][scene]") {
  const Scratch s("calibration_recorded");
  write(s.dir / "scene.json", std::string(R"({"calibration": "calibration.json", "bars": [
      {"name": "striker", "material": "steel", "length": "0.3 m", "diameter": "19.05 mm",
       "velocity": "10 m/s"},
      {"name": "incident", "material": "steel", "length": "2 m", "diameter": "19.05 mm",
       "gauges": [{"name": "inc", "position": "1 m"}, {"name": "far", "position": "1.5 m"}]}],
    "materials": {)") + kSteel + "}}");
  Calibration c;
  c.reference_gauge = "inc";
  const double c0 = 5000, rho = 7850;  // the scene's steel: 7.85 g/cm3
  c.bars.push_back({"incident", {c0, 1}, {0.29, 0.01}, rho});
  c.gauges.push_back({"inc", "incident", {1, 1e-3}, {1, 0.01}, {0, 1e-7}});
  c.gauges.push_back({"far", "incident", {1.5, 1e-3}, {1.02, 0.01}, {1e-7, 1e-8}});
  const auto with = [&](const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json j = calibration_to_json(c);
    edit(j);
    write(s.dir / "calibration.json", j.dump());
    return error_of(s.dir / "scene.json");
  };
  const std::string cal = (s.dir / "calibration.json").lexically_normal().string();
  // As written: read, the modulus ρ c0² of the scene's density.
  CHECK(with([](nlohmann::json&) {}) == "(no error)");
  CHECK(read_scene(s.dir / "scene.json").bars[1].material.youngs_modulus_Pa ==
        Approx(rho * c0 * c0).epsilon(kUlps));
  // The modulus edited by hand (210 GPa where ρ c0² is 196.25 GPa).
  std::string e = with([](nlohmann::json& j) { j["bars"][0]["youngs_modulus_Pa"] = 210e9; });
  INFO(e);
  CHECK(e.rfind(cal + ": bars[0].youngs_modulus_Pa: 210000000000.0: expected density_kg_m3 x "
                      "wave_speed_m_s^2 = 1.9625e+11 Pa",
                0) == 0);
  // The density edited, or the scene's changed since the calibration.
  e = with([](nlohmann::json& j) {
    j["bars"][0]["density_kg_m3"] = 8000;
    j["bars"][0]["youngs_modulus_Pa"] = 8000 * 5000.0 * 5000.0;
  });
  CHECK(e.rfind(cal + ": bars[0].density_kg_m3: 8000 kg/m^3: expected the density of bar "
                      "\"incident\"",
                0) == 0);
  // Another reference gauge named: the gains stay relative to "inc" (gain 1, delay 0).
  e = with([](nlohmann::json& j) { j["reference_gauge"] = "far"; });
  CHECK(e.rfind(cal + ": reference_gauge: \"far\": gains and delays are relative to this gauge's "
                      "channel, whose gauges[] entry has gain 1.02",
                0) == 0);
  e = with([](nlohmann::json& j) { j["reference_gauge"] = "nowhere"; });
  CHECK(e.rfind(cal + ": reference_gauge: \"nowhere\": expected the name of a gauge in gauges[]",
                0) == 0);
  // Absolute gains: the reference's gain is its own (not 1).
  e = with([](nlohmann::json& j) {
    j["absolute_gain"] = true;
    j["gauges"][0]["gain"]["value"] = 0.97;
  });
  CHECK(e == "(no error)");
  // A bar or gauge calibrated twice: one entry was used without a word. Refused.
  e = with([](nlohmann::json& j) { j["bars"].push_back(j["bars"][0]); });
  CHECK(e == cal + ": bars[1].bar: \"incident\": calibrated twice (bars[0]): one value per bar");
  e = with([](nlohmann::json& j) { j["gauges"].push_back(j["gauges"][1]); });
  CHECK(e == cal + ": gauges[2].gauge: \"far\": calibrated twice (gauges[1]): one value per gauge");
  // What the scene does not have is named where the calibration says it (before: the scene's
  // `calibration` key, with the gauge's position as "2.500000 m").
  const std::string scene = (s.dir / "scene.json").string();
  e = with([](nlohmann::json& j) { j["gauges"][1]["position_m"]["value"] = 2.5; });
  CHECK(e == cal +
                 ": gauges[1].position_m.value: 2.5 m: must lie on the bar: within [0, 2 m] from "
                 "its left end (bar \"incident\" of " +
                 scene + ")");
  e = with([](nlohmann::json& j) { j["bars"][0]["bar"] = "transmitter"; });
  CHECK(e == cal + ": bars[0].bar: \"transmitter\": no such bar (with a material) in " + scene +
                 ": a calibration of other bars");
  e = with([](nlohmann::json& j) { j["gauges"][1]["bar"] = "striker"; });
  CHECK(e == cal + ": gauges[1].bar: \"striker\": gauge \"far\" is on bar \"incident\" in " +
                 scene + ": a calibration of other bars");
}

// A material's `uncertainty` is a fit's record of its law parameters' intervals (fit.json): read
// as such, refused as anything else (a standard uncertainty there was read by nothing).
TEST_CASE("A material's uncertainty is a fit's intervals of its law parameters", "[model][scene]") {
  const Scratch s("material_uncertainty");
  const auto scene_with = [&](const std::string& uncertainty) {
    write(s.dir / "scene.json", R"({"bars": [
      {"name": "striker", "material": "al", "length": "0.3 m", "diameter": "19.05 mm"},
      {"name": "incident", "material": "al", "length": "2 m", "diameter": "19.05 mm"}],
      "materials": {"al": {"model": "bilinear", "density": 2700, "youngs_modulus": "70 GPa",
        "poisson_ratio": 0.33, "yield_stress": "300 MPa", "tangent_modulus": "1 GPa",
        "uncertainty": )" + uncertainty +
                                    "}}}");
    return error_of(s.dir / "scene.json");
  };
  const std::string file = s.dir / "scene.json";
  CHECK(scene_with(R"({"yield_stress": {"interval_95": [2.9e8, 3.1e8], "method": "bootstrap",
                        "weakly_identified": false}})") == "(no error)");
  CHECK(scene_with(R"({"yield_stress": "2 %"})")
            .rfind(file + ": materials.al.uncertainty.yield_stress: \"2 %\": expected {", 0) == 0);
  CHECK(scene_with(R"({"A": {"interval_95": [1, 2]}})")
            .rfind(file + ": materials.al.uncertainty.A: {\"interval_95\":[1,2]}: not a law "
                          "parameter of this bilinear material",
                   0) == 0);
  CHECK(scene_with(R"({"yield_stress": {"interval_95": [3.1e8, 2.9e8]}})")
            .rfind(file + ": materials.al.uncertainty.yield_stress.interval_95: ", 0) == 0);
  CHECK(scene_with(R"({"yield_stress": {"interval95": [2.9e8, 3.1e8]}})")
            .rfind(file + ": materials.al.uncertainty.yield_stress.interval95: unknown key", 0) ==
        0);
}

}  // namespace tests_model_test_scene_reader
