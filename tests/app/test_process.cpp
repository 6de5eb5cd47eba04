
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "lab_record.hpp"
#include "run_shpb.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_app_test_process {

using namespace std::string_literals;
namespace fs = std::filesystem;

namespace {

using shpb_test::run_shpb;
using shpb_test::summary;

fs::path temp_dir(const std::string& name) { return shpb_test::scratch_dir("process_" + name); }

// A steel Kolsky bar whose measurement is `signals.csv` beside the scene (strain columns by name).
fs::path write_scene(const fs::path& dir, const std::string& signals) {
  nlohmann::json scene = shpb_test::steel_scene();
  scene["name"] = "test bar";
  return shpb_test::write(dir, scene, signals);
}

// The clean record (lab_record.hpp): incident −1e-3 trapezoid at 50 µs, reflected +0.6e-3 at
// 450 µs, transmitted −0.4e-3 at 350 µs (face clock: all reach the specimen at 250 µs).
std::string good_signals() { return shpb_test::csv(shpb_test::Record{}); }

const fs::path kExperiments = fs::path(SHPB_SOURCE_DIR) / "experiments";

}  // namespace

TEST_CASE("process writes pulses.csv, curve.csv and summary.json with the documented columns",
          "[app][process]") {
  const fs::path d = temp_dir("good");
  const fs::path scene = write_scene(d, good_signals());
  const auto r = run_shpb({"process", scene.string(), "-o", (d / "out").string()});
  REQUIRE(r.code == 0);
  std::ifstream curve(d / "out/curve.csv");
  std::string header;
  std::getline(curve, header);
  CHECK(
      header.rfind("time_s,strain_rate_1_s,strain,stress_1wave_Pa,stress_2wave_Pa,stress_3wave_Pa,"
                   "true_strain,true_stress_Pa,equilibrium_ratio",
                   0) == 0);
  std::ifstream pulses(d / "out/pulses.csv");
  std::getline(pulses, header);
  CHECK(header == "time_s,incident,reflected,transmitted");
  const auto s = summary(d / "out");
  // Incident plateau 1e-3 on steel: V = 2 c0 ε = 10 m/s (striker of the bar's material).
  CHECK(s["striker_velocity_m_s"]["inferred"].get<double>() == Approx(10).epsilon(5e-3));
  CHECK(s["windows"]["incident"]["start_s"].get<double>() == Approx(50e-6).margin(1e-6));
  CHECK(s["shifts_s"]["incident"].get<double>() == Approx(1.0 / 5000));
  // Rate (c0/L)(1e-3 + 0.6e-3 − 0.4e-3) = 1200 1/s on the plateau.
  CHECK(s["plateau_strain_rate_1_s"].get<double>() == Approx(1200).epsilon(5e-3));
}

TEST_CASE("Broken signal files exit 2 naming file, line and column, and write nothing",
          "[app][process]") {
  const std::string head = "time_s,incident,transmitted\n";
  const std::string rows = "0,0,0\n1e-7,0,0\n2e-7,0,0\n3e-7,0,0\n";
  struct Case {
    const char* name;
    std::string body;
    std::string expected;
  };
  const Case cases[] = {
      {"missing column", "time_s,incident,other\n" + rows, "line 1: column \"transmitted\""},
      {"text in numbers", head + rows + "4e-7,abc,0\n", "line 6, column 2 (\"incident\"): \"abc\""},
      {"NaN", head + rows + "4e-7,0,nan\n", "line 6, column 3 (\"transmitted\"): \"nan\""},
      {"non-monotonic time", head + rows + "2.5e-7,0,0\n", "line 6 (time column)"},
      {"truncated line", head + rows + "4e-7,0", "line 6, column 3"},
      {"empty", "", "line 1"},
  };
  for (const auto& c : cases) {
    CAPTURE(c.name);
    const fs::path d = temp_dir("broken");
    const fs::path scene = write_scene(d, c.body);
    const auto r = run_shpb({"process", scene.string(), "-o", (d / "out").string()});
    CHECK(r.code == 2);
    CHECK(r.err.rfind("error: ", 0) == 0);
    CHECK(r.err.find("signals.csv: " + c.expected) != std::string::npos);
    CHECK(r.err.find('\n') == r.err.size() - 1);  // one line
    CHECK_FALSE(fs::exists(d / "out"));
  }
}

