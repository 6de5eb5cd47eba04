#pragma once
// The classic experiment's simulated gauges as a measured record: the scene that reads a file of
// them, the record itself, and the checks that a file read so gives the curve of the same record
// read with its time column (test_record_time_base.cpp, test_instrument_exports.cpp).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "lab_record.hpp"
#include "run_shpb.hpp"

namespace shpb_test::classic {

namespace fs = std::filesystem;
using nlohmann::json;

inline const fs::path kSource = SHPB_SOURCE_DIR;

// The same samples on the same clock: the curves agree to round-off. The timed record's interval
// is its stamps' mean step and the untimed one's the scene's, equal to their last bits, so the
// stress differs by far less than this fraction of its peak (0 measured).
inline constexpr double kSameRecord = 1e-9;
// A start given to the record moves every time by it, to round-off of the times (µs at 1e-20 s).
inline constexpr double kSameTime_s = 1e-15;

// The classic experiment (its specimen file named from anywhere) measured by `file`, the channels
// by `incident` and `transmitted` in `unit` (volts read at one strain per volt), with `time` as
// measurement.time (none if null) and `extra` merged into the measurement. Written to dir/name;
// returns its path.
inline fs::path classic_reading(const fs::path& dir, const std::string& name, const fs::path& file,
                                const json& time, const json& incident = "incident",
                                const json& transmitted = "transmitted",
                                const std::string& unit = "strain",
                                const json& extra = json::object()) {
  json scene = json::parse(read_text(kSource / "experiments/classic-al6061/scene.json"));
  scene["bars"][2]["material"] = (kSource / "specimens/al6061-t6.json").string();
  json channels = {{{"gauge", "incident"}, {"column", incident}, {"unit", unit}},
                   {{"gauge", "transmitted"}, {"column", transmitted}, {"unit", unit}}};
  if (unit == "V")
    for (auto& c : channels) c["scale"] = 1.0;
  scene["measurement"] = {
      {"file", file.string()},
      {"channels", channels},
      {"dispersion", {{"correction", "none"}}}};  // the 1D model does not disperse
  if (!time.is_null()) scene["measurement"]["time"] = time;
  scene["measurement"].update(extra);
  std::ofstream(dir / name) << scene.dump(2);
  return dir / name;
}

// The classic experiment simulated into dir/sim: gauges.csv (time_s, incident, transmitted).
inline std::vector<std::vector<double>> simulated(const fs::path& dir) {
  json scene = json::parse(read_text(kSource / "experiments/classic-al6061/scene.json"));
  scene["bars"][2]["material"] = (kSource / "specimens/al6061-t6.json").string();
  std::ofstream(dir / "sim.json") << scene.dump(2);
  REQUIRE(run_shpb({"simulate", (dir / "sim.json").string(), "-o", (dir / "sim").string(), "-q"})
              .code == 0);
  return read_columns(dir / "sim/gauges.csv");
}

// The record's rows, `between[k]` written before column k + 1 (",": the next column) and `end`
// after the last, 17 digits.
inline std::string record_rows(const std::vector<std::vector<double>>& rec,
                               const std::vector<std::string>& between = {",", ","},
                               const std::string& end = "\n") {
  std::ostringstream s;
  s.precision(17);
  for (std::size_t i = 0; i < rec[0].size(); ++i) {
    s << rec[0][i];
    for (std::size_t k = 1; k < rec.size(); ++k) s << between[k - 1] << rec[k][i];
    s << end;
  }
  return s.str();
}

inline RunResult process(const fs::path& scene, const fs::path& out) {
  return run_shpb({"process", scene.string(), "-o", out.string(), "--quiet"});
}

// `process` that must succeed.
inline void processed(const fs::path& scene, const fs::path& out) {
  const RunResult r = process(scene, out);
  INFO(r.err);
  REQUIRE(r.code == 0);
}

// curve.csv of `out` against the timed record's `ref`: the same rows, times later by `shift_s`
// (within `time_tolerance_s`), the 3-wave stress and the strain the same.
inline void check_same_curve(const fs::path& ref, const fs::path& out, double shift_s,
                             double time_tolerance_s = kSameTime_s) {
  const auto a = read_table(ref / "curve.csv");
  const auto b = read_table(out / "curve.csv");
  const auto& sa = a["stress_3wave_Pa"];
  const auto& sb = b["stress_3wave_Pa"];
  REQUIRE(sa.size() == sb.size());
  const double peak = summary(ref)["peak_stress_Pa"].get<double>();
  double stress_off = 0, time_off = 0, strain_off = 0;
  for (std::size_t i = 0; i < sa.size(); ++i) {
    stress_off = std::max(stress_off, std::abs(sa[i] - sb[i]));
    time_off = std::max(time_off, std::abs(b["time_s"][i] - a["time_s"][i] - shift_s));
    strain_off = std::max(strain_off, std::abs(a["strain"][i] - b["strain"][i]));
  }
  CHECK(stress_off <= kSameRecord * peak);
  CHECK(time_off <= time_tolerance_s);
  CHECK(strain_off <= kSameRecord * summary(ref)["max_strain"].get<double>());
  CHECK(summary(out)["peak_stress_Pa"].get<double>() ==
        Approx(peak).epsilon(kSameRecord).margin(0));
}

// A refusal: exit 2 and one line saying each of `said`.
inline void check_refused(const RunResult& r, const std::vector<std::string>& said) {
  INFO(r.err);
  CHECK(r.code == 2);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  for (const auto& s : said) CHECK(r.err.find(s) != std::string::npos);
}

}  // namespace shpb_test::classic
