// `shpb process` and `compare` on lab records with the traps a new user walks into: gauge
// positions given as the distance to the specimen, time units that do not match the column,
// microstrain declared as strain, hand-set windows between samples, equilibrium that comes and
// goes, fracture, a strain rate without a plateau, simulations shorter than the record. Every
// case runs the executable on a synthetic record whose pulses are known exactly.
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "../skip.hpp"
#include "dispersion/propagation.hpp"
#include "lab_record.hpp"
#include "run_shpb.hpp"
#include "write_xlsx.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_app_test_lab_data {

namespace fs = std::filesystem;
using nlohmann::json;
using shpb_test::clean;
using shpb_test::csv;
using shpb_test::has_warning;
using shpb_test::kDt;
using shpb_test::kSamples;
using shpb_test::read_columns;
using shpb_test::read_text;
using shpb_test::Record;
using shpb_test::run_shpb;
using shpb_test::scratch_dir;
using shpb_test::steel_scene;
using shpb_test::summary;
using shpb_test::trap;
using shpb_test::write;
using shpb_test::write_xlsx;

namespace {

constexpr double kC0 = 5000;  // steel bars: sqrt(200 GPa / 8000 kg/m3)
constexpr double kSpecimenL = 5e-3;

}  // namespace

TEST_CASE("A gauge entered by its distance to the specimen is placed from the specimen face",
          "[app][labdata]") {
  const fs::path d = scratch_dir("labdata_distance");
  json scene = steel_scene();
  scene["bars"][1]["gauges"][0] = {{"name", "incident"}, {"distance_to_specimen", "1 m"}};
  scene["bars"][3]["gauges"][0] = {{"name", "transmitted"}, {"distance_to_specimen", "0.5 m"}};
  const auto r =
      run_shpb({"process", write(d, scene, csv(clean())).string(), "-o", (d / "out").string()});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json s = summary(d / "out");
  CHECK(s["gauge_distances_m"]["incident"].get<double>() == Approx(1.0));
  CHECK(s["gauge_distances_m"]["transmitted"].get<double>() == Approx(0.5));
  // The record matches the geometry: no alignment warning (its noise-free flat tops may be
  // taken for clipping, which is another warning).
  CHECK_FALSE(s["alignment"]["suspect"].get<bool>());
  CHECK(r.err.find("likely") == std::string::npos);
}

TEST_CASE("A gauge 60 mm off is warned about with the right sign and size", "[app][labdata]") {
  // The incident gauge really is 1 m from the specimen; the scene says 1.06 m (a data sheet's
  // distance read as a position from the other end): the reflected pulse comes 2 × 60 mm / c0 =
  // 24 µs before the geometry's time.
  const fs::path d = scratch_dir("labdata_gauge_off");
  json scene = steel_scene();
  scene["bars"][1]["gauges"][0]["position"] = "0.94 m";
  const auto r =
      run_shpb({"process", write(d, scene, csv(clean())).string(), "-o", (d / "out").string()});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json s = summary(d / "out");
  // Onset picking on both pulses (same rise) cancels; a sample of jitter remains.
  constexpr double kOnsetTolerance_s = 2 * kDt;
  CHECK(s["alignment"]["reflected_onset_minus_expected_s"].get<double>() ==
        Approx(-2 * 0.06 / kC0).margin(kOnsetTolerance_s));
  CHECK(s["alignment"]["suspect"].get<bool>());
  CHECK(r.err.find("warning: gauge \"incident\": the reflected pulse starts 24") !=
        std::string::npos);
  // The size said: 60 mm closer, to the half sample (0.25 mm) of onset picking.
  std::smatch m;
  std::string said;  // the alignment warning (a noise-free record also reads as clipped)
  for (const auto& w : s["warnings"])
    if (w.get<std::string>().find("likely") != std::string::npos) said = w.get<std::string>();
  REQUIRE(
      std::regex_search(said, m, std::regex("incident gauge is likely ([0-9.]+) mm closer to")));
  constexpr double kTwoSamples_mm = 2 * (0.5 * kC0 * kDt) * 1e3;  // c0·dt/2 per sample of offset
  CHECK(std::stod(m[1]) == Approx(60).margin(kTwoSamples_mm));
  CHECK(r.err.find(said) != std::string::npos);  // printed as well
  // The transmitted gauge alone 60 mm off (scene 0.56 m, really 0.5 m): 12 µs early. The
  // synthetic record has no specimen transit (~1 µs of the 5 mm specimen), so the size is
  // right to that transit: 5 mm of bar.
  scene = steel_scene();
  scene["bars"][3]["gauges"][0]["position"] = "0.56 m";
  const auto t =
      run_shpb({"process", write(d, scene, csv(clean())).string(), "-o", (d / "out2").string()});
  REQUIRE(t.code == 0);
  const json s2 = summary(d / "out2");
  CHECK(s2["alignment"]["suspect"].get<bool>());
  CHECK(has_warning(s2, "the transmitted gauge is likely 6"));
  CHECK(has_warning(s2, "mm closer to the specimen"));
}