TEST_CASE("The LANL copper and PMMA tests process end to end from the scene alone",
          "[app][process][data]") {
  struct Expect {
    const char* experiment;
    double v_lo, v_hi;  // the READMEs estimate the striker at ≈ 22 and ≈ 13.5 m/s
  };
  for (const auto& e :
       {Expect{"lanl-cu-ofe-273k", 15, 25}, Expect{"lanl-pmma13-mini-kolsky", 10, 16}}) {
    CAPTURE(e.experiment);
    const fs::path out = temp_dir(e.experiment) / "out";
    const auto r = run_shpb({"process", (kExperiments / e.experiment / "scene.json").string(), "-o",
                             out.string(), "--quiet"});
    REQUIRE(r.code == 0);
    const auto s = summary(out);
    CHECK(s["windows"]["incident"]["source"] == "detected");
    const double v = s["striker_velocity_m_s"]["inferred"].get<double>();
    CHECK(v > e.v_lo);
    CHECK(v < e.v_hi);
    // Both rates fall steadily over the loading (no plateau to quote): the mean is reported.
    CHECK(s["plateau_strain_rate_1_s"].is_null());
    CHECK(s["strain_rate"]["mean_over_loading_1_s"].get<double>() > 1000);
    CHECK(s["dispersion"]["correction"] == "pochhammer-chree");
    CHECK(fs::file_size(out / "curve.csv") > 1000);
  }
}

// A normal draw of a bar's modulus with a standard uncertainty above a sixth of it crosses zero
// often enough to matter (model/uncertainty_reader.hpp: kSignKeepingSigmas): refused before any
// draw, naming the JSON path, the value and its uncertainty; a sixth of it is drawn.
TEST_CASE("process refuses an uncertainty that would draw a positive quantity <= 0",
          "[app][process][uncertainty]") {
  const fs::path dir = temp_dir("uncertainty_sign");
  nlohmann::json scene = shpb_test::steel_scene();
  for (const auto& [given, refused] :
       {std::pair{"250 GPa", true}, std::pair{"34 GPa", true}, std::pair{"33 GPa", false}}) {
    CAPTURE(given);
    scene["measurement"]["uncertainty"] = {{"bars", {{"incident", {{"youngs_modulus", given}}}}}};
    const fs::path file = shpb_test::write(dir, scene, good_signals());
    fs::remove_all(dir / "out");
    const auto r = run_shpb(
        {"process", file.string(), "-o", (dir / "out").string(), "--draws", "20", "--quiet"});
    INFO(r.err);
    if (!refused) {
      CHECK(r.code == 0);
      continue;
    }
    CHECK(r.code == 2);
    // The error is the last line (the nominal reduction's warnings on this record come first).
    const std::string last = r.err.substr(r.err.rfind("error: "));
    CHECK(last.rfind("error: " + file.string() +
                         ": measurement.uncertainty.bars.incident.youngs_modulus: ",
                     0) == 0);
    CHECK(last.find("on a value of 2e+11 Pa that must stay > 0") != std::string::npos);
    CHECK(std::count(last.begin(), last.end(), '\n') == 1);
    CHECK_FALSE(fs::exists(dir / "out"));
  }
}

