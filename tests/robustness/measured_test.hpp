#pragma once
// A measured test on disk for the robustness cases that need one: a short Kolsky bar whose
// specimen material is a file, simulated into sim/ (a shpb result), and a scene measuring that
// sim/gauges.csv. Also the check every refusal shares: exit 2, one "error:" line saying `says`.
#include <algorithm>
#include <catch2/catch.hpp>
#include <string>

#include "child_process.hpp"

namespace shpb_robust {

constexpr double kMeasuredTestLimit_s = 120.0;  // a hang, not a slow machine

// A Kolsky bar with a bilinear aluminium specimen read from `material` (a file beside the scene)
// and, if `measured` is given, that gauges.csv as its measurement: a test `process`, `fit` and a
// campaign can read.
inline std::string kolsky_scene(const std::string& material, const std::string& measured = "") {
  std::string s = R"({
  "bars": [
    {"name": "striker", "material": "steel", "length": "100 mm", "diameter": "12 mm",
     "velocity": "10 m/s"},
    {"name": "incident", "material": "steel", "length": "600 mm", "diameter": "12 mm",
     "gauges": [{"name": "incident", "position": "300 mm"}]},
    {"name": "specimen", "material": ")" +
                  material + R"(", "length": "4 mm", "diameter": "8 mm"},
    {"name": "transmitter", "material": "steel", "length": "600 mm", "diameter": "12 mm",
     "gauges": [{"name": "transmitted", "position": "300 mm"}]}
  ],
  "specimen": "specimen",
  "materials": {"steel": {"model": "elastic", "density": "7850 kg/m3", "youngs_modulus": "200 GPa",
                          "poisson_ratio": 0.29}},
  "simulation": {"sample_rate": "5 MHz"})";
  if (!measured.empty())
    s += R"(,
  "measurement": {"file": ")" +
         measured + R"(", "time": {"column": "time_s", "unit": "s"},
    "channels": [{"gauge": "incident", "column": "incident", "unit": "strain"},
                 {"gauge": "transmitted", "column": "transmitted", "unit": "strain"}],
    "dispersion": {"correction": "none"}})";
  return s + "\n}\n";
}

inline const char* const kAluminium = R"({"model": "bilinear", "density": "2700 kg/m3",
  "youngs_modulus": "70 GPa", "poisson_ratio": 0.33, "yield_stress": "150 MPa",
  "tangent_modulus": "700 MPa"})";

// In `dir`: aluminium.json, sim.json simulated into sim/ (a shpb result holding gauges.csv), and
// measured.json whose measurement is sim/gauges.csv.
inline void measured_test(const fs::path& dir) {
  fs::create_directories(dir);
  write_bytes(dir / "aluminium.json", kAluminium);
  write_bytes(dir / "sim.json", kolsky_scene("aluminium.json"));
  const Outcome o =
      run({"simulate", (dir / "sim.json").string(), "-o", (dir / "sim").string(), "-q"}, dir,
          kMeasuredTestLimit_s);
  INFO(o.err);
  REQUIRE(o.code == 0);
  write_bytes(dir / "measured.json", kolsky_scene("aluminium.json", "sim/gauges.csv"));
}

// measured_test(dir) twice over: second.json a copy of measured.json, and c.json the campaign of
// the two (tests "one" and "two").
inline void measured_campaign(const fs::path& dir) {
  measured_test(dir);
  fs::copy_file(dir / "measured.json", dir / "second.json");
  write_bytes(dir / "c.json", R"({"tests": [{"scene": "measured.json", "name": "one"},
    {"scene": "second.json", "name": "two"}]})");
}

// One line, exit 2: how every refusal looks.
inline void check_refused(const Outcome& o, const std::string& says) {
  INFO(o.err);
  CHECK(o.code == 2);
  CHECK(o.err.rfind("error: ", 0) == 0);
  CHECK(std::count(o.err.begin(), o.err.end(), '\n') == 1);
  CHECK(o.err.find(says) != std::string::npos);
}

}  // namespace shpb_robust