TEST_CASE("A time unit that does not match the column exits 2 before anything is sized from it",
          "[app][labdata]") {
  // The time column named "t": a header without a unit, so only the interval can tell.
  const auto unitless = [](const std::string& text) { return "t" + text.substr(text.find(',')); };
  for (const std::string unit : {"us", "ns"}) {
    CAPTURE(unit);
    const fs::path d = scratch_dir("labdata_unit");
    json scene = steel_scene();
    scene["measurement"]["time"] = {{"column", "t"}, {"unit", unit}};
    const auto start = std::chrono::steady_clock::now();
    const auto r = run_shpb(
        {"process", write(d, scene, unitless(csv(clean()))).string(), "-o", (d / "out").string()});
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    INFO(r.err);
    CHECK(r.code == 2);
    CHECK(r.err.rfind("error: ", 0) == 0);
    CHECK(r.err.find("column \"t\" in \"" + unit + "\"") != std::string::npos);
    CHECK(r.err.find('\n') == r.err.size() - 1);
    CHECK_FALSE(fs::exists(d / "out"));
    INFO("refused in " << seconds << " s");
  }
  // Seconds declared on a column in microseconds: a 0.1 s sample interval.
  const fs::path d = scratch_dir("labdata_unit_s");
  json scene = steel_scene();
  std::string micro = "t,incident,transmitted\n";
  for (int i = 0; i < kSamples; ++i) micro += std::to_string(i * 0.1) + ",0,0\n";
  scene["measurement"]["time"]["column"] = "t";
  const auto r = run_shpb({"process", write(d, scene, micro).string(), "-o", (d / "out").string()});
  CHECK(r.code == 2);
  CHECK(r.err.find("sample interval 0.1 s") != std::string::npos);
  // Seconds declared on a column in milliseconds at 10 MS/s: a 100 µs interval, which a digitizer
  // may have, but the 100 µs incident pulse becomes 0.1 s, 250 round trips 2d/c0 = 0.4 ms of the
  // incident gauge 1 m from the specimen: it would overlap its own reflection.
  const fs::path m = scratch_dir("labdata_unit_ms");
  std::string milli = "t,incident,transmitted\n";
  const Record rec = clean();
  for (int i = 0; i < kSamples; ++i) {
    std::ostringstream row;
    row.precision(17);
    row << i * kDt * 1e3 << "," << rec.incident_gauge(i * kDt) << ","
        << rec.transmitted_gauge(i * kDt) << "\n";
    milli += row.str();
  }
  const auto ms =
      run_shpb({"process", write(m, scene, milli).string(), "-o", (m / "out").string()});
  INFO(ms.err);
  CHECK(ms.code == 2);
  CHECK(ms.err.find("measurement.time.unit: gauge \"incident\": incident pulse") !=
        std::string::npos);
  CHECK(ms.err.find("is the time unit right?") != std::string::npos);
  CHECK(ms.err.find('\n') == ms.err.size() - 1);
  CHECK_FALSE(fs::exists(m / "out"));
  // compare finds the measured pulses by the same rule, and validate refuses what they refuse.
  const auto cmp = run_shpb({"compare", (m / "scene.json").string(), "-o", (m / "cmp").string()});
  INFO(cmp.err);
  CHECK(cmp.code == 2);
  CHECK(cmp.err.find("is the time unit right?") != std::string::npos);
  const auto val = run_shpb({"validate", (m / "scene.json").string()});
  INFO(val.err);
  CHECK(val.code == 2);
  CHECK(val.err.find("is the time unit right?") != std::string::npos);
}

TEST_CASE(
    "A time column whose header gives another unit is refused, where the interval cannot tell",
    "[app][labdata][compare]") {
  // The 10 MHz record with its time in ms ("Time (ms)", as PicoScope or a spreadsheet writes it)
  // and no measurement.time.unit: read as seconds, its 1e-4 ms interval passes for a 10 kHz
  // digitiser's 1e-4 s, and compare stretched the test a thousandfold without a word.
  const fs::path d = scratch_dir("labdata_header_unit");
  std::string text = csv(clean());
  std::ostringstream ms;
  ms.precision(17);
  ms << "Time (ms),incident,transmitted\n";
  std::istringstream in(text.substr(text.find('\n') + 1));
  for (std::string line; std::getline(in, line);) {
    const auto comma = line.find(',');
    ms << std::stod(line.substr(0, comma)) * 1e3 << line.substr(comma) << "\n";
  }
  json scene = steel_scene();
  scene["measurement"].erase("time");
  const auto r = run_shpb(
      {"compare", write(d, scene, ms.str()).string(), "-o", (d / "out").string(), "--quiet"});
  INFO(r.err);
  CHECK(r.code == 2);
  CHECK(r.err.rfind("error: ", 0) == 0);
  CHECK(
      r.err.find("signals.csv: line 1, column 1: \"Time (ms)\": the header gives the time in ms") !=
      std::string::npos);
  CHECK(r.err.find('\n') == r.err.size() - 1);
  CHECK_FALSE(fs::exists(d / "out"));
  // Declared, the same file is read: the unit and the header agree.
  scene["measurement"]["time"] = {{"unit", "ms"}};
  const auto ok = run_shpb({"validate", write(d, scene, ms.str()).string()});
  INFO(ok.err);
  CHECK(ok.code == 0);
}

TEST_CASE("Microstrain declared as strain is warned about, then pulses.csv is written and exit 3",
          "[app][labdata]") {
  const fs::path d = scratch_dir("labdata_microstrain");
  const auto r = run_shpb(
      {"process", write(d, steel_scene(), csv(clean(), 1e6)).string(), "-o", (d / "out").string()});
  INFO(r.err);
  CHECK(r.code == 3);
  const auto warning = r.err.find("warning: gauge \"incident\": implausible strain scale");
  const auto error = r.err.find("error: ");
  CHECK(warning != std::string::npos);
  CHECK(r.err.find("look like microstrain") != std::string::npos);
  CHECK(warning < error);  // said before the failure
  CHECK(r.err.find("engineering strain reached 1") != std::string::npos);
  REQUIRE(fs::exists(d / "out/pulses.csv"));
  CHECK_FALSE(fs::exists(d / "out/curve.csv"));
  const json s = summary(d / "out");
  CHECK(s["error"].get<std::string>().find("engineering strain reached 1") != std::string::npos);
  CHECK(has_warning(s, "implausible strain scale"));
  // The pulses are there, at the faces, in the file's (wrong) scale: incident plateau 1e-3·1e6.
  const auto p = read_columns(d / "out/pulses.csv");
  CHECK(*std::min_element(p[1].begin(), p[1].end()) == Approx(-1e3).epsilon(1e-9));
}