// A trigger delay or window start is drawn as a time shift of a pulse: a standard uncertainty of
// a sixth of the record or more moves pulses off the record (before this check: 1e300 samples ran
// to exit 0 with bands and no warning). Refused before any draw, naming the JSON path and value.
TEST_CASE("process refuses a time-shift uncertainty that would move pulses off the record",
          "[app][process][uncertainty]") {
  const fs::path dir = temp_dir("uncertainty_shift");
  // The record (lab_record.hpp) holds kSamples samples kDt apart: 799.9 us, a sixth 133.3 us.
  const std::vector<std::tuple<std::string, nlohmann::json, std::string>> cases = {
      {"window_start", 1e300, "measurement.uncertainty.window_start: 1e+300 samples: "},
      {"window_start", 1334, "measurement.uncertainty.window_start: 1334 samples: "},
      {"trigger_delay", "1 ms", "measurement.uncertainty.trigger_delay: 0.001 s: "},
      {"trigger_delay", "0.1 us", ""},
      {"window_start", 1, ""}};
  for (const auto& [key, given, refused] : cases) {
    CAPTURE(key, given.dump());
    nlohmann::json scene = shpb_test::steel_scene();
    scene["measurement"]["uncertainty"] = {{key, given}};
    const fs::path file = shpb_test::write(dir, scene, good_signals());
    fs::remove_all(dir / "out");
    const auto r = run_shpb(
        {"process", file.string(), "-o", (dir / "out").string(), "--draws", "20", "--quiet"});
    INFO(r.err);
    if (refused.empty()) {
      CHECK(r.code == 0);
      continue;
    }
    CHECK(r.code == 2);
    const std::string last = r.err.substr(r.err.rfind("error: "));
    CHECK(last.rfind("error: " + file.string() + ": " + refused, 0) == 0);
    CHECK(last.find("would move its pulse off the record") != std::string::npos);
    CHECK(std::count(last.begin(), last.end(), '\n') == 1);
    CHECK_FALSE(fs::exists(dir / "out"));
  }
}

// What process refuses in measurement.uncertainty before any draw, from the scene and its record
// alone, validate refuses too, with the same line (before: validate exit 0 on a gauge-position
// uncertainty of 7 m on a gauge 1 m from the specimen; process exit 2). What process accepts,
// validate accepts.
TEST_CASE("validate refuses the measurement.uncertainty process refuses, with its message",
          "[app][process][validate][uncertainty]") {
  const fs::path dir = temp_dir("uncertainty_validate");
  const std::vector<std::pair<nlohmann::json, bool>> cases = {
      {{{"gauge_position", "7 m"}}, true},
      {{{"bars", {{"incident", {{"youngs_modulus", "250 GPa"}}}}}}, true},
      {{{"trigger_delay", "1 ms"}}, true},
      // The default cut-off on these bars: f a/c0 = 0.2619, c0 = 5000 m/s, a = 10 mm: 131 kHz.
      {{{"dispersion_cutoff", "1 MHz"}}, true},
      {{{"gauge_position", "1 mm"}, {"trigger_delay", "0.1 us"}, {"dispersion_cutoff", "10 %"}},
       false}};
  for (const auto& [uncertainty, refused] : cases) {
    CAPTURE(uncertainty.dump());
    nlohmann::json scene = shpb_test::steel_scene();
    scene["measurement"]["dispersion"]["correction"] = "pochhammer-chree";  // it has a cut-off
    scene["measurement"]["uncertainty"] = uncertainty;
    const fs::path file = shpb_test::write(dir, scene, good_signals());
    fs::remove_all(dir / "out");
    const auto v = run_shpb({"validate", file.string()});
    const auto p = run_shpb(
        {"process", file.string(), "-o", (dir / "out").string(), "--draws", "20", "--quiet"});
    INFO(v.err << p.err);
    CHECK(v.code == (refused ? 2 : 0));
    CHECK(p.code == (refused ? 2 : 0));
    if (!refused) continue;
    const std::string last = p.err.substr(p.err.rfind("error: "));
    CHECK(v.err.substr(v.err.rfind("error: ")) == last);
    CHECK(last.rfind("error: " + file.string() + ": measurement.uncertainty.", 0) == 0);
    CHECK(std::count(last.begin(), last.end(), '\n') == 1);
  }
}

// A gauge whose record holds no pulse above its noise: the one line names the record's file and
// column the user would open, with the scene's channel (before: the scene and
// "measurement.channels: gauge "incident"" alone, the file and column unsaid). Exit 2.
TEST_CASE("process names the record file and column of a gauge without a pulse", "[app][process]") {
  const fs::path dir = temp_dir("no_pulse");
  shpb_test::Record flat;
  flat.incident_gauge = [](double) { return 0.0; };
  const fs::path scene = write_scene(dir, shpb_test::csv(flat));
  const auto r = run_shpb({"process", scene.string(), "-o", (dir / "out").string(), "--quiet"});
  INFO(r.err);
  CHECK(r.code == 2);
  const std::string last = r.err.substr(r.err.rfind("error: "));
  CHECK(last.rfind("error: " + (dir / "signals.csv").string() +
                       ": column \"incident\" (measurement.channels[0], gauge \"incident\"): "
                       "its signal never rises above its noise",
                   0) == 0);
  CHECK(std::count(last.begin(), last.end(), '\n') == 1);
  CHECK_FALSE(fs::exists(dir / "out"));
}

