// shpb fit through the executable on synthetic truth: three simulated tests of OFHC copper
// (specimens/ofhc-copper.json) at about 1000, 2000 and 4000 /s, their gauge signals with seeded
// noise of 1 % of each gauge's peak, fitted from A, B, n, C 20 % off (docs/methods.md §9).
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "../app/run_shpb.hpp"
#include "synthetic_scene.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_fit_test_fit_synthetic {

namespace fs = std::filesystem;
using nlohmann::json;
using shpb_test::run_shpb;

namespace {

// Acceptance: A, B and n within 3 % of the truth, C (a rate term worth 3.5 % of the stress
// between 1000 and 4000 /s) within 10 %, each within two standard errors, and the signals stage
// closer to the truth than the curve stage. Also: every test gives the curve stage samples, and
// the fitted pulses reach the noise floor within kFittedNrmse. The standard errors count each
// window's record noise, the records' rest levels and the clock (tools/fit_noise_seeds over 40
// other noise seeds: root mean square of the errors 0.87–1.08 standard errors): a two-standard-
// error check of four parameters then holds for about 90 % of the seeds (35 of 40), as it should,
// and this seed is asserted (docs/validation.md, shpb fit).
constexpr double kShapeTolerance = 0.03;
constexpr double kRateTolerance = 0.10;
constexpr double kStandardErrors = 2.0;
// The fitted pulses: within three times the noise (1 % of the incident gauge's peak is 1–2 % of
// the reflected and transmitted peaks, so a perfect fit has an NRMSE of 0.010–0.018).
constexpr double kFittedNrmse = 0.03;

const fs::path kCopper = fs::path(SHPB_SOURCE_DIR) / "specimens/ofhc-copper.json";
// The Johnson–Cook rate term through a first-order filter of this time constant, in the truth and
// in the fit alike (the start below is the truth's file with A, B, n, C moved). Without it the rate
// term follows each step's strain rate, which rings in the specimen: at 0.1 % steps of A the
// signals' second differences are as large as the first even with global stepping; with it they
// are 1e-3 of them (docs/validation.md, shpb fit). 1 µs: about one elastic transit of the specimen
// (1.1 µs), short against the 10 µs rise of the loading.
const char* const kRateFilter = "1 us";

// Asynchronous stepping, the default: its gauge signals are smooth in the law through the loading
// and rough after it, where the unloaded specimen leaves the bars and rattles between them
// (docs/methods.md §9); the fitted windows end before that (src/fit/fit_case.cpp).
const char* const kStepping = "asynchronous";

// `shpb fit DIR/campaign.json -o DIR/out` without a bootstrap; its summary.json.
json fit_summary(const fs::path& dir, const char* out) {
  const auto r = run_shpb({"fit", (dir / "campaign.json").string(), "-o", (dir / out).string(),
                           "--threads", "2", "-q", "--bootstrap", "0"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  return json::parse(std::ifstream(dir / out / "summary.json"));
}

}  // namespace

TEST_CASE("fit recovers Johnson-Cook A, B, n, C from three noisy simulated tests", "[fit]") {
  const fs::path dir = shpb_test::scratch_dir("fit_synthetic");
  // The truth's rate term is read through the strain-rate filter, which the fit then uses too.
  shpb_test::write_synthetic_campaign(dir, kCopper, kRateFilter, kStepping, 2024);
  using shpb_test::kTruthA, shpb_test::kTruthB, shpb_test::kTruthN, shpb_test::kTruthC;
  const auto r = run_shpb({"fit", (dir / "campaign.json").string(), "-o", (dir / "out").string(),
                           "--threads", "2", "-q", "--bootstrap", "0"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json s = json::parse(std::ifstream(dir / "out/summary.json"));
  const json& p = s["parameters"];
  const std::map<std::string, double> truths = {
      {"A", kTruthA}, {"B", kTruthB}, {"n", kTruthN}, {"C", kTruthC}};
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
  json check = shpb_test::synthetic_scene(18.5, dir / "out/fit.json", kStepping);
  std::ofstream(dir / "check.json") << check.dump(1);
  CHECK(run_shpb({"validate", (dir / "check.json").string()}).code == 0);
  fs::remove_all(dir);
}

TEST_CASE("A bridge's offset on a test's record moves neither fit's start nor its residuals",
          "[fit]") {
  // One noiseless test at 18.5 m/s, its record offset by 3 % of the incident plateau (the
  // short bars' ~2.3e-3 strain at this speed), as an unbalanced bridge records it; the striker
  // velocity inferred from the plateau, the law at the truth. The record's rest level is the
  // offset exactly (the simulated bars are at rest before the pulse).
  const fs::path dir = shpb_test::scratch_dir("fit_offset");
  shpb_test::SyntheticSetup setup;
  setup.velocities = {18.5};
  setup.noise_fraction = 0;
  shpb_test::write_synthetic_campaign(dir, kCopper, kRateFilter, kStepping, 1, setup);
  constexpr double kOffset = 7e-5;
  {
    std::ifstream in(dir / "measured0.csv");
    std::ofstream out(dir / "offset0.csv");
    out.precision(17);
    std::string line;
    std::getline(in, line);
    out << line << '\n';
    double t = 0, inc = 0, tra = 0;
    char comma = 0;
    while (in >> t >> comma >> inc >> comma >> tra)
      out << t << ',' << inc + kOffset << ',' << tra + kOffset << '\n';
  }
  json scene = json::parse(std::ifstream(dir / "scene0.json"));
  scene["measurement"]["file"] = "offset0.csv";
  scene["measurement"].erase("striker_velocity");
  std::ofstream(dir / "scene0.json") << scene.dump(1);
  json campaign = json::parse(std::ifstream(dir / "campaign.json"));
  campaign["material"] = "truth-law.json";
  campaign["free"] = {{"A", {40e6, 200e6}}};
  campaign["nuisance"] = {{"striker_velocity", "10 %"}};
  campaign["stages"] = {"signals"};
  std::ofstream(dir / "campaign.json") << campaign.dump(1);
  const auto r = run_shpb({"fit", (dir / "campaign.json").string(), "-o", (dir / "out").string(),
                           "--threads", "1", "-q", "--bootstrap", "0", "--max-iterations", "1"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json s = json::parse(std::ifstream(dir / "out/summary.json"));
  INFO(s.dump(1));
  // No refit was drawn: no bootstrap block (before: refits 0 and a seed 0 that drew nothing).
  CHECK(s["bootstrap"].is_null());
  // V = c0 ε_I (Z_s + Z_b)/Z_s from a plateau flat to ~1 % (docs/methods.md §4).
  constexpr double kInferredVelocity = 0.01;
  CHECK(s["parameters"]["v0:striker_velocity"]["start"].get<double>() ==
        Approx(18.5).epsilon(kInferredVelocity));
  // At the truth, the start's pulses differ from the record only by that 1 % of velocity.
  for (const char* pulse : {"reflected", "transmitted"})
    CHECK(s["tests"][0][std::string("nrmse_") + pulse + "_before"].get<double>() <=
          kInferredVelocity);
  fs::remove_all(dir);
}

// A transmitted channel whose amplifier range cut the pulse: the record holds the clip level where
// the specimen's force rose beyond it. Those samples say only that the strain reached the level
// (a censored measurement), and fit must use them so (Tobit 1958): a sample at the clip level adds
// a residual only where the simulation stays short of it, and the processed curve is not fitted
// where it is computed from one. Taken at face value, the cut plateau reads as a weaker specimen
// (A 80 % low, n 56 % low before). One noiseless test at 18.5 m/s, A, B, n fitted from the
// truth's file 20 % off (C held), from its whole record and from the record with its transmitted
// channel clipped at 85 % of its peak: the clipped record must give the law the whole one gives.
TEST_CASE("fit reads a clipped channel's clipped samples as bounds, not values", "[fit]") {
  const fs::path dir = shpb_test::scratch_dir("fit_clipped");
  shpb_test::SyntheticSetup setup;
  setup.velocities = {18.5};
  setup.noise_fraction = 0;
  shpb_test::write_synthetic_campaign(dir, kCopper, kRateFilter, kStepping, 1, setup);
  json campaign = json::parse(std::ifstream(dir / "campaign.json"));
  campaign["free"].erase("C");
  std::ofstream(dir / "campaign.json") << campaign.dump(1);
  auto fitted = [&](const char* out) { return fit_summary(dir, out); };
  const json whole = fitted("whole");
  constexpr double kClipLevel = 0.85;  // of the transmitted pulse's peak: a range set too tight
  {
    std::vector<std::array<double, 3>> rows;
    std::ifstream in(dir / "measured0.csv");
    std::string header;
    std::getline(in, header);
    double t = 0, inc = 0, tra = 0, peak = 0;
    char comma = 0;
    while (in >> t >> comma >> inc >> comma >> tra) {
      rows.push_back({t, inc, tra});
      peak = std::max(peak, std::abs(tra));
    }
    std::ofstream out(dir / "measured0.csv");
    out.precision(17);
    out << header << '\n';
    for (const auto& [time, incident, transmitted] : rows)
      out << time << ',' << incident << ','
          << std::clamp(transmitted, -kClipLevel * peak, kClipLevel * peak) << '\n';
  }
  const json clipped = fitted("clipped");
  INFO(clipped.dump(1));
  bool said = false;  // the clipping is said
  for (const auto& w : clipped["warnings"])
    said |= w.get<std::string>().find("clipped") != std::string::npos;
  CHECK(said);
  // The clipped samples hold as bounds what the whole record held as values: the two fits end
  // within 0.1 % of each other (measured); a tenth of the noisy campaign's 3 % bound on the truth.
  constexpr double kSameLaw = kShapeTolerance / 10;
  for (const char* name : {"A", "B", "n"}) {
    const double a = whole["parameters"][name]["value"], b = clipped["parameters"][name]["value"];
    INFO(name << " whole record " << a << ", clipped " << b);
    CHECK(std::abs(b / a - 1) <= kSameLaw);
  }
}

// A law that cannot represent the tests must say so (docs/methods.md §9, "Lack of fit"): three
// noisy tests of a strongly rate-dependent copper (Johnson–Cook C 0.12: the flow stress 9 % higher
// at 4000 /s than at 1000 /s) fitted with a rate-independent bilinear law leave residuals above the
// record's noise, which fit names per test and pulse; the same records fitted with the truth's own
// law (Johnson–Cook, A, B, n, C free) reach the noise and say nothing of the kind.
TEST_CASE("fit says when the law cannot reproduce the tests: residuals far above the noise",
          "[fit]") {
  const fs::path dir = shpb_test::scratch_dir("fit_misfit");
  json copper = json::parse(std::ifstream(kCopper));
  constexpr double kStrongRateTerm = 0.12;  // C: 5 times the copper's, as a polymer or a bcc metal
  copper["C"] = kStrongRateTerm;
  std::ofstream(dir / "rate-copper.json") << copper.dump(1);
  shpb_test::write_synthetic_campaign(dir, dir / "rate-copper.json", kRateFilter, kStepping, 7);
  // The misfit criterion of src/fit/fit_run.cpp: residuals' RMS over the record's noise.
  constexpr double kMisfitOverNoise = 2.0;
  auto fitted = [&](const char* out) { return fit_summary(dir, out); };
  auto says_misfit = [](const json& s) {
    for (const auto& w : s["warnings"])
      if (w.get<std::string>().find("cannot reproduce this test") != std::string::npos) return true;
    return false;
  };
  auto worst_misfit = [](const json& s) {
    double worst = 0;
    for (const auto& t : s["tests"])
      for (const char* pulse : {"reflected", "transmitted"})
        worst = std::max(worst, t[std::string("misfit_over_noise_") + pulse].get<double>());
    return worst;
  };
  const json right = fitted("johnson-cook");
  INFO(right.dump(1));
  CHECK_FALSE(says_misfit(right));
  CHECK(worst_misfit(right) <= kMisfitOverNoise);

  json campaign = json::parse(std::ifstream(dir / "campaign.json"));
  campaign["material"] = {{"model", "bilinear"},
                          {"density", copper["density"]},
                          {"youngs_modulus", copper["youngs_modulus"]},
                          {"poisson_ratio", copper["poisson_ratio"]},
                          {"yield_stress", "150 MPa"},
                          {"tangent_modulus", "1 GPa"}};
  campaign["free"] = {{"yield_stress", {"20 MPa", "1 GPa"}},
                      {"tangent_modulus", {"10 MPa", "20 GPa"}}};
  std::ofstream(dir / "campaign.json") << campaign.dump(1);
  const json wrong = fitted("bilinear");
  INFO(wrong.dump(1));
  CHECK(says_misfit(wrong));
  CHECK(worst_misfit(wrong) > kMisfitOverNoise);
  fs::remove_all(dir);
}

}  // namespace tests_fit_test_fit_synthetic