TEST_CASE("Hand-set windows between samples are put on the nearest sample for all three pulses",
          "[app][labdata]") {
  // Fronts of 1 µs (10 samples): a misalignment of one sample is 10 % of the peak on the front.
  const double rise = 1e-6;
  for (const double offset : {0.049e-6, -0.049e-6, 0.0}) {
    CAPTURE(offset);
    const fs::path d = scratch_dir("labdata_windows");
    json scene = steel_scene();
    scene["measurement"]["windows"] = {{"incident", {50e-6 + offset, 150e-6 + offset}},
                                       {"reflected", {450e-6 + offset, 550e-6 + offset}},
                                       {"transmitted", {350e-6 + offset, 450e-6 + offset}}};
    const auto r = run_shpb(
        {"process", write(d, scene, csv(clean(rise))).string(), "-o", (d / "out").string()});
    INFO(r.err);
    REQUIRE(r.code == 0);
    // At the faces all three start at 250 µs (the gauges are 1 m and 0.5 m away, c0 = 5000 m/s).
    const auto p = read_columns(d / "out/pulses.csv");
    double worst = 0;
    for (std::size_t i = 0; i < p[0].size(); ++i) {
      const double t = p[0][i];
      worst = std::max({worst, std::abs(p[1][i] + 1e-3 * trap(t, 250e-6, 100e-6, rise)) / 1e-3,
                        std::abs(p[2][i] - 0.6e-3 * trap(t, 250e-6, 100e-6, rise)) / 0.6e-3,
                        std::abs(p[3][i] + 0.4e-3 * trap(t, 250e-6, 100e-6, rise)) / 0.4e-3});
    }
    // Whole-sample shifts of a sampled trapezoid are exact up to round-off of the time stamps.
    constexpr double kExactShift = 1e-6;
    CHECK(worst < kExactShift);
  }
}

TEST_CASE(
    "Equilibrium is the fraction of the loaded time with R <= 5 % and the interval that "
    "lasts until unloading",
    "[app][labdata]") {
  // Front and back forces agree (R = 0) except 10–40 µs into the pulse, where the transmitted
  // pulse carries an extra 0.1e-3 (R = 2·0.1/0.9 = 0.22): equilibrium is met early, lost, and
  // holds again from ≈ 41.6 µs (where the bump's 2 µs ramp is down to R = 5 %) until unloading.
  Record rec = clean();
  rec.transmitted_gauge = [](double t) {
    return -0.4e-3 * trap(t, 350e-6) - 0.1e-3 * trap(t, 360e-6, 32e-6, 2e-6);
  };
  const fs::path d = scratch_dir("labdata_equilibrium");
  const auto r =
      run_shpb({"process", write(d, steel_scene(), csv(rec)).string(), "-o", (d / "out").string()});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json s = summary(d / "out");
  // R ≤ 5 % again where the bump h satisfies 2h/(0.8 + h) ≤ 0.05 (h ≤ 0.0205e-3) on its way
  // down: 41.59 µs after the pulse starts at the face; the window starts at the detected onset
  // (0.3 µs into the 10 µs front). Tolerance: a sample of onset picking each side.
  constexpr double kEdge_s = 3 * kDt;
  CHECK(s["time_to_equilibrium_s"].get<double>() == Approx(41.59e-6 - 0.3e-6).margin(kEdge_s));
  CHECK(s["equilibrium"]["holds_until_unloading_from_s"].get<double>() ==
        Approx(250e-6 + 41.59e-6).margin(kEdge_s));
  // Loaded (mean force ≥ 20 % of its 0.9e-3·EA peak) from 2.25 µs; the curve ends at the load
  // drop below 50 % of the peak stress (0.8·ramp < 0.45: 94.4 µs). R > 5 % from 10.41 µs
  // (h ≥ 0.0205e-3 on the way up) to 41.59 µs.
  const double loaded = 94.375e-6 - 2.25e-6, out_of_equilibrium = 41.59e-6 - 10.41e-6;
  constexpr double kFractionTolerance = 0.01;  // a few samples at each of four edges
  CHECK(s["equilibrium"]["fraction_of_loaded_time"].get<double>() ==
        Approx(1 - out_of_equilibrium / loaded).margin(kFractionTolerance));
}