// An auxetic bar is a valid material (-1 < nu < 0.5) but not a processed bar (the dispersion
// tables cover 0 ... 0.49): the refusal names where the ratio was given — a key of `materials`, a
// material file, or the bar's inline material — not a path the file does not have (before:
// "bars[1].material.poisson_ratio" for a ratio given in materials.steel).
TEST_CASE("process names where a processed bar's unsupported Poisson ratio was given",
          "[app][process]") {
  const fs::path dir = temp_dir("poisson_path");
  fs::create_directories(dir / "m");
  const nlohmann::json steel = shpb_test::steel_scene()["materials"]["steel"];
  struct Case {
    std::string what, file, where;
    std::function<void(nlohmann::json&)> edit;
  };
  const std::vector<Case> cases = {
      {"a key of materials", "scene.json", "materials.steel.poisson_ratio",
       [](nlohmann::json& s) { s["materials"]["steel"]["poisson_ratio"] = -0.2; }},
      {"a material file", "m/bar.json", "poisson_ratio",
       [&](nlohmann::json& s) {
         nlohmann::json m = steel;
         m["poisson_ratio"] = -0.2;
         std::ofstream(dir / "m/bar.json") << m.dump();
         s["bars"][3]["material"] = "m/bar.json";
       }},
      {"an inline material", "scene.json", "bars[1].material.poisson_ratio",
       [&](nlohmann::json& s) {
         s["bars"][1]["material"] = steel;
         s["bars"][1]["material"]["poisson_ratio"] = -0.2;
       }}};
  for (const Case& c : cases) {
    INFO(c.what);
    nlohmann::json scene = shpb_test::steel_scene();
    c.edit(scene);
    const fs::path file = shpb_test::write(dir, scene, good_signals());
    fs::remove_all(dir / "out");
    const auto r = run_shpb({"process", file.string(), "-o", (dir / "out").string(), "--quiet"});
    INFO(r.err);
    CHECK(r.code == 2);
    const std::string last = r.err.substr(std::min(r.err.rfind("error: "), r.err.size()));
    const std::string named = (dir / c.file).string();
    CHECK(last.rfind("error: " + named + ": " + c.where + ": -0.2: must be in [0, 0.49]", 0) == 0);
    CHECK_FALSE(fs::exists(dir / "out"));
  }
}

TEST_CASE("The epoxy file's repeated time stamps and doubtful scale are reported",
          "[app][process][data]") {
  const fs::path out = temp_dir("epoxy") / "out";
  const auto r = run_shpb(
      {"process", (kExperiments / "epoxy-resin-sample01/scene.json").string(), "-o", out.string()});
  REQUIRE(r.code == 0);
  CHECK(r.err.find("warning: ") != std::string::npos);
  CHECK(r.err.find("time stamps repeat") != std::string::npos);
  CHECK(r.err.find("time base rebuilt from the sample interval 8e-08 s") != std::string::npos);
  CHECK(r.err.find("implausible strain scale") != std::string::npos);
  // Rebuilt time base, two implausible scales and the transmitted pulse ~28 µs later than the
  // geometry puts it (the soft epoxy, or the gauge distance: said, not decided). The reflected
  // onset, 0.7 µs early on that clock, is not: its front rises 4.3 µs more slowly than the
  // incident one (13.4 against 9.1 µs to half height), so its foot is that much less certain.
  CHECK(r.err.find("the transmitted pulse starts") != std::string::npos);
  CHECK(r.err.find("the reflected pulse starts") == std::string::npos);
  constexpr double kOneSample_s = 8e-8;  // the rebuilt clock's interval
  CHECK(summary(out)["alignment"]["reflected_onset_minus_expected_s"].get<double>() ==
        Approx(-0.708e-6).margin(kOneSample_s));
  // And a soft specimen in equilibrium over less than half its loading, never until unloading.
  CHECK(r.err.find("in equilibrium (R = 2|P1-P2|/|P1+P2| <= 0.05) over only 46.5 %") !=
        std::string::npos);
  // Said whole, down to the transmitted face's peak it closes with (a long message once lost it).
  CHECK(r.err.find("(the 1-wave, transmitted face's, ") != std::string::npos);
  CHECK(summary(out)["warnings"].size() == 5);
}

