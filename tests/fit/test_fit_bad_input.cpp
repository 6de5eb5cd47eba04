// shpb fit with bad campaign files: exit 2, one line naming the file and the JSON path, and no
// output folder written (docs/commands.md). `process --campaign` judges the fit's keys of the same
// file the same way (a campaign file is one file for both commands).
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../app/run_shpb.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_fit_test_fit_bad_input {

namespace fs = std::filesystem;
using shpb_test::run_shpb;

namespace {

// A scene with a measurement (its CSV is never opened when the campaign is rejected first) and
// one without.
void write_scenes(const fs::path& dir) {
  const std::string bars = R"(
    "bars": [
      {"name": "striker", "material": "steel", "length": "0.2 m", "diameter": "20 mm", "velocity": "10 m/s"},
      {"name": "incident", "material": "steel", "length": "1 m", "diameter": "20 mm",
       "gauges": [{"name": "incident", "position": "0.5 m"}]},
      {"name": "specimen", "material": ")" +
                           (fs::path(SHPB_SOURCE_DIR) / "specimens/ofhc-copper.json").string() +
                           R"(",
       "length": "5 mm", "diameter": "10 mm"},
      {"name": "transmitter", "material": "steel", "length": "1 m", "diameter": "20 mm",
       "gauges": [{"name": "transmitted", "position": "0.5 m"}]}],
    "specimen": "specimen",
    "materials": {"steel": {"model": "elastic", "density": "7850 kg/m3", "youngs_modulus": "200 GPa",
                            "poisson_ratio": 0.29}})";
  std::ofstream(dir / "measured.json") << "{" << bars << R"(,
    "measurement": {"file": "signals.csv", "format": "csv",
      "channels": [{"gauge": "incident", "column": "incident", "unit": "strain"},
                   {"gauge": "transmitted", "column": "transmitted", "unit": "strain"}]}})";
  std::ofstream(dir / "unmeasured.json") << "{" << bars << "}";
  std::ofstream(dir / "signals.csv") << "time_s,incident,transmitted\n0,0,0\n1e-7,0,0\n";
}

struct Case {
  std::string campaign, expected;
  bool fit_use = false;  // refused for what only the fit does with a test (not its keys)
};

// Each campaign: exit 2, one line starting with the campaign file and holding `expected`, and no
// output folder; `process --campaign` of the file the same (before, it processed the tests and
// ignored the fit's keys whatever they held).
void check_rejected(const fs::path& dir, const std::vector<Case>& cases) {
  int k = 0;
  for (const Case& c : cases) {
    const fs::path file = dir / ("campaign" + std::to_string(k++) + ".json");
    std::ofstream(file) << c.campaign;
    const fs::path out = dir / "out";
    const auto r = run_shpb({"fit", file.string(), "-o", out.string(), "-q"});
    INFO(c.campaign);
    INFO(r.err);
    CHECK(r.code == 2);
    CHECK(r.err.rfind("error: " + file.string() + ": ", 0) == 0);
    CHECK(r.err.find(c.expected) != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(!fs::exists(out));
    if (c.fit_use) continue;
    const auto p = run_shpb({"process", "--campaign", file.string(), "-o", out.string(), "-q"});
    CHECK(p.code == 2);
    CHECK(p.err == r.err);
    CHECK(!fs::exists(out));
  }
}

}  // namespace

