// shpb fit through the executable on the measured LANL OFE copper test (experiments/
// lanl-cu-ofe-273k/campaign.json: Johnson–Cook A, B, n, the striker velocity and the impact rise
// time, nothing else; the scene gives the lab's calibrated reflected time; docs/methods.md §9).
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "../app/run_shpb.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_fit_test_fit_lanl {

namespace fs = std::filesystem;
using nlohmann::json;
using shpb_test::run_shpb;

namespace {
// Acceptance: the fitted simulation's reflected and transmitted pulses each within NRMSE 0.06 of
// the measured ones (the published law gives 0.128 and 0.173).
constexpr double kFittedNrmse = 0.06;
}  // namespace

TEST_CASE("fit brings the LANL copper pulses within NRMSE 0.06 and says C is not identifiable",
          "[fit][experiment][data]") {
  const fs::path root(SHPB_SOURCE_DIR);
  const fs::path experiment = root / "experiments/lanl-cu-ofe-273k";
  const fs::path dir = shpb_test::scratch_dir("fit_lanl");
  const auto r = run_shpb({"fit", (experiment / "campaign.json").string(), "-o",
                           (dir / "out").string(), "--threads", "2", "-q", "--bootstrap", "0"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json s = json::parse(std::ifstream(dir / "out/summary.json"));
  INFO(s.dump(1));
  REQUIRE(s["tests"].size() == 1);
  const json& t = s["tests"][0];
  CHECK(t["nrmse_reflected_after"].get<double>() <= kFittedNrmse);
  CHECK(t["nrmse_transmitted_after"].get<double>() <= kFittedNrmse);
  // Exactly the free set named above: the delay of the reflected and transmitted pulses is the
  // lab's calibration, not a fitted shift.
  for (const auto& p : s["parameters"].items())
    CHECK(p.key().find("time_shift") == std::string::npos);
  // No law parameter pinned at a bound (n ended at 1 when the pulses' delay was missing).
  for (const auto& w : s["warnings"])
    for (const char* p : {"A ends", "B ends", "n ends"})
      CHECK(w.get<std::string>().rfind(p, 0) == std::string::npos);
  CHECK(s["simulations_per_second"].get<double>() > 0);
  CHECK(s["simulations_per_cpu_second"].get<double>() > 0);

  // C freed too (curve stage only: the warning depends on the tests' strain rates, not on the
  // stage): one test at one rate cannot pin it, and the fit says so by name.
  json campaign = json::parse(std::ifstream(experiment / "campaign.json"));
  campaign["tests"][0]["scene"] = (experiment / "scene.json").string();
  campaign["material"] = (root / "specimens/ofhc-copper.json").string();
  campaign["free"]["C"] = {0.001, 0.2};
  campaign["stages"] = {"curve"};
  std::ofstream(dir / "campaign-c.json") << campaign.dump(1);
  const auto rc = run_shpb({"fit", (dir / "campaign-c.json").string(), "-o",
                            (dir / "out-c").string(), "-q", "--bootstrap", "0"});
  INFO(rc.err);
  REQUIRE(rc.code == 0);
  const json sc = json::parse(std::ifstream(dir / "out-c/summary.json"));
  bool warned = false;
  for (const auto& w : sc["warnings"])
    warned = warned || w.get<std::string>().rfind("C is not identifiable", 0) == 0;
  CHECK(warned);
  fs::remove_all(dir);
}

namespace {
// The lab's own calibration of its incident bar (the file header): the reflected pulse reaches the
// gauge 156.6 µs after the incident one passed it, 3.4 µs more than 2d/c0 from the header's
// nominal E and ρ. A fit with the bars' wave speeds freed and that time withheld must find it
// again within 0.5 µs: a fifth of the record's 10 MHz samples short of the 3.4 µs it corrects,
// and below the 0.5 % wave-speed uncertainty of the scene (0.8 µs of the round trip).
constexpr double kLabRoundTrip_s = 156.6e-6;
constexpr double kRoundTripTolerance_s = 0.5e-6;

const fs::path kRoot(SHPB_SOURCE_DIR);

// The LANL scene without the lab's calibrated reflected time (only the nominal bars), in `dir`.
json write_nominal_bars_scene(const fs::path& experiment, const fs::path& dir) {
  json scene = json::parse(std::ifstream(experiment / "scene.json"));
  scene["measurement"].erase("reflected_time");
  scene["measurement"]["file"] =
      (experiment / scene["measurement"]["file"].get<std::string>()).string();
  std::ofstream(dir / "scene.json") << scene.dump(1);
  return scene;
}

// The experiment's campaign on another scene.
json lanl_campaign_on(const fs::path& scene) {
  json campaign = json::parse(std::ifstream(kRoot / "experiments/lanl-cu-ofe-273k/campaign.json"));
  campaign["tests"][0]["scene"] = scene.string();
  campaign["material"] = (kRoot / "specimens/ofhc-copper.json").string();
  return campaign;
}

// The incident gauge's distance to the specimen face: the bar's length less the gauge's position.
double incident_gauge_distance_m(const json& scene) {
  const json& bar = scene["bars"][1];
  REQUIRE(bar["length"] == "1.22 m");
  REQUIRE(bar["gauges"][0]["position"] == "839 mm");
  return 1.22 - 0.839;
}
}  // namespace

// A whole fit (~240 simulations, 6–10 s in Release): the Release pass only; the lighter test below
// runs the same code paths under the sanitizers.
TEST_CASE("fit with the bars' wave speeds freed finds the LANL round trip the lab timed",
          "[fit][experiment][data][release-only]") {
  const fs::path experiment = kRoot / "experiments/lanl-cu-ofe-273k";
  const fs::path dir = shpb_test::scratch_dir("fit_lanl_bars");
  const json scene = write_nominal_bars_scene(experiment, dir);
  json campaign = lanl_campaign_on(dir / "scene.json");
  campaign["nuisance"]["incident_wave_speed"] = "5 %";
  campaign["nuisance"]["transmitter_wave_speed"] = "5 %";
  std::ofstream(dir / "campaign.json") << campaign.dump(1);

  const auto r = run_shpb({"fit", (dir / "campaign.json").string(), "-o", (dir / "out").string(),
                           "--threads", "2", "-q", "--bootstrap", "0"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json s = json::parse(std::ifstream(dir / "out/summary.json"));
  INFO(s.dump(1));
  const json& t = s["tests"][0];
  CHECK(t["nrmse_reflected_after"].get<double>() <= kFittedNrmse);
  CHECK(t["nrmse_transmitted_after"].get<double>() <= kFittedNrmse);
  // The round trip from the fitted wave speed and the scene's geometry: the incident gauge's
  // distance to the specimen face is the bar's length less the gauge's position.
  const double d = incident_gauge_distance_m(scene);
  const json& c = s["parameters"]["cu-ofe-273k:incident_wave_speed"];
  REQUIRE(c["std_error"].is_number());
  const double round_trip = 2 * d / c["value"].get<double>();
  CHECK(round_trip == Approx(kLabRoundTrip_s).margin(kRoundTripTolerance_s));
  CHECK(t["round_trip_s"].get<double>() == Approx(round_trip).epsilon(1e-12));
  CHECK(s["parameters"]["cu-ofe-273k:transmitter_wave_speed"]["std_error"].is_number());
}

TEST_CASE("fit frees the LANL incident bar's wave speed and the transmitted channel's delay",
          "[fit][experiment][data]") {
  // One iteration of the signals stage with only the bars free (17 simulations): the wave speed
  // moves the round trip from 2d/c0 of the nominal bars towards the lab's timed one, and both
  // fitted pulses come closer to the measured ones.
  const fs::path experiment = kRoot / "experiments/lanl-cu-ofe-273k";
  const fs::path dir = shpb_test::scratch_dir("fit_lanl_bars_light");
  const json scene = write_nominal_bars_scene(experiment, dir);
  json campaign = lanl_campaign_on(dir / "scene.json");
  campaign.erase("free");
  campaign["nuisance"] = {{"incident_wave_speed", "5 %"}, {"transmitted_delay", {"-5 us", "5 us"}}};
  campaign["stages"] = {"signals"};
  std::ofstream(dir / "campaign.json") << campaign.dump(1);
  const auto r = run_shpb({"fit", (dir / "campaign.json").string(), "-o", (dir / "out").string(),
                           "--threads", "2", "--max-iterations", "1", "-q", "--bootstrap", "0"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json s = json::parse(std::ifstream(dir / "out/summary.json"));
  INFO(s.dump(1));
  const json& t = s["tests"][0];
  const double d = incident_gauge_distance_m(scene);
  const json& c = s["parameters"]["cu-ofe-273k:incident_wave_speed"];
  const double nominal_round_trip = 2 * d / c["start"].get<double>();
  const double round_trip = t["round_trip_s"].get<double>();
  CHECK(round_trip == Approx(2 * d / c["value"].get<double>()).epsilon(1e-12));
  CHECK(std::abs(round_trip - kLabRoundTrip_s) < std::abs(nominal_round_trip - kLabRoundTrip_s));
  for (const char* pulse : {"reflected", "transmitted"})
    CHECK(t[std::string("nrmse_") + pulse + "_after"].get<double>() <
          t[std::string("nrmse_") + pulse + "_before"].get<double>());
  const json& delay = s["parameters"]["cu-ofe-273k:transmitted_delay"];
  CHECK(delay["unit"] == "s");
  CHECK(delay["std_error"].is_number());
}

}  // namespace tests_fit_test_fit_lanl
