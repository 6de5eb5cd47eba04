// `shpb compare` end to end: a simulation compared with itself (its gauges.csv as the scene's
// measurement) gives zero shifts, unit ratios and zero error; the striker velocity inferred from
// its incident plateau is the one it was run with; so it does from a copy altered as lab records
// differ (a bridge's offset, a channel wired the other way), and a record shorter than its pulses
// is said.
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "lab_record.hpp"
#include "run_shpb.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_app_test_compare {

namespace fs = std::filesystem;
using shpb_test::has_warning;
using shpb_test::read_text;
using shpb_test::run_shpb;
using shpb_test::scratch_dir;

namespace {

const fs::path kClassic = fs::path(SHPB_SOURCE_DIR) / "experiments/classic-al6061/scene.json";
constexpr double kStrikerVelocity = 15.0;  // m/s, as the classic scene says
// Sums over a thousand samples of identical signals re-sampled onto the same grid.
constexpr double kRoundOff = 1e-9;
// The window edges make the correlation parabola slightly asymmetric (~1e-5 of a sample here).
constexpr double kShiftTolerance_s = 1e-4 * 1e-7;
// The velocity inferred from the incident plateau (docs/methods.md §4) is the simulated one within
// 1 % (the plateau of a C ≈ 0.98 bar is flat to ~1 %), and every simulated pulse scales with it.
constexpr double kInferredVelocity = 0.01;

// The classic scene with its own simulated gauges as the measurement.
fs::path self_measured_scene(const fs::path& dir) {
  REQUIRE(run_shpb({"simulate", kClassic.string(), "-o", (dir / "sim").string(), "--quiet"}).code ==
          0);
  auto scene = nlohmann::json::parse(read_text(kClassic));
  scene["bars"][2]["material"] = (fs::path(SHPB_SOURCE_DIR) / "specimens/al6061-t6.json").string();
  scene["measurement"] = {
      {"file", (dir / "sim" / "gauges.csv").string()},
      {"time", {{"column", "time_s"}, {"unit", "s"}}},
      {"channels",
       {{{"gauge", "incident"}, {"column", "incident"}, {"unit", "strain"}},
        {{"gauge", "transmitted"}, {"column", "transmitted"}, {"unit", "strain"}}}}};
  const fs::path file = dir / "scene.json";
  std::ofstream(file) << scene.dump(2);
  return file;
}

// The self-measured scene of `dir` reading instead a copy of its gauges altered row by row (the
// incident and the transmitted strain) and ending at `until_s`.
fs::path altered_scene(const fs::path& dir,
                       const std::function<void(double, double&, double&)>& alter,
                       double until_s = 1.0) {
  std::istringstream in(read_text(dir / "sim" / "gauges.csv"));
  std::ofstream out(dir / "altered.csv");
  std::string line;
  std::getline(in, line);
  out << line << "\n";
  while (std::getline(in, line)) {
    double t = 0, inc = 0, tra = 0;
    char comma = 0;
    std::istringstream(line) >> t >> comma >> inc >> comma >> tra;
    if (t > until_s) break;
    alter(t, inc, tra);
    out.precision(17);
    out << t << "," << inc << "," << tra << "\n";
  }
  auto scene = nlohmann::json::parse(read_text(dir / "scene.json"));
  scene["measurement"]["file"] = (dir / "altered.csv").string();
  const fs::path file = dir / "altered.json";
  std::ofstream(file) << scene.dump(2);
  return file;
}

// The self-measured scene's simulated gauges (time, incident, transmitted), row by row, and their
// header.
std::vector<std::array<double, 3>> simulated_rows(const fs::path& dir, std::string& header) {
  std::istringstream in(read_text(dir / "sim" / "gauges.csv"));
  std::vector<std::array<double, 3>> rows;
  std::string line;
  std::getline(in, header);
  while (std::getline(in, line)) {
    std::array<double, 3> v{};
    char comma = 0;
    std::istringstream(line) >> v[0] >> comma >> v[1] >> comma >> v[2];
    rows.push_back(v);
  }
  return rows;
}

// The comparison of `scene` (velocity inferred, no dispersion: the record is a 1D simulation).
nlohmann::json compared(const fs::path& scene, const fs::path& dir) {
  const auto r = run_shpb(
      {"compare", scene.string(), "-o", (dir / "out").string(), "--no-dispersion", "--quiet"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  return nlohmann::json::parse(read_text(dir / "out" / "summary.json"));
}

// The self-measured scene of `dir` reading instead its record `name`.csv, compared.
nlohmann::json compared_record(const fs::path& dir, const std::string& name) {
  auto scene = nlohmann::json::parse(read_text(dir / "scene.json"));
  scene["measurement"]["file"] = (dir / (name + ".csv")).string();
  const fs::path file = dir / (name + ".json");
  std::ofstream(file) << scene.dump(2);
  return compared(file, dir);
}

// The striker velocity and every pulse's plateau ratio (and peak ratio: `peaks`) of the clean
// record, within kInferredVelocity.
void check_clean_figures(const nlohmann::json& summary, bool peaks) {
  CHECK(summary["striker_velocity_m_s"].get<double>() ==
        Approx(kStrikerVelocity).epsilon(kInferredVelocity));
  REQUIRE(summary["pulses"].size() == 3);
  for (const auto& p : summary["pulses"]) {
    INFO(p.dump());
    CHECK(p["plateau_ratio"].get<double>() == Approx(1.0).epsilon(kInferredVelocity));
    if (peaks) CHECK(p["peak_ratio"].get<double>() == Approx(1.0).epsilon(kInferredVelocity));
  }
}

}  // namespace

TEST_CASE("A simulation compared with itself gives zero shifts, unit ratios and zero error",
          "[app][compare]") {
  const fs::path dir = scratch_dir("compare_self");
  const fs::path scene = self_measured_scene(dir);
  const auto r = run_shpb({"compare", scene.string(), "-o", (dir / "out").string(),
                           "--no-dispersion", "--striker-velocity", "15 m/s", "--quiet"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  std::istringstream csv(read_text(dir / "out" / "comparison.csv"));
  std::string line;
  std::getline(csv, line);
  REQUIRE(line ==
          "gauge,pulse,window_start_s,window_end_s,arrival_shift_s,peak_ratio,plateau_ratio,"
          "duration_ratio,rise_time_measured_s,rise_time_simulated_s,nrmse,correlation");
  int rows = 0;
  while (std::getline(csv, line)) {
    INFO(line);
    std::istringstream fields(line);
    std::string gauge, pulse, v;
    std::getline(fields, gauge, ',');
    std::getline(fields, pulse, ',');
    double x[10];
    for (double& value : x) {
      std::getline(fields, v, ',');
      value = std::stod(v);
    }
    CHECK(std::abs(x[2]) < kShiftTolerance_s);       // arrival shift (s)
    CHECK(x[3] == Approx(1.0).epsilon(kRoundOff));   // peak ratio
    CHECK(x[4] == Approx(1.0).epsilon(kRoundOff));   // plateau ratio
    CHECK(x[5] == Approx(1.0).epsilon(kRoundOff));   // duration ratio
    CHECK(x[6] == Approx(x[7]).epsilon(kRoundOff));  // rise times
    CHECK(x[8] < kRoundOff);                         // NRMSE
    CHECK(x[9] == Approx(1.0).epsilon(kRoundOff));   // correlation
    ++rows;
  }
  CHECK(rows == 3);  // incident, reflected, transmitted
  const auto summary = nlohmann::json::parse(read_text(dir / "out" / "summary.json"));
  CHECK(summary["striker_velocity_source"].get<std::string>().rfind("given", 0) == 0);
  CHECK(summary["clock_offset_s"].get<double>() == Approx(0.0).margin(1e-12));
}

TEST_CASE("The striker velocity inferred from the incident plateau is the simulated one",
          "[app][compare]") {
  const fs::path dir = scratch_dir("compare_infer");
  const fs::path scene = self_measured_scene(dir);
  const auto r = run_shpb({"compare", scene.string(), "-o", (dir / "out").string(), "--quiet"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto summary = nlohmann::json::parse(read_text(dir / "out" / "summary.json"));
  CHECK(summary["striker_velocity_source"].get<std::string>().rfind("inferred", 0) == 0);
  // V = c0 ε_I (Z_s + Z_b)/Z_s (docs/methods.md §4); the plateau of a C ≈ 0.98 bar is flat to ~1 %.
  CHECK(summary["striker_velocity_m_s"].get<double>() == Approx(kStrikerVelocity).epsilon(0.01));
}

TEST_CASE("A bridge's offset is no strain: compare measures the pulses from the rest level",
          "[app][compare]") {
  // 3 % of the incident plateau (1.5e-3 strain) added to both channels, as an unbalanced bridge
  // records it: the inferred velocity and every pulse are those of the clean record (its rest
  // level is the offset exactly: the simulated bars are at rest before the pulse).
  const fs::path dir = scratch_dir("compare_offset");
  self_measured_scene(dir);
  constexpr double kOffset = 4.5e-5;
  const auto summary = compared(
      altered_scene(dir, [](double, double& inc, double& tra) { inc += kOffset, tra += kOffset; }),
      dir);
  check_clean_figures(summary, true);
}

TEST_CASE("The rest level is the whole record before the pulse, not its first samples",
          "[app][compare]") {
  // An amplifier settling after the trigger: the record's first 30 µs (the first 5 % the baseline
  // of process reads is 40 µs) sit 3 % of the incident plateau off, the 170 µs after them at rest
  // until the incident pulse arrives (~200 µs). The pulses are those of the clean record.
  const fs::path dir = scratch_dir("compare_settling");
  self_measured_scene(dir);
  constexpr double kSettling = 4.5e-5, kSettlingEnd_s = 30e-6;
  const auto summary = compared(altered_scene(dir,
                                              [](double t, double& inc, double& tra) {
                                                if (t < kSettlingEnd_s)
                                                  inc += kSettling, tra += kSettling;
                                              }),
                                dir);
  check_clean_figures(summary, false);
}

TEST_CASE("A pulse-shaped record with a short pre-trigger reads its rest before the shoulder",
          "[app][compare]") {
  // The classic record's incident front reshaped as a pulse shaper's: a step to 0.47 of the
  // plateau, a shoulder there for 5 us, then a ramp to the plateau over 20 us; the record starts
  // 3 us (30 samples) before that front. Its half-height sample lies on the ramp 6 us after the
  // onset, and the rest level was the median of the record up to it: 30 samples of rest and 60 of
  // shoulder, a level 0.47 of the plateau up, from which the plateau read half its height (the
  // inferred striker velocity 8 m/s for 15). The rest is read before the onset where the rise to
  // half height outlasts it.
  const fs::path dir = scratch_dir("compare_shaped_short_rest");
  self_measured_scene(dir);
  constexpr double kPlateau = 1.5e-3, kStep = 0.47, kShoulder_s = 5e-6, kRamp_s = 20e-6;
  constexpr double kRest_s = 3e-6;
  std::string header;
  const std::vector<std::array<double, 3>> rows = simulated_rows(dir, header);
  // The incident front's first motion: its first sample beyond 1 % of the plateau.
  const auto on = std::find_if(rows.begin(), rows.end(),
                               [&](const auto& v) { return std::abs(v[1]) > 0.01 * kPlateau; });
  REQUIRE(on != rows.end());
  const double t_on = (*on)[0];
  std::ofstream out(dir / "shaped.csv");
  out << header << "\n";
  out.precision(17);
  for (const auto& v : rows) {
    if (v[0] < t_on - kRest_s) continue;
    const double u = v[0] - t_on;
    // The clean front clipped at the step, then the plateau scaled down along the ramp.
    const double inc =
        u < 0             ? v[1]
        : u < kShoulder_s ? std::max(v[1], -kStep * kPlateau)
                          : v[1] * std::min(1.0, kStep + (1 - kStep) * (u - kShoulder_s) / kRamp_s);
    out << v[0] << "," << inc << "," << v[2] << "\n";
  }
  out.close();
  const auto summary = compared_record(dir, "shaped");
  // The plateau's median takes in the ramp's samples above half height, 2 % low at most here.
  constexpr double kShapedPlateau = 0.03;
  CHECK(summary["striker_velocity_m_s"].get<double>() ==
        Approx(kStrikerVelocity).epsilon(kShapedPlateau));
}

TEST_CASE("A sharp front after a short pre-trigger: the rest level is read before its rise",
          "[app][compare]") {
  // The classic record as a 50 MS/s scope holds it (linear between the simulated 10 MHz samples:
  // its front rises to half height over 24 samples), at rest for 10 samples before the front
  // reaches 3 % of the plateau, and ending 150 us later. The rest level was the median up to the
  // half-height sample, 24 of its 34 samples on the rise: a level 12 % of the peak up the front,
  // from which the plateau read short (the inferred striker velocity 13.4 m/s for 15), and the
  // rest before the onset found against it, less one rise, too short to read it again.
  const fs::path dir = scratch_dir("compare_sharp_short_rest");
  self_measured_scene(dir);
  constexpr double kPlateau = 1.5e-3, kScopeDt_s = 2e-8, kRecord_s = 150e-6, kRestEnd = 0.03;
  constexpr int kRestSamples = 10;
  std::string header;
  const std::vector<std::array<double, 3>> rows = simulated_rows(dir, header);
  auto at = [&](double t, int column) {
    const double dt = rows[1][0] - rows[0][0];
    const auto k = std::min(static_cast<std::size_t>(t / dt), rows.size() - 2);
    const double f = (t - rows[k][0]) / dt;
    return rows[k][column] + f * (rows[k + 1][column] - rows[k][column]);
  };
  int front = 0;
  while (std::abs(at(front * kScopeDt_s, 1)) <= kRestEnd * kPlateau) ++front;
  std::ofstream out(dir / "scope.csv");
  out << header << "\n";
  out.precision(17);
  for (int i = front - kRestSamples; i * kScopeDt_s < front * kScopeDt_s + kRecord_s; ++i)
    out << i * kScopeDt_s << "," << (i < front ? 0.0 : at(i * kScopeDt_s, 1)) << ","
        << at(i * kScopeDt_s, 2) << "\n";
  out.close();
  const auto summary = compared_record(dir, "scope");
  CHECK(summary["striker_velocity_m_s"].get<double>() ==
        Approx(kStrikerVelocity).epsilon(kInferredVelocity));
}

TEST_CASE("A channel wired the other way is turned over and said, as process does",
          "[app][compare]") {
  const fs::path dir = scratch_dir("compare_turned");
  self_measured_scene(dir);
  const auto summary =
      compared(altered_scene(dir, [](double, double&, double& tra) { tra = -tra; }), dir);
  CHECK(has_warning(summary, "gauge \"transmitted\": its first pulse is tensile"));
  REQUIRE(summary["pulses"].size() == 3);
  const auto& transmitted = summary["pulses"][2];
  CHECK(transmitted["correlation"].get<double>() == Approx(1.0).epsilon(kInferredVelocity));
  CHECK(transmitted["plateau_ratio"].get<double>() == Approx(1.0).epsilon(kInferredVelocity));
}

TEST_CASE("A record that ends inside its pulses is compared over what it holds, and said",
          "[app][compare]") {
  // The reflected and transmitted pulses reach the classic bars' mid-length gauges ~600 µs after
  // impact and last ~120 µs: a record ending at 700 µs cuts both.
  const fs::path dir = scratch_dir("compare_short_record");
  self_measured_scene(dir);
  constexpr double kRecordEnd_s = 700e-6;
  const auto summary = compared(altered_scene(
                                    dir, [](double, double&, double&) {}, kRecordEnd_s),
                                dir);
  CHECK(summary["pulses"].size() == 3);
  CHECK(has_warning(summary, "the reflected pulse lasts until the record ends"));
  CHECK(has_warning(summary, "the transmitted pulse lasts until the record ends"));
  // A dead transmitted channel: that pulse is not compared, and that is said.
  const fs::path dead = dir / "dead";
  fs::create_directories(dead / "sim");
  fs::copy_file(dir / "sim" / "gauges.csv", dead / "sim" / "gauges.csv");
  fs::copy_file(dir / "scene.json", dead / "scene.json");
  const auto no_pulse =
      compared(altered_scene(dead, [](double, double&, double& tra) { tra = 0; }), dead);
  CHECK(has_warning(no_pulse, "no pulse above the noise: the transmitted pulse is not compared"));
  for (const auto& p : no_pulse["pulses"]) CHECK(p["pulse"] != "transmitted");
}

TEST_CASE("A record that ends before the reflected pulse arrives compares no incident tail as it",
          "[app][compare]") {
  // The classic gauges see the incident pulse from ~200 to ~320 µs after impact and its
  // reflection and the transmitted pulse 2d/c0 = 402 µs after it: a record ending at 500 µs holds
  // neither, only the incident pulse's numerical ringing (a few percent of it), which is no pulse.
  const fs::path dir = scratch_dir("compare_record_before_reflection");
  self_measured_scene(dir);
  constexpr double kRecordEnd_s = 500e-6;
  const auto summary = compared(altered_scene(
                                    dir, [](double, double&, double&) {}, kRecordEnd_s),
                                dir);
  REQUIRE(summary["pulses"].size() == 1);
  CHECK(summary["pulses"][0]["pulse"] == "incident");
  CHECK(has_warning(summary, "no reflected pulse in the record, which ends at"));
  CHECK(has_warning(summary, "no transmitted pulse in the record, which ends at"));
}

TEST_CASE(
    "A reflected pulse whose tail sinks into the rest band is compared over its first part, "
    "and said",
    "[app][compare]") {
  // The classic reflected pulse reaches its gauge ~600 µs after impact and lasts as long as the
  // incident one, ~120 µs; a record at rest from 640 µs on (a decaying pulse's tail within the
  // noise band) holds its first ~40 µs only, under half of it.
  const fs::path dir = scratch_dir("compare_short_reflected");
  self_measured_scene(dir);
  constexpr double kTailFrom_s = 640e-6, kTailTo_s = 800e-6;
  const auto summary = compared(altered_scene(dir,
                                              [&](double t, double& inc, double&) {
                                                if (t > kTailFrom_s && t < kTailTo_s) inc = 0;
                                              }),
                                dir);
  CHECK(summary["pulses"].size() == 3);
  CHECK(has_warning(summary, "the reflected pulse's window"));
  CHECK(has_warning(summary, "its tail lies within the record's rest band"));
}

TEST_CASE("A measurement without dispersion correction is compared with the 1D pulses, as fit does",
          "[app][compare]") {
  // The shipped tension bar's record is a 1D simulation ("dispersion": {"correction": "none"}):
  // its pulses never dispersed, and a dispersed simulation laid over them would not be the test.
  const fs::path dir = scratch_dir("compare_no_correction");
  const auto r = run_shpb(
      {"compare", (fs::path(SHPB_SOURCE_DIR) / "experiments/tension-bonded/scene.json").string(),
       "-o", (dir / "out").string(), "--quiet"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto summary = nlohmann::json::parse(read_text(dir / "out" / "summary.json"));
  CHECK(summary["dispersion"] == false);
}

TEST_CASE("LANL copper: the simulated incident pulse meets the measured one within 5 % and 2 us",
          "[app][compare][measured]") {
  const fs::path dir = scratch_dir("compare_lanl");
  const fs::path scene = fs::path(SHPB_SOURCE_DIR) / "experiments/lanl-cu-ofe-273k/scene.json";
  const auto r = run_shpb({"compare", scene.string(), "-o", (dir / "out").string(), "--quiet"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto summary = nlohmann::json::parse(read_text(dir / "out" / "summary.json"));
  CHECK(summary["dispersion"] == true);
  CHECK(summary["striker_velocity_source"].get<std::string>().rfind("inferred", 0) == 0);
  const auto& incident = summary["pulses"][0];
  REQUIRE(incident["pulse"] == "incident");
  // The measured rise is resolved by the fitted contact rise time: peak (the largest sample) and
  // plateau within 5 %, arrival within 2 µs.
  constexpr double kPeakTolerance = 0.05, kArrivalTolerance_s = 2e-6;
  CHECK(incident["peak_ratio"].get<double>() == Approx(1.0).margin(kPeakTolerance));
  CHECK(incident["plateau_ratio"].get<double>() == Approx(1.0).margin(kPeakTolerance));
  CHECK(std::abs(incident["arrival_shift_s"].get<double>()) < kArrivalTolerance_s);
}

}  // namespace tests_app_test_compare