TEST_CASE("The curve ends with loading: at a load drop (fracture) or the strain maximum",
          "[app][labdata]") {
  // Fracture 50 µs into the pulse: the transmitted pulse stops and the whole incident pulse is
  // reflected (front force zero) while the faces keep moving apart at 2 c0 ε_I / L.
  // Reflected: 0.6e-3 until 40 µs, ramping to 1e-3 over 40–50 µs, then the incident's shape.
  const Record rec = shpb_test::fractured();
  const fs::path d = scratch_dir("labdata_fracture");
  json scene = steel_scene();
  const auto r =
      run_shpb({"process", write(d, scene, csv(rec)).string(), "-o", (d / "out").string()});
  INFO(r.err);
  REQUIRE(r.code == 0);
  json s = summary(d / "out");
  CHECK(s["end_of_loading"]["how"].get<std::string>().find("load drop") != std::string::npos);
  // 3-wave stress ∝ 0.4e-3 until 40 µs, then (0.4 − 0.4 u')·… falls below half at 45 µs.
  // Strain up to there: rate (c0/L)(1 + ε_R − |ε_T|)/1e3: 1200/s on the plateau, ~0.05.
  const auto c = read_columns(d / "out/curve.csv");
  CHECK(c[0].back() - c[0].front() == Approx(45e-6 - 0.3e-6).margin(3 * kDt));
  const double max_strain = s["max_strain"].get<double>();
  CHECK(max_strain < 0.06);  // the whole record would give 0.15
  CHECK(s["plateau_strain_rate_1_s"].get<double>() == Approx(1200).epsilon(0.01));
  // With the load drop turned off the curve runs to the strain maximum (the end of the pulse).
  scene["measurement"]["load_drop"] = false;
  const auto r2 =
      run_shpb({"process", write(d, scene, csv(rec)).string(), "-o", (d / "out2").string()});
  REQUIRE(r2.code == 0);
  s = summary(d / "out2");
  CHECK(s["end_of_loading"]["how"] == "strain maximum");
  CHECK(s["max_strain"].get<double>() > 0.12);
}

TEST_CASE("A strain rate without a plateau quotes no plateau rate", "[app][labdata]") {
  // A triangular reflected pulse: the rate (c0/L)(|ε_I| + ε_R − |ε_T|) = 600 + 600·triangle
  // 1/s ramps from 600 to 1200 1/s and back, never flat.
  Record rec = clean();
  rec.incident_gauge = [](double t) {
    const double u = (t - 450e-6) / 100e-6;
    const double triangle = u > 0 && u < 1 ? 1 - std::abs(2 * u - 1) : 0;
    return -1e-3 * trap(t, 50e-6) + 0.6e-3 * triangle;
  };
  const fs::path d = scratch_dir("labdata_no_plateau");
  const auto r =
      run_shpb({"process", write(d, steel_scene(), csv(rec)).string(), "-o", (d / "out").string()});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json s = summary(d / "out");
  CHECK(s["plateau_strain_rate_1_s"].is_null());
  CHECK(s["strain_rate"]["plateau_fraction_of_loading"].get<double>() < 0.3);
  CHECK(s["strain_rate"]["mean_over_loading_1_s"].get<double>() > 700);
  CHECK(r.err.find("no plateau") != std::string::npos);
}

TEST_CASE("compare covers the measured pulses by default and warns when a set duration cuts them",
          "[app][labdata][compare]") {
  // The classic bar with its incident gauge 0.2 m from the striker end: the reflected pulse
  // passes it 3.8 m of travel after impact, long after the transmitted pulse has passed the
  // transmitted gauge (0.1 m into the transmitter bar); the default duration waits for the
  // reflected pulse too (model/wave_travel.hpp). The "measurement" is the scene's own
  // simulation, long enough to hold every pulse.
  const fs::path d = scratch_dir("labdata_compare_duration");
  const fs::path source = SHPB_SOURCE_DIR;
  json scene = json::parse(read_text(source / "experiments/classic-al6061/scene.json"));
  scene["bars"][1]["gauges"][0]["position"] = "0.2 m";
  scene["bars"][3]["gauges"][0]["position"] = "0.1 m";
  scene["bars"][2]["material"] = (source / "specimens/al6061-t6.json").string();
  scene["simulation"] = {{"duration", "1100 us"}, {"sample_rate", "10 MHz"}};
  std::ofstream(d / "sim.json") << scene.dump(2);
  REQUIRE(run_shpb({"simulate", (d / "sim.json").string(), "-o", (d / "sim").string(), "--quiet"})
              .code == 0);
  scene["simulation"].erase("duration");
  scene["measurement"] = {
      {"file", (d / "sim/gauges.csv").string()},
      {"time", {{"column", "time_s"}, {"unit", "s"}}},
      {"channels",
       {{{"gauge", "incident"}, {"column", "incident"}, {"unit", "strain"}},
        {{"gauge", "transmitted"}, {"column", "transmitted"}, {"unit", "strain"}}}}};
  std::ofstream(d / "compare.json") << scene.dump(2);
  auto compare = [&](const std::string& out) {
    return run_shpb({"compare", (d / "compare.json").string(), "-o", (d / out).string(),
                     "--no-dispersion", "--quiet"});
  };
  // Default duration (or compare's extension of it): every pulse compared whole (a simulation
  // against itself).
  auto r = compare("default");
  INFO(r.err);
  REQUIRE(r.code == 0);
  json s = summary(d / "default");
  CHECK(s["simulation"]["duration_source"] != "scene");
  // Nothing cut (the set-up's own warning stays: the gauge 0.2 m from the impact end sees the
  // end's reflection overlap the reflected pulse, as validate says).
  CHECK_FALSE(has_warning(s, "ends before"));
  REQUIRE(s["pulses"].size() == 3);
  constexpr double kSelfComparison = 1e-3;  // the same simulation, re-sampled on its own grid
  for (const auto& p : s["pulses"]) {
    CAPTURE(p["pulse"]);
    CHECK(p["duration_ratio"].get<double>() == Approx(1).margin(kSelfComparison));
    CHECK(p["peak_ratio"].get<double>() == Approx(1).margin(kSelfComparison));
  }
  // A duration set too short: the reflected pulse is cut, and that is said.
  scene["simulation"]["duration"] = "600 us";
  std::ofstream(d / "compare.json") << scene.dump(2);
  r = compare("short");
  REQUIRE(r.code == 0);
  s = summary(d / "short");
  CHECK(s["simulation"]["duration_source"] == "scene");
  CHECK(has_warning(s, "before the reflected pulse has passed gauge \"incident\""));
  CHECK(r.err.find("warning: the simulation ends") != std::string::npos);
}

