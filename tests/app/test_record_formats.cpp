// `shpb process` on the simulated tension record of experiments/tension-bonded re-recorded as other
// labs' instruments and exports write it: an 8-bit scope (quantised, and clipped), a jittered time
// base, a TranAX-style export (each line one quoted field, CR line ends, decimal commas). Every
// case runs the executable and is judged against the same record read as shipped.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "lab_record.hpp"
#include "run_shpb.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_app_test_record_formats {

namespace fs = std::filesystem;
using nlohmann::json;
using shpb_test::has_warning;
using shpb_test::read_columns;
using shpb_test::read_text;
using shpb_test::run_shpb;
using shpb_test::scratch_dir;
using shpb_test::summary;

namespace {

const fs::path kExperiment = fs::path(SHPB_SOURCE_DIR) / "experiments/tension-bonded";

// time_s, incident, transmitted of the shipped record.
std::vector<std::vector<double>> shipped() { return read_columns(kExperiment / "data/gauges.csv"); }

void write_csv(const fs::path& file, const std::vector<std::vector<double>>& cols) {
  std::ofstream out(file);
  out.precision(17);
  out << "time_s,incident,transmitted\n";
  for (std::size_t i = 0; i < cols[0].size(); ++i)
    out << cols[0][i] << "," << cols[1][i] << "," << cols[2][i] << "\n";
}

// The experiment's scene reading `signals` (relative to the scene's folder `dir`).
fs::path scene_reading(const fs::path& dir, const std::string& signals) {
  json scene = json::parse(read_text(kExperiment / "scene.json"));
  scene["measurement"]["file"] = signals;
  std::ofstream(dir / "scene.json") << scene.dump(2);
  return dir / "scene.json";
}

// An 8-bit digitizer of range ±range: 256 levels, values beyond the range held at its ends.
std::vector<double> digitize(const std::vector<double>& x, double range) {
  const double lsb = 2 * range / 256;
  std::vector<double> q(x.size());
  for (std::size_t i = 0; i < x.size(); ++i)
    q[i] = std::clamp(std::round(x[i] / lsb), -128.0, 127.0) * lsb;
  return q;
}

double peak_abs(const std::vector<double>& x) {
  double p = 0;
  for (double v : x) p = std::max(p, std::abs(v));
  return p;
}

// Longest run of samples equal to the record's maximum or minimum.
std::size_t longest_run_at_extreme(const std::vector<double>& x) {
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  std::size_t longest = 0;
  for (const double e : {*lo, *hi}) {
    std::size_t run = 0;
    for (double v : x) longest = std::max(longest, run = v == e ? run + 1 : 0);
  }
  return longest;
}

}  // namespace

