// shpb fit through the executable on synthetic truth: three simulated tests of OFHC copper
// (specimens/ofhc-copper.json) at about 1000, 2000 and 4000 /s, their gauge signals with seeded
// noise of 1 % of each gauge's peak, fitted from A, B, n, C 20 % off (docs/methods.md §9).
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "../app/run_shpb.hpp"
#include "model/scene.hpp"
#include "solver/simulation.hpp"
#include "synthetic_scene.hpp"

namespace fs = std::filesystem;
using nlohmann::json;
using shpb_test::run_shpb;

namespace {

// Acceptance: A, B and n within 3 % of the truth, C (a rate term worth 3.5 % of the stress
// between 1000 and 4000 /s) within 10 %, each within two standard errors, and the signals stage
// closer to the truth than the curve stage. Also: every test gives the curve stage samples, and
// the fitted pulses reach the noise floor within kFittedNrmse. Measured over other noise seeds
// the estimates scatter up to 1.8 times their standard errors (C; mostly the clock alignment on
// the noisy incident pulse's half-plateau crossing), so the two-standard-error check holds for
// this seed with C at 1.7, not for every seed (README, shpb fit).
constexpr double kShapeTolerance = 0.03;
constexpr double kRateTolerance = 0.10;
constexpr double kStandardErrors = 2.0;
// 1 % of the peak: the noise of a good strain-gauge record (and of the specification).
constexpr double kNoiseFraction = 0.01;
// The fitted pulses: within three times the noise (1 % of the incident gauge's peak is 1–2 % of
// the reflected and transmitted peaks, so a perfect fit has an NRMSE of 0.010–0.018).
constexpr double kFittedNrmse = 0.03;

const fs::path kCopper = fs::path(SHPB_SOURCE_DIR) / "specimens/ofhc-copper.json";
// The Johnson–Cook rate term through a first-order filter of this time constant, in the truth and
// in the fit alike (the start below is the truth's file with A, B, n, C moved). Without it the rate
// term follows each step's strain rate, which rings in the specimen: at 0.1 % steps of A the
// signals' second differences are as large as the first even with global stepping; with it they
// are 1e-3 of them (README, shpb fit). 1 µs: about one elastic transit of the specimen (1.1 µs),
// short against the 10 µs rise of the loading.
const char* const kRateFilter = "1 us";

// Global stepping: with asynchronous stepping the gauge signals are smooth in the law through the
// loading but rough in the tail, where the unloaded specimen rattles between the bar ends (impacts
// whose number and instants jump with the law; docs/methods.md §9), which the compared windows
// reach: the finite-difference Jacobian is noise there and the fit stops 3–29 % off (README, shpb
// fit).
json scene_at(double velocity_m_s, const fs::path& specimen) {
  return shpb_test::synthetic_scene(velocity_m_s, specimen, "global");
}

}  // namespace

