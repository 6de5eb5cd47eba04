// `shpb compare` end to end: a simulation compared with itself (its gauges.csv as the scene's
// measurement) gives zero shifts, unit ratios and zero error; the striker velocity inferred from
// its incident plateau is the one it was run with.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "run_shpb.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_app_test_compare {

namespace fs = std::filesystem;
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