TEST_CASE("process --signals reduces a gauges.csv written by simulate without dispersion",
          "[app][process]") {
  const fs::path d = temp_dir("simulated");
  const fs::path scene = kExperiments / "classic-al6061/scene.json";
  REQUIRE(run_shpb({"simulate", scene.string(), "-o", (d / "sim").string(), "--quiet"}).code == 0);
  const auto r = run_shpb({"process", scene.string(), "--signals", (d / "sim/gauges.csv").string(),
                           "-o", (d / "out").string()});
  REQUIRE(r.code == 0);
  const auto s = summary(d / "out");
  CHECK(s["dispersion"]["correction"] == "none");
  CHECK(s["signals"]["source"] == "simulated (--signals)");
  // The scene's striker moves at 15 m/s; the incident plateau gives it back.
  CHECK(s["striker_velocity_m_s"]["inferred"].get<double>() == Approx(15).epsilon(0.01));
}

TEST_CASE("A gauge factor shared by every channel moves the stress by its whole uncertainty",
          "[app][process][uncertainty]") {
  // Gauges from one lot: a gauge factor 1 % off scales every strain of the record, so the 3-wave
  // stress (front and back forces averaged) scales with it and its peak's standard uncertainty is
  // the gauge factor's, 1 %. Drawn for each channel on its own the two halves' errors partly
  // cancel (1/sqrt(2): 0.71 %), understating a lot's error. 400 draws give a standard deviation
  // to sqrt(1/(2·399)) = 3.5 %: ±10 % is three of those.
  constexpr double kGaugeFactorU = 0.01, kDraws = 400, kSpread = 0.1;
  const fs::path dir = temp_dir("shared_gauge_factor");
  nlohmann::json scene = shpb_test::steel_scene();
  // Half bridges, gauge factor 2, 5 V, gain 100: 250 V per unit strain.
  const nlohmann::json bridge = {
      {"arms", 2}, {"gauge_factor", 2.0}, {"excitation", "5 V"}, {"gain", 100}};
  for (auto& ch : scene["measurement"]["channels"]) {
    ch["unit"] = "V";
    ch["bridge"] = bridge;
  }
  scene["measurement"]["uncertainty"] = {{"gauge_factor", "1 %"}, {"shared", {"gauge_factor"}}};
  const fs::path file = shpb_test::write(dir, scene, shpb_test::csv(shpb_test::Record{}, 250.0));
  const auto r = run_shpb({"process", file.string(), "-o", (dir / "out").string(), "--draws",
                           std::to_string(int(kDraws)), "--threads", "2", "-q"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto peak = summary(dir / "out")["uncertainty"]["figures"]["peak_stress_Pa"];
  INFO(peak.dump());
  const double relative =
      peak["standard_uncertainty"].get<double>() / peak["nominal"].get<double>();
  CHECK(relative >= (1 - kSpread) * kGaugeFactorU);
  CHECK(relative <= (1 + kSpread) * kGaugeFactorU);
}

// Each drawn input is named in words (docs/outputs.md, process: summary.json's inputs[]), with the
// scene's JSON path of its uncertainty beside it: before, the name was the scene's key ("channel 0
// (incident) gauge_factor", "incident wave_speed"), which summary.json, the printed line and the
// report's panels showed a reader.
TEST_CASE("process names each uncertain input in words beside the scene key it came from",
          "[app][process][uncertainty]") {
  const fs::path dir = temp_dir("input_names");
  nlohmann::json scene = shpb_test::steel_scene();
  for (auto& ch : scene["measurement"]["channels"]) {
    ch["unit"] = "V";
    ch["bridge"] = {{"arms", 2}, {"gauge_factor", 2.0}, {"excitation", "5 V"}, {"gain", 100}};
  }
  scene["measurement"]["uncertainty"] = {
      {"gauge_factor", "1 %"},
      {"excitation", "0.1 %"},
      {"shared", {"excitation"}},
      {"gauge_position", "1 mm"},
      {"trigger_delay", "0.1 us"},
      {"bars", {{"incident", {{"wave_speed", "0.5 %"}}}, {"specimen", {{"length", "0.01 mm"}}}}}};
  const fs::path file = shpb_test::write(dir, scene, shpb_test::csv(shpb_test::Record{}, 250.0));
  const auto r = run_shpb(
      {"process", file.string(), "-o", (dir / "out").string(), "--draws", "20", "--threads", "2"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const std::string u = "measurement.uncertainty.";
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"gauge factor of channel 0 (gauge incident)", u + "gauge_factor"},
      {"gauge factor of channel 1 (gauge transmitted)", u + "gauge_factor"},
      {"bridge excitation of every channel (one draw)", u + "excitation"},
      {"wave speed of bar incident", u + "bars.incident.wave_speed"},
      {"length of bar specimen", u + "bars.specimen.length"},
      {"distance of gauge incident to the specimen", u + "gauge_position"},
      {"distance of gauge transmitted to the specimen", u + "gauge_position"},
      {"trigger delay of the transmitted record", u + "trigger_delay"}};
  std::vector<std::pair<std::string, std::string>> named;
  const nlohmann::json written = summary(dir / "out");
  for (const auto& i : written["uncertainty"]["inputs"])
    named.emplace_back(i["name"].get<std::string>(), i["key"].get<std::string>());
  CHECK(named == expected);
  // The printed line names the largest contributors so: in words, no scene key.
  const std::string output = r.out + r.err;
  const auto at = output.find("largest contributors: ");
  REQUIRE(at != std::string::npos);
  const std::string contributors = output.substr(at, output.find('\n', at) - at);
  INFO(contributors);
  CHECK(contributors.find('_') == std::string::npos);
}

// The curve bands (docs/methods.md §10) at a strain only where at least 97.5 % of the draws reach
// it: a draw whose loading ends short of a strain has no state there. Its end-of-loading value
// (unloading) used to stand in and pulled the bands' last strains down, the strain rate's lower
// edge below zero (LANL copper: −22 /s at the nominal's last strain, 0.1671; the draws' maximum
// strain has its 95 % interval from 0.1623). The band then ends at the draws' 2.5 % quantile of
// their maximum strain, max_strain's lower 95 % limit, within a sample's strain step.
TEST_CASE("process's curve bands end where the draws' loadings end, not below zero",
          "[app][process][uncertainty]") {
  const fs::path dir = temp_dir("band_end");
  const fs::path scene = kExperiments / "lanl-cu-ofe-273k/scene.json";
  const auto r = run_shpb({"process", scene.string(), "-o", (dir / "out").string(), "--draws",
                           "400", "--threads", "2", "-q"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto strain_interval =
      summary(dir / "out")["uncertainty"]["figures"]["max_strain"]["interval_95"];
  const double lowest_end = strain_interval[0].get<double>();
  // curve.csv as text: a band's cell is empty where the band is undefined.
  std::istringstream in(shpb_test::read_text(dir / "out/curve.csv"));
  std::string line, cell;
  std::getline(in, line);
  std::vector<std::string> names;
  for (std::istringstream h(line); std::getline(h, cell, ',');) names.push_back(cell);
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
  };
  const std::size_t strain = column("strain"), rate_low = column("strain_rate_p2.5_1_s"),
                    stress_low = column("stress_3wave_p2.5_Pa");
  REQUIRE(rate_low < names.size());
  double last_band = 0, previous = 0, step = 0;
  std::size_t rows = 0, banded = 0;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::istringstream f(line);
    while (std::getline(f, cell, ',')) cells.push_back(cell);
    cells.resize(names.size());
    const double e = std::stod(cells[strain]);
    step = std::max(step, e - previous);
    previous = e;
    ++rows;
    if (cells[rate_low].empty()) {
      CHECK(cells[stress_low].empty());
      continue;
    }
    ++banded;
    last_band = std::max(last_band, e);
    INFO("strain " << e);
    CHECK(std::stod(cells[rate_low]) > 0);
    CHECK(std::stod(cells[stress_low]) > 0);
  }
  INFO("rows " << rows << ", with bands " << banded << ", last band at strain " << last_band
               << ", max_strain's 95 % interval from " << lowest_end);
  CHECK(banded < rows);
  CHECK(last_band <= lowest_end + step);
  CHECK(last_band >= lowest_end - step);
}

}  // namespace tests_app_test_process