TEST_CASE("fit recovers Johnson-Cook A, B, n, C from three noisy simulated tests", "[fit]") {
  const fs::path dir = shpb_test::scratch_dir("fit_synthetic");
  const double velocities[] = {13.5, 18.5, 28.0};  // ≈ 1000, 2000, 4000 /s in this set-up
  // The truth: the file's law with its rate term read through the strain-rate filter, which the
  // fit then uses too (the start below is this file with A, B, n, C moved).
  json truth = json::parse(std::ifstream(kCopper));
  truth["strain_rate_filter"] = kRateFilter;
  const fs::path truth_law = dir / "truth-law.json";
  std::ofstream(truth_law) << truth.dump(1);
  json campaign = {{"name", "synthetic OFHC copper"}, {"tests", json::array()}};
  for (int k = 0; k < 3; ++k) {
    const fs::path truth_file = dir / ("truth" + std::to_string(k) + ".json");
    std::ofstream(truth_file) << scene_at(velocities[k], truth_law).dump(1);
    const shpb::Scene truth = shpb::read_scene(truth_file);
    const shpb::SimulationResult sim = shpb::simulate(truth);
    REQUIRE(sim.stable);
    std::mt19937 rng(2024 + k);  // seeded: the test is reproducible
    std::normal_distribution<double> normal(0.0, 1.0);
    std::vector<std::vector<double>> gauges;
    for (const char* g : {"incident", "transmitted"}) {
      std::vector<double> x = sim.gauges.column(g);
      double peak = 0;
      for (double v : x) peak = std::max(peak, std::abs(v));
      for (double& v : x) v += kNoiseFraction * peak * normal(rng);
      gauges.push_back(x);
    }
    const std::string csv = "measured" + std::to_string(k) + ".csv";
    {
      std::ofstream out(dir / csv);
      out.precision(17);
      out << "time_s,incident,transmitted\n";
      for (std::size_t i = 0; i < sim.gauges.samples(); ++i)
        out << sim.gauges.time_s[i] << ',' << gauges[0][i] << ',' << gauges[1][i] << '\n';
    }
    json scene = scene_at(velocities[k], truth_law);
    scene["measurement"] = {
        {"file", csv},
        {"format", "csv"},
        {"time", {{"column", "time_s"}, {"unit", "s"}}},
        {"channels",
         {{{"gauge", "incident"}, {"column", "incident"}, {"unit", "strain"}},
          {{"gauge", "transmitted"}, {"column", "transmitted"}, {"unit", "strain"}}}},
        {"dispersion", {{"correction", "none"}}},  // 1D signals: nothing to undo or add
        {"striker_velocity", std::to_string(velocities[k]) + " m/s"}};
    // Built by append: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string.
    std::string name = "scene", label = "v";
    name += std::to_string(k);
    name += ".json";
    label += std::to_string(k);
    std::ofstream(dir / name) << scene.dump(1);
    campaign["tests"].push_back({{"scene", name}, {"name", label}});
  }
  const double a = 90e6, b = 292e6, n = 0.31, c = 0.025;  // the file's A, B, n, C
  json start = truth;
  start["A"] = 1.2 * a, start["B"] = 0.8 * b, start["n"] = 1.2 * n, start["C"] = 0.8 * c;
  std::ofstream(dir / "start.json") << start.dump(1);
  campaign["material"] = "start.json";
  campaign["free"] = {{"A", {"20 MPa", "300 MPa"}},
                      {"B", {"50 MPa", "800 MPa"}},
                      {"n", {0.05, 0.95}},
                      {"C", {0.001, 0.2}}};
  std::ofstream(dir / "campaign.json") << campaign.dump(1);

  const auto r = run_shpb({"fit", (dir / "campaign.json").string(), "-o", (dir / "out").string(),
                           "--threads", "2", "-q"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json s = json::parse(std::ifstream(dir / "out/summary.json"));
  const json& p = s["parameters"];
  const std::map<std::string, double> truths = {{"A", a}, {"B", b}, {"n", n}, {"C", c}};
  double curve_distance = 0, signals_distance = 0;
  for (const auto& [name, value] : truths) {
    const double fitted = p[name]["value"];
    REQUIRE(p[name]["std_error"].is_number());
    REQUIRE(p[name]["after_curve"].is_number());
    const double error = p[name]["std_error"], after_curve = p[name]["after_curve"];
    const double off = std::abs(fitted / value - 1);
    INFO(name << " fitted " << fitted << " truth " << value << " std error " << error);
    CHECK(off <= (name == "C" ? kRateTolerance : kShapeTolerance));
    CHECK(std::abs(fitted - value) <= kStandardErrors * error);
    curve_distance += std::pow(after_curve / value - 1, 2);
    signals_distance += std::pow(fitted / value - 1, 2);
  }
  INFO(s.dump(1));
  // The curve stage fits the processed curve, blind to what happens before equilibrium and fed
  // the processed (ringing) strain rate: the signals stage must end closer to the truth.
  CHECK(signals_distance < curve_distance);
  for (const auto& t : s["tests"]) {
    CHECK(t["curve_points"].get<long>() > 0);
    for (const char* pulse : {"reflected", "transmitted"}) {
      const double before = t[std::string("nrmse_") + pulse + "_before"];
      const double after = t[std::string("nrmse_") + pulse + "_after"];
      CHECK(after < before);
      CHECK(after <= kFittedNrmse);
    }
  }
  CHECK(s["simulations"].get<long>() > 0);
  CHECK(fs::exists(dir / "out/fit.json"));
  CHECK(fs::exists(dir / "out/curves.csv"));
  CHECK(fs::exists(dir / "out/signals.csv"));
  // fit.json is a material file a scene can use.
  json check = scene_at(18.5, dir / "out/fit.json");
  std::ofstream(dir / "check.json") << check.dump(1);
  CHECK(run_shpb({"validate", (dir / "check.json").string()}).code == 0);
  fs::remove_all(dir);
}