TEST_CASE("process needs no specimen material; volt channels take a strain-per-volt scale",
          "[app][labdata]") {
  const fs::path d = scratch_dir("labdata_friction");
  const auto base = run_shpb({"process", write(d, steel_scene(), csv(clean())).string(), "-o",
                              (d / "strain").string(), "--quiet"});
  REQUIRE(base.code == 0);
  const double peak = summary(d / "strain")["peak_stress_Pa"].get<double>();
  // No specimen material: the geometry is all the reduction uses.
  json scene = steel_scene();
  scene["bars"][2].erase("material");
  auto r = run_shpb({"process", write(d, scene, csv(clean())).string(), "-o",
                     (d / "no-material").string(), "--quiet"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(summary(d / "no-material")["peak_stress_Pa"].get<double>() == Approx(peak).epsilon(1e-12));
  // ... but a simulation does need it: exit 2 naming it.
  r = run_shpb({"simulate", (d / "scene.json").string(), "-o", (d / "sim").string()});
  CHECK(r.code == 2);
  CHECK(r.err.find("bars[2].material: (missing)") != std::string::npos);
  // Volts with a calibration factor: 2.5e-4 strain per volt (4 V at a 1e-3 incident plateau).
  constexpr double kScale = 2.5e-4;
  scene = steel_scene();
  for (auto& ch : scene["measurement"]["channels"]) {
    ch["unit"] = "V";
    ch["scale"] = kScale;
  }
  r = run_shpb({"process", write(d, scene, csv(clean(), 1 / kScale)).string(), "-o",
                (d / "volts").string(), "--quiet"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  // Identical but for the round-off of printing the volts with 17 digits.
  constexpr double kRoundOff = 1e-12;
  CHECK(summary(d / "volts")["peak_stress_Pa"].get<double>() == Approx(peak).epsilon(kRoundOff));
}

TEST_CASE("A bars-together record is checked: Pochhammer-Chree against a plain time shift",
          "[app][labdata][dispersion]") {
  // Two 20 mm steel bars pushed together, gauges 0.5 m into the first and 1.0 m into the
  // second: 2 m apart. The far record is the near pulse (5 µs fronts, the dispersion shows)
  // moved 2 m with Pochhammer–Chree dispersion, as `compare` moves simulated pulses.
  const double distance = 2.0;
  std::vector<double> near(kSamples);
  for (int i = 0; i < kSamples; ++i) near[i] = -1e-3 * trap(i * kDt, 50e-6, 100e-6, 5e-6);
  const shpb::BarWaveguide bar{0.01, kC0, 0.29};
  const std::vector<double> far = shpb::propagate(near, kDt, distance, bar);
  std::ostringstream s;
  s.precision(17);
  s << "time_s,near,far\n";
  for (int i = 0; i < kSamples; ++i) s << i * kDt << "," << near[i] << "," << far[i] << "\n";
  json scene = json::parse(R"({
  "bars": [
    { "name": "a", "material": "steel", "length": "1.5 m", "diameter": "20 mm",
      "gauges": [ { "name": "near", "position": "0.5 m" } ] },
    { "name": "b", "material": "steel", "length": "1.5 m", "diameter": "20 mm",
      "gauges": [ { "name": "far", "position": "1.0 m" } ] }
  ],
  "materials": {
    "steel": { "model": "elastic", "density": 8000, "youngs_modulus": "200 GPa", "poisson_ratio": 0.29 }
  },
  "measurement": {
    "file": "signals.csv", "time": { "column": "time_s", "unit": "s" },
    "channels": [ { "gauge": "near", "column": "near", "unit": "strain" },
                  { "gauge": "far", "column": "far", "unit": "strain" } ]
  }
})");
  const fs::path d = scratch_dir("labdata_bars_together");
  const auto r =
      run_shpb({"process", write(d, scene, s.str()).string(), "-o", (d / "out").string()});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json out = summary(d / "out");
  CHECK(out["distance_m"].get<double>() == Approx(distance));
  const double with = out["rms_of_peak"]["pochhammer_chree"].get<double>();
  const double shift = out["rms_of_peak"]["time_shift"].get<double>();
  WARN("bars together over 2 m: RMS " << 100 * with << " % of peak with Pochhammer-Chree, "
                                      << 100 * shift << " % with a time shift");
  constexpr double kAcceptedRms = 0.005;  // a set-up check passes at 0.5 % of peak
  CHECK(with <= kAcceptedRms);
  CHECK(shift > 2 * with);
  CHECK(fs::exists(d / "out/pulses.csv"));

  // The cut-off given as f·a/c0 is the near bar's, as process takes it on the incident bar
  // (docs/scene-format.md, measurement.dispersion), and the same check as the cut-off in Hz.
  constexpr double kFaOverC0 = 0.15;
  const double hz = kFaOverC0 * kC0 / bar.radius_m;
  scene["measurement"]["dispersion"] = {{"cutoff_fa_c0", kFaOverC0}};
  const fs::path d2 = scratch_dir("labdata_bars_together_fa");
  REQUIRE(
      run_shpb({"process", write(d2, scene, s.str()).string(), "-o", (d2 / "out").string()}).code ==
      0);
  scene["measurement"]["dispersion"] = {{"cutoff", std::to_string(hz) + " Hz"}};
  const fs::path d3 = scratch_dir("labdata_bars_together_hz");
  REQUIRE(
      run_shpb({"process", write(d3, scene, s.str()).string(), "-o", (d3 / "out").string()}).code ==
      0);
  constexpr double kPrinted = 1e-9;  // the Hz value went through a printed decimal
  CHECK(summary(d2 / "out")["cutoff_Hz"].get<double>() == Approx(hz).epsilon(kPrinted));
  CHECK(summary(d2 / "out")["rms_of_peak"]["pochhammer_chree"].get<double>() ==
        Approx(summary(d3 / "out")["rms_of_peak"]["pochhammer_chree"].get<double>())
            .epsilon(kPrinted));

  // The same record from 2 µs into the near pulse's 5 µs front (a scope triggered on the pulse
  // with no pre-trigger): no rest level to read before it, refused as a test's record is.
  std::ostringstream cut;
  cut.precision(17);
  cut << "time_s,near,far\n";
  for (int i = 0; i < kSamples; ++i)
    if (i * kDt >= 52e-6) cut << i * kDt << "," << near[i] << "," << far[i] << "\n";
  const fs::path d4 = scratch_dir("labdata_bars_together_on_front");
  const auto on_front =
      run_shpb({"process", write(d4, scene, cut.str()).string(), "-o", (d4 / "out").string()});
  INFO(on_front.err);
  CHECK(on_front.code == 2);
  CHECK(on_front.err.find("signals.csv: column \"near\"") != std::string::npos);
  CHECK(on_front.err.find("it starts on its first pulse's front") != std::string::npos);
  CHECK(!fs::exists(d4 / "out"));
}

TEST_CASE("The report of a processed test heads with the striker, equilibrium and every warning",
          "[app][labdata][report]") {
  if (!shpb_test::have_matplotlib()) {
    SHPB_SKIP("python3 with matplotlib and numpy not installed: report test skipped");
  }
  const fs::path d = scratch_dir("labdata_report");
  json scene = steel_scene();
  scene["bars"][1]["gauges"][0]["position"] = "0.94 m";  // 60 mm off: a warning to show
  REQUIRE(run_shpb({"process", write(d, scene, csv(clean())).string(), "-o", (d / "out").string(),
                    "--quiet"})
              .code == 0);
  REQUIRE(run_shpb({"report", (d / "out").string()}).code == 0);
  const std::string page = read_text(d / "out/report.html");
  const auto headline = page.find("striker velocity (inferred)</th><td>10 m/s");
  const auto warning = page.find("likely 60");
  const auto details = page.find("<details>");
  CHECK(headline != std::string::npos);
  CHECK(page.find("equilibrium (R ≤ 5 %)") != std::string::npos);
  CHECK(warning != std::string::npos);
  CHECK(warning < details);  // before the full summary
  CHECK(fs::exists(d / "out/figures/raw_signals.png"));
}

TEST_CASE("An .xlsx and an .xls file with the same signals as a CSV give identical results",
          "[app][labdata][excel]") {
  // The clean record at 1 MHz (800 samples): small enough for the committed .xls, made by
  // tests/data/make_signals_xls.pl (Perl Spreadsheet::WriteExcel) from the same formula.
  const double dt = 1e-6;
  const std::string text = csv(clean(), 1.0, dt, 800);
  const fs::path d = scratch_dir("labdata_excel");
  const auto base = run_shpb(
      {"process", write(d, steel_scene(), text).string(), "-o", (d / "csv").string(), "--quiet"});
  REQUIRE(base.code == 0);
  const json ref = summary(d / "csv");
  const auto ref_pulses = read_columns(d / "csv/pulses.csv");
  write_xlsx(d / "signals.xlsx", text);
  fs::copy_file(fs::path(SHPB_SOURCE_DIR) / "tests/data/signals.xls", d / "signals.xls",
                fs::copy_options::overwrite_existing);
  // Numbers in the .xlsx are the CSV's text; the .xls holds doubles computed by Perl from the
  // same formula, equal to the last bit or two.
  for (const auto& [file, tolerance] :
       {std::pair{"signals.xlsx", 0.0}, std::pair{"signals.xls", 1e-12}}) {
    CAPTURE(file);
    json scene = steel_scene();
    scene["measurement"]["file"] = file;
    scene["measurement"]["sheet"] = "signals";
    std::ofstream(d / "scene.json") << scene.dump(2);
    const fs::path out = d / (std::string(file) + "-out");
    const auto r =
        run_shpb({"process", (d / "scene.json").string(), "-o", out.string(), "--quiet"});
    INFO(r.err);
    REQUIRE(r.code == 0);
    const json s = summary(out);
    for (const char* key : {"peak_stress_Pa", "max_strain", "incident_plateau_strain"})
      CHECK(s[key].get<double>() == Approx(ref[key].get<double>()).epsilon(tolerance));
    CHECK(s["windows"] == ref["windows"]);
    const auto p = read_columns(out / "pulses.csv");
    REQUIRE(p[0].size() == ref_pulses[0].size());
    double worst = 0;
    for (std::size_t c = 1; c < 4; ++c)
      for (std::size_t i = 0; i < p[c].size(); ++i)
        worst = std::max(worst, std::abs(p[c][i] - ref_pulses[c][i]));
    CHECK(worst <= tolerance * 1e-3);  // strains of 1e-3
    // A sheet that is not there is named with the ones that are.
    scene["measurement"]["sheet"] = "Signals 2";
    std::ofstream(d / "scene.json") << scene.dump(2);
    const auto bad = run_shpb({"process", (d / "scene.json").string(), "-o", (d / "bad").string()});
    CHECK(bad.code == 2);
    CHECK(bad.err.find(
              "sheet: \"Signals 2\": no such sheet; the workbook has \"notes\", \"signals\"") !=
          std::string::npos);
  }
}

TEST_CASE(
    "Tektronix channels side by side in a workbook sheet: refused as one channel, read as CSV",
    "[app][labdata][excel]") {
  // The clean record at 1 MHz as two Tektronix channel files pasted side by side into one sheet:
  // each block is metadata (columns 0-2, first rows only), time (3) and volts (4).
  const double dt = 1e-6;
  const int samples = 800;
  const Record r = clean();
  std::ostringstream sheet;
  sheet.precision(17);
  const char* meta[][2] = {{"Record Length", "800"}, {"Sample Interval", "1e-06"},
                           {"Trigger Point", "0"},   {"Source", "CH1"},
                           {"Vertical Units", "V"},  {"Horizontal Units", "s"}};
  for (int i = 0; i < samples; ++i) {
    const double t = i * dt;
    const double volts[] = {r.incident_gauge(t), r.transmitted_gauge(t)};
    for (int channel = 0; channel < 2; ++channel) {
      if (i < 6)
        sheet << meta[i][0] << "," << meta[i][1] << ",,";
      else
        sheet << ",,,";
      sheet << t << "," << volts[channel] << (channel == 1 ? "\n" : ",");
    }
  }
  const fs::path d = scratch_dir("labdata_tek_sheet");
  const auto base =
      run_shpb({"process", write(d, steel_scene(), csv(clean(), 1.0, dt, samples)).string(), "-o",
                (d / "csv").string(), "--quiet"});
  REQUIRE(base.code == 0);
  write_xlsx(d / "scope.xlsx", sheet.str());
  json scene = steel_scene();
  scene["measurement"]["file"] = "scope.xlsx";
  scene["measurement"]["sheet"] = "signals";
  scene["measurement"]["channels"][0]["column"] = 4;
  scene["measurement"]["channels"][1]["column"] = 9;
  scene["measurement"]["time"] = {{"unit", "s"}};
  std::ofstream(d / "scene.json") << scene.dump(2);
  auto p = run_shpb({"process", (d / "scene.json").string(), "-o", (d / "auto").string()});
  CHECK(p.code == 2);
  CHECK(p.err.find("\"format\": \"csv\"") != std::string::npos);
  // As the message says: the CSV reader, time in column 3, each channel's volts by index.
  scene["measurement"]["format"] = "csv";
  scene["measurement"]["time"] = {{"column", 3}, {"unit", "s"}};
  std::ofstream(d / "scene.json") << scene.dump(2);
  p = run_shpb({"process", (d / "scene.json").string(), "-o", (d / "sheet").string(), "--quiet"});
  INFO(p.err);
  REQUIRE(p.code == 0);
  const json ref = summary(d / "csv"), s = summary(d / "sheet");
  for (const char* key : {"peak_stress_Pa", "max_strain", "incident_plateau_strain"})
    CHECK(s[key].get<double>() == Approx(ref[key].get<double>()).epsilon(1e-12));
}

TEST_CASE(
    "A TRUE/FALSE cell in an .xlsx record is refused naming its sheet and cell, not read as 1",
    "[app][labdata][excel]") {
  const fs::path d = scratch_dir("labdata_excel_boolean");
  std::vector<std::string> shared;
  const std::string rows = shpb_test::xlsx_rows(csv(clean(), 1.0, 1e-6, 800), shared);
  json scene = steel_scene();
  scene["measurement"]["file"] = "signals.xlsx";
  scene["measurement"]["sheet"] = "signals";
  std::ofstream(d / "scene.json") << scene.dump(2);
  // Cell C300 (transmitted, a sample inside the record) and A2 (the first sample's time) as
  // Excel writes a boolean: t="b", 1 for TRUE and 0 for FALSE.
  for (const auto& [cell, value, shown] :
       {std::tuple{"C300", "1", "TRUE"}, std::tuple{"A2", "0", "FALSE"}}) {
    CAPTURE(cell);
    const std::string open = "<c r=\"" + std::string(cell) + "\">";
    const auto at = rows.find(open);
    REQUIRE(at != std::string::npos);
    std::string changed = rows;
    changed.replace(at, rows.find("</c>", at) + 4 - at,
                    "<c r=\"" + std::string(cell) + "\" t=\"b\"><v>" + value + "</v></c>");
    shpb_test::write_zip(d / "signals.xlsx", shpb_test::xlsx_parts(changed, shared));
    const auto r =
        run_shpb({"process", (d / "scene.json").string(), "-o", (d / "out").string(), "--quiet"});
    INFO(r.err);
    CHECK(r.code == 2);
    CHECK(r.err.find("signals.xlsx: sheet \"signals\", cell " + std::string(cell) + ": " + shown +
                     ": a boolean cell") != std::string::npos);
    CHECK_FALSE(fs::exists(d / "out"));
  }
}

TEST_CASE(
    "\"test\": \"tension\" reduces a tensile record tension positive; a 1-wave/2-wave "
    "disagreement is warned about",
    "[app][labdata]") {
  const fs::path d = scratch_dir("labdata_tension");
  REQUIRE(run_shpb({"process", write(d, steel_scene(), csv(clean())).string(), "-o",
                    (d / "compression").string(), "--quiet"})
              .code == 0);
  const json c = summary(d / "compression");
  // The same test in tension: every strain of opposite sign.
  Record tensile = clean();
  tensile.incident_gauge = [](double t) { return -clean().incident_gauge(t); };
  tensile.transmitted_gauge = [](double t) { return -clean().transmitted_gauge(t); };
  json scene = steel_scene();
  scene["measurement"]["test"] = "tension";
  auto r =
      run_shpb({"process", write(d, scene, csv(tensile)).string(), "-o", (d / "tension").string()});
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.err.find("disagree") == std::string::npos);  // (noise-free flat tops read as clipped)
  const json t = summary(d / "tension");
  CHECK(t["test"] == "tension");
  constexpr double kRoundOff = 1e-12;
  CHECK(t["peak_stress_Pa"].get<double>() ==
        Approx(c["peak_stress_Pa"].get<double>()).epsilon(kRoundOff));
  CHECK(t["max_strain"].get<double>() == Approx(c["max_strain"].get<double>()).epsilon(kRoundOff));
  // Tensile true values: ln(1 + e) and σ(1 + e); the pulses keep the record's signs.
  const auto curve = read_columns(d / "tension/curve.csv");
  const std::size_t last = curve[0].size() - 1;
  CHECK(curve[6][last] == Approx(std::log1p(curve[2][last])).epsilon(kRoundOff));
  CHECK(curve[7][last] == Approx(curve[5][last] * (1 + curve[2][last])).epsilon(kRoundOff));
  const auto p = read_columns(d / "tension/pulses.csv");
  CHECK(*std::max_element(p[1].begin(), p[1].end()) == Approx(1e-3));  // tensile incident
  // A record whose transmitted pulse is a third of what the front face carries: the 1- and
  // 2-wave stresses disagree threefold (0.133e-3 against 0.4e-3 of bar strain).
  Record mixed = clean();
  mixed.transmitted_gauge = [](double t) { return clean().transmitted_gauge(t) / 3; };
  r = run_shpb(
      {"process", write(d, steel_scene(), csv(mixed)).string(), "-o", (d / "mixed").string()});
  REQUIRE(r.code == 0);
  CHECK(has_warning(summary(d / "mixed"), "the 1-wave and 2-wave stresses disagree"));
  CHECK(r.err.find("ratio 3") != std::string::npos);
}

TEST_CASE("A simulated tension test with bonded specimen interfaces is processed back to its law",
          "[app][labdata][tension]") {
  const fs::path d = scratch_dir("labdata_tension_law");
  const fs::path source = SHPB_SOURCE_DIR;
  json scene = json::parse(read_text(source / "experiments/tension-bonded/scene.json"));
  std::ofstream(d / "scene.json") << scene.dump(2);
  auto r =
      run_shpb({"simulate", (d / "scene.json").string(), "-o", (d / "sim").string(), "--quiet"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  // The bonded interfaces carried tension (negative contact force) at the specimen.
  const auto interfaces = read_columns(d / "sim/interfaces.csv");
  CHECK(*std::min_element(interfaces[3].begin(), interfaces[3].end()) < 0);
  // The record the experiment ships (data/gauges.csv) is this run's: equal to round-off of the
  // strains (1e-3), whatever the compiler's floating-point contraction.
  {
    constexpr double kRecordRoundOff = 1e-12;
    const auto fresh = read_columns(d / "sim/gauges.csv");
    const auto kept = read_columns(source / "experiments/tension-bonded/data/gauges.csv");
    REQUIRE(kept.size() == fresh.size());
    REQUIRE(kept[0].size() == fresh[0].size());
    double worst = 0;
    for (std::size_t c = 1; c < fresh.size(); ++c)
      for (std::size_t i = 0; i < fresh[c].size(); ++i)
        worst = std::max(worst, std::abs(kept[c][i] - fresh[c][i]));
    CHECK(worst <= kRecordRoundOff);
  }
  scene["measurement"]["file"] = (d / "sim/gauges.csv").string();
  std::ofstream(d / "scene.json") << scene.dump(2);
  r = run_shpb({"process", (d / "scene.json").string(), "-o", (d / "out").string(), "--quiet"});
  REQUIRE(r.code == 0);
  CHECK(summary(d / "out")["test"] == "tension");
  // The scene's bilinear law: σ = Y + E_t (ε − Y/E) beyond yield (E 70 GPa, Y 300 MPa, E_t 2 GPa)
  // in true stress and logarithmic strain (the simulator's finite strain), against the processed
  // true 3-wave stress and true strain where the specimen is in equilibrium (R ≤ 5 %) and plastic
  // (ε > 3 Y/E). The step-fronted pulse rings the specimen up, so single samples scatter more
  // (2.7 % at worst); their RMS is the figure.
  constexpr double kE = 70e9, kY = 300e6, kEt = 2e9;
  constexpr double kLawRms = 0.02;
  const auto c = read_columns(d / "out/curve.csv");
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < c[0].size(); ++i) {
    const double e = c[6][i], stress = c[7][i], ratio = c[8][i];
    if (ratio > 0.05 || e < 3 * kY / kE) continue;
    const double law = kY + kEt * (e - kY / kE);
    sum += (stress - law) * (stress - law) / (law * law);
    ++n;
  }
  REQUIRE(n > 20);
  const double rms = std::sqrt(sum / static_cast<double>(n));
  WARN("tension: 3-wave stress against the bilinear law, RMS " << 100 * rms << " % over " << n
                                                               << " samples in equilibrium");
  CHECK(rms < kLawRms);
}

}  // namespace tests_app_test_lab_data
