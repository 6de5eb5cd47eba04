// shpb fit's intervals through the executable (docs/methods.md §9, "Intervals"): the parametric
// bootstrap on the fit's own synthetic campaign (light: the sanitizer builds run it). Whether the
// reported intervals hold the truth is a statistical question with minutes of CPU per campaign:
// the benchmarks answer it (`make bench`: the classic-bar copper campaign, and with
// BENCH_FIT_COVERAGE=1 the coverage over 100 campaigns; tools/fit_interval_coverage.cpp).
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "../app/run_shpb.hpp"
#include "synthetic_scene.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_fit_test_fit_intervals {

namespace fs = std::filesystem;
using nlohmann::json;
using shpb_test::run_shpb;

namespace {

const fs::path kCopper = fs::path(SHPB_SOURCE_DIR) / "specimens/ofhc-copper.json";
// The rate term through a 1 µs filter in truth and fit alike (tests/fit/test_fit_synthetic.cpp).
const char* const kRateFilter = "1 us";
// The fewest refits that give a bootstrap interval (fit/fit_bootstrap.cpp).
const char* const kFewestRefits = "10";

const std::map<std::string, double> kTruth = {{"A", shpb_test::kTruthA},
                                              {"B", shpb_test::kTruthB},
                                              {"n", shpb_test::kTruthN},
                                              {"C", shpb_test::kTruthC}};

}  // namespace

TEST_CASE("fit's bootstrap refits the campaign and reports each parameter's 95 % interval",
          "[fit][bootstrap]") {
  const fs::path dir = shpb_test::scratch_dir("fit_bootstrap");
  shpb_test::write_synthetic_campaign(dir, kCopper, kRateFilter, "asynchronous", 2024);
  const auto r = run_shpb({"fit", (dir / "campaign.json").string(), "-o", (dir / "out").string(),
                           "--threads", "2", "-q", "--bootstrap", kFewestRefits});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json s = json::parse(std::ifstream(dir / "out/summary.json"));
  INFO(s.dump(1));
  CHECK(s["bootstrap"]["refits"] == 10);
  CHECK(s["bootstrap"]["finished"].get<int>() + s["bootstrap"]["failed"].get<int>() == 10);
  const json fit = json::parse(std::ifstream(dir / "out/fit.json"));
  for (const auto& [name, truth] : kTruth) {
    const json& p = s["parameters"][name];
    REQUIRE(p["interval_95"].is_array());
    const double lo = p["interval_95"][0], hi = p["interval_95"][1], value = p["value"];
    // The reported interval holds the value and at least the linearised one.
    CHECK(lo < value);
    CHECK(value < hi);
    CHECK(lo <= p["linearised_interval_95"][0].get<double>());
    CHECK(hi >= p["linearised_interval_95"][1].get<double>());
    REQUIRE(p["bootstrap"].is_object());
    CHECK(p["bootstrap"]["std_dev"].get<double>() > 0);
    // fit.json carries the same interval (a material file: shpb reads it back, below).
    CHECK(fit["uncertainty"][name]["interval_95"] == p["interval_95"]);
    CHECK(fit["uncertainty"][name]["method"] == p["interval_method"]);
  }
  json check = shpb_test::synthetic_scene(18.5, dir / "out/fit.json", "asynchronous");
  std::ofstream(dir / "check.json") << check.dump(1);
  CHECK(run_shpb({"validate", (dir / "check.json").string()}).code == 0);
  fs::remove_all(dir);
}

}  // namespace tests_fit_test_fit_intervals