TEST_CASE("A tension record's raw_signals.csv keeps the record's signs",
          "[app][process][tension]") {
  const fs::path d = scratch_dir("formats_tension_raw");
  const auto r = run_shpb(
      {"process", (kExperiment / "scene.json").string(), "-o", (d / "out").string(), "--quiet"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  // The channels are strain, not inverted: raw_signals.csv is the record as read, tension
  // positive — the incident pulse of a tension bar is tensile (+1e-3 = V/2c0).
  const auto record = shipped();
  const auto raw = read_columns(d / "out/raw_signals.csv");
  REQUIRE(raw.size() == 3);
  REQUIRE(raw[0].size() == record[0].size());
  constexpr double kPrintRoundOff = 1e-12;  // 17-digit text both ways
  for (std::size_t c = 1; c < 3; ++c)
    for (std::size_t i = 0; i < raw[c].size(); ++i)
      REQUIRE(raw[c][i] == Approx(record[c][i]).margin(kPrintRoundOff * 1e-3));
  // The first pulse past half the incident amplitude V/2c0 = 1e-3 is the tensile incident one.
  const auto first =
      std::find_if(raw[1].begin(), raw[1].end(), [](double x) { return std::abs(x) > 0.5e-3; });
  REQUIRE(first != raw[1].end());
  CHECK(*first > 0);
}

TEST_CASE("An 8-bit record is not called clipped; a record cut by its range is",
          "[app][process][clipping]") {
  const fs::path d = scratch_dir("formats_clipping");
  const auto record = shipped();
  // A scope set just above each channel's peak (2 % headroom). The transmitted pulse of the
  // hardening specimen rises slowly to its top: it stays on the top level for tens of samples,
  // but no longer than on the level below (no pile-up).
  constexpr double kHeadroom = 1.02;
  auto quantised = record;
  for (std::size_t c = 1; c < 3; ++c)
    quantised[c] = digitize(record[c], kHeadroom * peak_abs(record[c]));
  // The trap: several samples running at the extreme level, as on a clipped record.
  CHECK(std::max(longest_run_at_extreme(quantised[1]), longest_run_at_extreme(quantised[2])) >= 8);
  write_csv(d / "quantised.csv", quantised);
  auto r = run_shpb({"process", scene_reading(d, "quantised.csv").string(), "-o",
                     (d / "quantised").string(), "--quiet"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.err.find("clipped") == std::string::npos);
  CHECK_FALSE(has_warning(summary(d / "quantised"), "clipped"));
  // The same scope with the incident channel's range at 80 % of its peak: the tensile incident
  // plateau is cut and piles up at the top level.
  constexpr double kCutRange = 0.8;
  auto clipped = record;
  clipped[1] = digitize(record[1], kCutRange * peak_abs(record[1]));
  clipped[2] = quantised[2];
  write_csv(d / "clipped.csv", clipped);
  r = run_shpb({"process", scene_reading(d, "clipped.csv").string(), "-o", (d / "clipped").string(),
                "--quiet"});
  REQUIRE(r.code == 0);
  CHECK(has_warning(summary(d / "clipped"), "gauge \"incident\""));
  CHECK(has_warning(summary(d / "clipped"), "clipped"));
  CHECK_FALSE(has_warning(summary(d / "clipped"), "gauge \"transmitted\""));
}

// The incident channel digitized on 8 bits at ±80 % of its peak: its tensile plateau is cut and
// held at the top code, with no noise to tell it from a flat top ("may be clipped" at most). Its
// stated range settles it (docs/scene-format.md, measurement.channels[].range): at the range the
// plateau is clipped, its samples bounds; stated twice as wide, the same flat top lies far inside
// the range and is no clip.
TEST_CASE("A channel's stated range settles whether its record is clipped",
          "[app][process][clipping]") {
  const fs::path d = scratch_dir("formats_range");
  const auto record = shipped();
  constexpr double kCutRange = 0.8;
  const double range = kCutRange * peak_abs(record[1]);
  auto cut = record;
  cut[1] = digitize(record[1], range);
  write_csv(d / "cut.csv", cut);
  for (const double stated : {range, 2 * range}) {
    INFO("stated range " << stated);
    json scene = json::parse(read_text(scene_reading(d, "cut.csv")));
    scene["measurement"]["channels"][0]["range"] = stated;
    std::ofstream(d / "ranged.json") << scene.dump(2);
    const fs::path out = d / (stated == range ? "at" : "inside");
    const auto r =
        run_shpb({"process", (d / "ranged.json").string(), "-o", out.string(), "--quiet"});
    INFO(r.err);
    REQUIRE(r.code == 0);
    CHECK(has_warning(summary(out), "looks clipped") == (stated == range));
    CHECK_FALSE(has_warning(summary(out), "may be clipped"));
  }
  // A range whose ends are reversed, or a voltage for a column in strain: exit 2 naming the key.
  for (const json& bad : {json::array({2 * range, range}), json("5 V")}) {
    INFO("range " << bad.dump());
    json scene = json::parse(read_text(d / "scene.json"));
    scene["measurement"]["channels"][0]["range"] = bad;
    std::ofstream(d / "bad.json") << scene.dump(2);
    const auto r =
        run_shpb({"process", (d / "bad.json").string(), "-o", (d / "bad").string(), "--quiet"});
    CHECK(r.code == 2);
    CHECK(r.err.find("measurement.channels[0].range") != std::string::npos);
    CHECK_FALSE(fs::exists(d / "bad"));
  }
}

TEST_CASE("A channel read twice is said by process and compare", "[app][process][compare]") {
  // The transmitted column replaced by the incident one times 1.7 (one channel exported under two
  // names, or mapped twice with another bridge factor), and by its negative. Two gauges on a bar
  // record different pulses: the shipped record draws no such warning.
  const fs::path d = scratch_dir("formats_copied");
  const auto record = shipped();
  for (const double scale : {1.7, -1.0}) {
    INFO("transmitted = " << scale << " x incident");
    auto copied = record;
    for (std::size_t i = 0; i < record[1].size(); ++i) copied[2][i] = scale * record[1][i];
    write_csv(d / "copied.csv", copied);
    const fs::path scene = scene_reading(d, "copied.csv");
    for (const char* command : {"process", "compare"}) {
      const fs::path out = d / (std::string(command) + (scale < 0 ? "-inverted" : ""));
      const auto r = run_shpb({command, scene.string(), "-o", out.string(), "--quiet"});
      INFO(command << ": " << r.err);
      REQUIRE(r.code == 0);
      CHECK(has_warning(summary(out), "hold the same record"));
    }
  }
  const auto r = run_shpb(
      {"process", (kExperiment / "scene.json").string(), "-o", (d / "shipped").string(), "-q"});
  REQUIRE(r.code == 0);
  CHECK_FALSE(has_warning(summary(d / "shipped"), "hold the same record"));
}

TEST_CASE("A jittered time base is resampled onto a uniform grid, with a warning",
          "[app][process][timebase]") {
  const fs::path d = scratch_dir("formats_jitter");
  const auto record = shipped();
  // The record read every 1010 ns on a uniform clock, and the same record stamped with steps
  // alternating 998 / 1022 ns (an export's clock jitter, 1.2 % of the step), whose mean is 1010 ns.
  auto at = [&](double t, std::size_t c) {
    const double dt = record[0][1] - record[0][0];
    const auto i = static_cast<std::size_t>(t / dt);
    const double f = t / dt - static_cast<double>(i);
    return record[c][i] + f * (record[c][i + 1] - record[c][i]);
  };
  std::vector<std::vector<double>> uniform(3), jittered(3);
  double t = 0;
  for (std::size_t k = 0; t + 1.1e-6 < record[0].back(); ++k) {
    uniform[0].push_back(static_cast<double>(k) * 1010e-9);
    jittered[0].push_back(t);
    for (std::size_t c = 1; c < 3; ++c) {
      uniform[c].push_back(at(uniform[0].back(), c));
      jittered[c].push_back(at(t, c));
    }
    t += k % 2 ? 1022e-9 : 998e-9;
  }
  if (jittered[0].size() % 2 == 0)  // an even number of steps: their mean is 1010 ns exactly
    for (auto* cols : {&uniform, &jittered})
      for (auto& c : *cols) c.pop_back();
  write_csv(d / "uniform.csv", uniform);
  write_csv(d / "jittered.csv", jittered);
  auto r = run_shpb({"process", scene_reading(d, "uniform.csv").string(), "-o",
                     (d / "uniform").string(), "--quiet"});
  REQUIRE(r.code == 0);
  r = run_shpb({"process", scene_reading(d, "jittered.csv").string(), "-o",
                (d / "jittered").string(), "--quiet"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json u = summary(d / "uniform"), j = summary(d / "jittered");
  CHECK(has_warning(j, "resampled (linear) onto a uniform grid"));
  CHECK(r.err.find("1.01e-06 s") != std::string::npos);  // the interval used
  CHECK(j["signals"]["sample_interval_s"].get<double>() == Approx(1010e-9).epsilon(1e-9));
  // Resampling moves each sample by at most 12 ns (1.2 % of a step) along a front that rises
  // over ~10 µs: the reduction agrees to well within 1 %.
  constexpr double kResampling = 0.01;
  for (const char* key : {"peak_stress_Pa", "max_strain", "incident_plateau_strain"})
    CHECK(j[key].get<double>() == Approx(u[key].get<double>()).epsilon(kResampling));
  // Asked not to resample, the record is refused with the way forward.
  json scene = json::parse(read_text(d / "scene.json"));
  scene["measurement"]["time"]["resample"] = false;
  std::ofstream(d / "scene.json") << scene.dump(2);
  r = run_shpb({"process", (d / "scene.json").string(), "-o", (d / "refused").string()});
  CHECK(r.code == 2);
  CHECK(r.err.find("\"resample\": true") != std::string::npos);
  // Asked to, onto a given interval: 1 us.
  scene["measurement"]["time"]["resample"] = "1 us";
  std::ofstream(d / "scene.json") << scene.dump(2);
  r = run_shpb({"process", (d / "scene.json").string(), "-o", (d / "onto").string(), "--quiet"});
  REQUIRE(r.code == 0);
  CHECK(summary(d / "onto")["signals"]["sample_interval_s"].get<double>() ==
        Approx(1e-6).epsilon(1e-9));
  // A missing sample (one step of 2 us) is a gap, not jitter: refused by default.
  auto gap = uniform;
  for (auto& c : gap) c.erase(c.begin() + 300);
  write_csv(d / "gap.csv", gap);
  r = run_shpb({"process", scene_reading(d, "gap.csv").string(), "-o", (d / "gap").string()});
  CHECK(r.code == 2);
  CHECK(r.err.find("gap or jump") != std::string::npos);
}

TEST_CASE("A TranAX-style export (quoted lines, CR line ends, decimal commas) is read",
          "[app][process][csv]") {
  const fs::path d = scratch_dir("formats_tranax");
  const auto record = shipped();
  // The same 11 significant digits written twice: as the export (each line quoted whole, tab
  // separated, decimal commas, CR line ends) and as a plain CSV.
  {
    std::ofstream out(d / "export.csv", std::ios::binary), plain(d / "plain.csv");
    out << "\"Time [s]\tincident\ttransmitted\"\r";
    plain << "time_s,incident,transmitted\n";
    char line[200];
    for (std::size_t i = 0; i < record[0].size(); ++i) {
      std::snprintf(line, sizeof line, "%.10E,%.10E,%.10E", record[0][i], record[1][i],
                    record[2][i]);
      plain << line << "\n";
      std::string s = line;
      std::replace(s.begin(), s.end(), ',', '\t');
      std::replace(s.begin(), s.end(), '.', ',');
      out << "\"" << s << "\"\r";
    }
  }
  json scene = json::parse(read_text(kExperiment / "scene.json"));
  scene["measurement"]["file"] = "export.csv";
  scene["measurement"]["time"] = {{"column", "Time [s]"}, {"unit", "s"}};
  std::ofstream(d / "scene.json") << scene.dump(2);
  auto r =
      run_shpb({"process", (d / "scene.json").string(), "-o", (d / "export").string(), "--quiet"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  r = run_shpb(
      {"process", scene_reading(d, "plain.csv").string(), "-o", (d / "plain").string(), "--quiet"});
  REQUIRE(r.code == 0);
  // The same numbers: the same reduction, to the last bit.
  const json e = summary(d / "export"), p = summary(d / "plain");
  for (const char* key : {"peak_stress_Pa", "max_strain", "incident_plateau_strain"})
    CHECK(e[key].get<double>() == p[key].get<double>());
  // Where no row is numbers, the message says what was read and the likely cause.
  std::ofstream(d / "bars.csv") << "time|incident|transmitted\n0|0|0\n1e-7|0|0\n";
  std::ofstream(d / "blanks.csv") << "time incident transmitted\n0,0 0,0 0,0\n1,0E-7 0,0 0,0\n";
  for (const auto& [file, cause] :
       {std::pair{"bars.csv", "the whole line is one field \"1e-7|0|0\""},
        std::pair{"blanks.csv", "blank-separated numbers with decimal commas"}}) {
    scene["measurement"]["file"] = file;
    scene["measurement"]["time"] = {{"column", 0}, {"unit", "s"}};
    scene["measurement"]["channels"][0]["column"] = 1;
    scene["measurement"]["channels"][1]["column"] = 2;
    std::ofstream(d / "scene.json") << scene.dump(2);
    r = run_shpb({"process", (d / "scene.json").string(), "-o", (d / "bad").string()});
    CAPTURE(file);
    CHECK(r.code == 2);
    CHECK(r.err.find("no numeric rows") != std::string::npos);
    CHECK(r.err.find(cause) != std::string::npos);
  }
}

}  // namespace tests_app_test_record_formats