TEST_CASE("Bad fit campaigns: exit 2 naming file and JSON path, nothing written", "[fit]") {
  const fs::path dir = shpb_test::scratch_dir("fit_bad");
  write_scenes(dir);
  const std::string copper = (fs::path(SHPB_SOURCE_DIR) / "specimens/ofhc-copper.json").string();
  const std::string tests = R"("tests": [{"scene": "measured.json"}])";
  const std::string material = R"("material": ")" + copper + R"(")";
  const std::vector<Case> cases = {
      {"{" + tests + "," + material + R"(, "free": {"A": ["50 MPa", "150 MPa"]}, "stagse": []})",
       "stagse"},
      {"{" + tests + "," + material + R"(, "free": {"Q": ["50 MPa", "150 MPa"]}})",
       "free.Q: \"Q\": not a parameter of the johnson-cook law; "},
      {"{" + tests + "," + material + R"(, "free": {"yield_stress": [1, 2]}})",
       "free.yield_stress"},
      {"{" + tests + "," + material + R"(, "free": {"A": ["150 MPa", "50 MPa"]}})",
       "free.A: [1.5e+08 Pa, 5e+07 Pa]: the lower bound must be below the upper bound"},
      {"{" + tests + "," + material + R"(, "free": {"A": ["100 MPa", "150 MPa"]}})",
       "free.A: "},  // the file's A = 90 MPa lies outside
      {"{" + tests + "," + material + R"(, "free": {"n": [0.1, 1.5]}})", "free.n[1]: "},
      {"{" + tests + "," + material + R"(, "free": {"A": "50 MPa"}})", "free.A: "},
      {"{" + tests + "," + material + R"(, "free": {"A": ["50 MPa", "150 MPa"]},
          "nuisance": {"striker_speed": [1, 2]}})",
       "nuisance.striker_speed"},
      {"{" + tests + "," + material + R"(, "free": {"A": ["50 MPa", "150 MPa"]},
          "nuisance": {"rise_time": ["3 us", "1 us"]}})",
       "nuisance.rise_time: "},
      {"{" + tests + "," + material + R"(, "free": {"A": ["50 MPa", "150 MPa"]},
          "stages": ["signal"]})",
       "stages[0]: \"signal\""},
      {"{" + tests + "," + material + R"(, "free": {"A": ["50 MPa", "150 MPa"]}, "stages": []})",
       "stages: []: expected a list of the stages to run: \"curve\" or \"signals\""},
      {"{" + tests + "," + material + R"(, "free": {"A": ["50 MPa", "150 MPa"]}, "loss": "l1"})",
       "loss: \"l1\""},
      {"{" + tests + R"(, "free": {"A": ["50 MPa", "150 MPa"]}})", "material: (missing)"},
      {"{" + tests + R"(, "material": "nowhere.json", "free": {"A": [1, 2]}})", "material: "},
      {"{" + tests + "," + material + "}", "free: (missing): nothing to fit"},
      {R"({"tests": [{"scene": "unmeasured.json"}],)" + material +
           R"(, "free": {"A": ["50 MPa", "150 MPa"]}})",
       "tests[0].scene: ", true},
  };
  check_rejected(dir, cases);
  fs::remove_all(dir);
}

TEST_CASE("Bad bar nuisances of a fit: exit 2 naming the key, the value and the rule", "[fit]") {
  const fs::path dir = shpb_test::scratch_dir("fit_bad_bars");
  write_scenes(dir);
  const std::string head = R"({"tests": [{"scene": "measured.json"}], "material": ")" +
                           (fs::path(SHPB_SOURCE_DIR) / "specimens/ofhc-copper.json").string() +
                           R"(", "nuisance": )";
  check_rejected(
      dir, {{head + R"({"incident_wave_speed": ["0 m/s", "5000 m/s"]}})",
             "nuisance.incident_wave_speed[0]: \"0 m/s\": a wave speed must be > 0"},
            {head + R"({"transmitter_wave_speed": "120 %"}})",
             "nuisance.transmitter_wave_speed: \"120 %\": expected \"N %\" with 0 < N < 100"},
            {head + R"({"transmitted_delay": "5 %"}})",
             "nuisance.transmitted_delay: \"5 %\": a time shift or delay starts at 0"},
            // Bounds are asked for in the key's own dimension (before: a stress example,
            // ["50 MPa", "150 MPa"], for every key), with the relative form where it holds.
            {head + R"({"rise_time": "6 us"}})",
             "nuisance.rise_time: \"6 us\": expected bounds [lower, upper], each a time such "
             "as \"600 us\" (a bare number is taken in s); or \"N %\" of each test's start\n"},
            {head + R"({"time_shift": "2 us"}})",
             "nuisance.time_shift: \"2 us\": expected bounds [lower, upper], each a time such "
             "as \"600 us\" (a bare number is taken in s)\n"}});
  fs::remove_all(dir);
}

}  // namespace tests_fit_test_fit_bad_input
