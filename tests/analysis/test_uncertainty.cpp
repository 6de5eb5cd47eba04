// Coverage of the Monte Carlo bands of `process` (analysis/uncertainty.hpp, docs/methods.md §10):
// the 95 % band of the 3-wave stress and of the strain rate must hold the specimen's true state in
// 95 % of the cases where the lab's values are wrong by draws of their declared uncertainties.
//
// Design (cheap enough to run in seconds): one simulation of a copper specimen (the fit tests'
// coarse Kolsky bar) is the truth: its gauges are what the bar really recorded, its specimen's
// stress and strain rate (averaged over one wave transit of the specimen, as
// test_simulated_gauges.cpp does) what the specimen really did. Each simulated test draws the lab's
// values around the true ones from the declared uncertainties — gauge factor, excitation and gain
// of each bridge, each bar's modulus, density and diameter, the specimen's length and diameter,
// the gauges' distances — and a trigger delay of the transmitted channel that the lab does not
// know. The record a lab reads is then exactly the simulated strain converted to volts with the
// true bridge and back with the lab's, its transmitted channel delayed: only the processing inputs
// differ from test to test, so the physics is simulated once. Dispersion, windows and friction do
// not apply to a simulated 1D record (no dispersion, no friction simulated, detected windows).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <random>
#include <vector>

#include "../fit/synthetic_scene.hpp"
#include "analysis/test_processing.hpp"
#include "analysis/uncertainty.hpp"
#include "dispersion/propagation.hpp"
#include "solver/simulation.hpp"
#include "specimen_truth.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_analysis_test_uncertainty {

using namespace shpb;

using shpb_test::moving_average;

namespace {

namespace fs = std::filesystem;

// Declared standard uncertainties: a calibrated bar and a micrometer-measured specimen.
constexpr double kGaugeFactorU = 0.01;        // relative: a gauge lot's stated tolerance
constexpr double kExcitationU = 0.005;        // relative: a bridge supply's accuracy
constexpr double kGainU = 0.005;              // relative: an amplifier's gain accuracy
constexpr double kModulusU = 0.01;            // relative: a bar modulus from a handbook or a test
constexpr double kDensityU = 0.005;           // relative
constexpr double kBarDiameterU = 0.01e-3;     // m: micrometer
constexpr double kSpecimenLengthU = 0.02e-3;  // m: micrometer on a soft, faced specimen
constexpr double kSpecimenDiameterU = 0.02e-3;
constexpr double kGaugePositionU = 1e-3;   // m: a gauge located with a rule
constexpr double kTriggerDelayU = 0.2e-6;  // s: two digitizer channels' skew
// Simulated tests and draws per test: 300 tests put the standard error of a pooled 95 % coverage
// near 1.3 % (points of one test are correlated: the tests count, not the points), 200 draws
// resolve a 2.5 % quantile by 5 draws beyond it.
constexpr int kTests = 300;
constexpr std::size_t kDraws = 200;
// A 95 % band covers the truth at 93 % to 97 % of the points: the nominal 95 % within about one
// and a half standard errors of the pooled coverage.
constexpr double kCoverageLow = 0.93, kCoverageHigh = 0.97;
// Points judged: in equilibrium (R <= 5 %), the stress at least 20 % of its peak, before the
// incident pulse ends at the front face (unloading).
constexpr double kLoadedFraction = 0.2;

StandardUncertainty relative(double u) { return {u, true, "test"}; }
StandardUncertainty absolute(double u) { return {u, false, "test"}; }

struct Coverage {
  std::size_t judged = 0, points = 0, stress = 0, rate = 0;  // points: judged with a band
};

// The declared uncertainties above, on the bars on either side of the specimen and on it.
UncertaintySpec declared_uncertainty(std::size_t specimen) {
  UncertaintySpec u;
  u.gauge_factor = relative(kGaugeFactorU);
  u.excitation = relative(kExcitationU);
  u.gain = relative(kGainU);
  u.gauge_position = absolute(kGaugePositionU);
  u.trigger_delay = absolute(kTriggerDelayU);
  for (std::size_t b : {specimen - 1, specimen + 1}) {
    BarUncertainty bu;
    bu.bar = b;
    bu.youngs_modulus = relative(kModulusU);
    bu.density = relative(kDensityU);
    bu.diameter = absolute(kBarDiameterU);
    u.bars.push_back(bu);
  }
  BarUncertainty su;
  su.bar = specimen;
  su.length = absolute(kSpecimenLengthU);
  su.diameter = absolute(kSpecimenDiameterU);
  u.bars.push_back(su);
  return u;
}

}  // namespace

TEST_CASE(
    "The Monte Carlo bands of the 3-wave stress and strain rate cover the specimen's truth "
    "at 95 % when the lab's values are drawn from their declared uncertainties",
    "[release-only][uncertainty]") {
  const fs::path copper = fs::path(SHPB_SOURCE_DIR) / "specimens/ofhc-copper.json";
  const Scene truth =
      read_scene_text(shpb_test::synthetic_scene(18.5, copper, "asynchronous").dump(),
                      fs::path(SHPB_SOURCE_DIR) / "tests/coverage-scene.json");
  const SimulationResult sim = simulate(truth);
  REQUIRE(sim.stable);
  const std::size_t specimen = *truth.specimen;
  const BarSpec& sp = truth.bars[specimen];
  const auto& ts = sim.specimen.time_s;
  const double transit = sp.length_m / sp.material.wave_speed_m_s();
  const auto half = static_cast<std::size_t>(0.5 * transit / (ts[1] - ts[0]));
  const auto true_stress = moving_average(sim.specimen.column("stress_Pa"), half);
  const auto true_rate = moving_average(sim.specimen.column("strain_rate_1_s"), half);
  const auto& true_strain = sim.specimen.column("strain");
  // The specimen's state where its strain first reaches e.
  auto truth_at = [&](const std::vector<double>& y, double e) {
    return value_at_first_reach(true_strain, y, true_strain.size(), e);
  };
  GaugeSignals record;
  record.time_s = sim.gauges.time_s;
  record.dt_s = record.time_s[1] - record.time_s[0];
  for (const char* name : {"incident", "transmitted"}) {
    record.gauges.push_back(name);
    record.strain.push_back(sim.gauges.column(name));
  }
  constexpr double kGaugeFactor = 2.06, kExcitation = 8, kGain = 200;

  const UncertaintySpec u = declared_uncertainty(specimen);

  Coverage cover;
  for (int test = 0; test < kTests; ++test) {
    std::mt19937_64 rng(static_cast<std::uint64_t>(test) + 1000);
    std::normal_distribution<double> normal;
    // The lab's values: the true ones off by a draw of their uncertainty.
    Scene lab = truth;
    for (std::size_t b : {specimen - 1, specimen + 1}) {
      BarSpec& bar = lab.bars[b];
      bar.material.youngs_modulus_Pa *= 1 + kModulusU * normal(rng);
      bar.material.density_kg_m3 *= 1 + kDensityU * normal(rng);
      const double d = bar.diameter_m + kBarDiameterU * normal(rng);
      bar.area_m2 *= (d / bar.diameter_m) * (d / bar.diameter_m);
      bar.diameter_m = d;
      bar.gauges[0].position_m += kGaugePositionU * normal(rng);
    }
    BarSpec& s = lab.bars[specimen];
    s.length_m += kSpecimenLengthU * normal(rng);
    const double ds = s.diameter_m + kSpecimenDiameterU * normal(rng);
    s.area_m2 *= (ds / s.diameter_m) * (ds / s.diameter_m);
    s.diameter_m = ds;
    MeasurementSpec m;
    m.uncertainty = u;
    GaugeSignals signals = record;
    for (std::size_t g = 0; g < 2; ++g) {
      ChannelSpec ch;
      ch.gauge = record.gauges[g];
      ch.unit = SignalUnit::kVolt;
      BridgeSpec lab_bridge{2, kGaugeFactor * (1 + kGaugeFactorU * normal(rng)),
                            kExcitation * (1 + kExcitationU * normal(rng)),
                            kGain * (1 + kGainU * normal(rng))};
      const BridgeSpec true_bridge{2, kGaugeFactor, kExcitation, kGain};
      const double factor = volts_to_strain(lab_bridge) / volts_to_strain(true_bridge);
      for (double& x : signals.strain[g]) x *= factor;
      ch.bridge = lab_bridge;
      m.channels.push_back(ch);
    }
    std::vector<double> delayed(signals.strain[1].size());
    delay_by_interpolation(signals.strain[1], kTriggerDelayU * normal(rng) / record.dt_s, delayed);
    signals.strain[1] = delayed;
    lab.measurement = m;

    ProcessingOptions options;
    options.dispersion.correction = false;  // the 1D model does not disperse
    const KolskySetup setup = resolve_setup(lab, signals.gauges);
    const ProcessedTest nominal = process_test(lab, signals, setup, options);
    const ProcessingResult& r = nominal.result;
    const UncertaintyResult band =
        propagate_uncertainty(lab, m, signals, options, r, {kDraws, std::uint64_t(test) + 1, 0});
    REQUIRE(band.failed == 0);
    const double unloading = r.incident_window.end_s + r.shift_incident_s;
    for (std::size_t i = 0; i < r.loading_end; ++i) {
      const double t = r.time_s[i];
      if (r.curve.equilibrium_ratio[i] > kEquilibriumThreshold || t > unloading ||
          r.curve.stress_3wave_Pa[i] < kLoadedFraction * r.peak_stress_Pa)
        continue;
      ++cover.judged;
      // No band is stated where fewer than 97.5 % of the draws reach the strain (methods.md §10).
      if (!std::isfinite(band.stress_3wave[0][i])) continue;
      const double e = r.curve.strain[i];
      const double stress = truth_at(true_stress, e), rate = truth_at(true_rate, e);
      ++cover.points;
      cover.stress += band.stress_3wave[0][i] <= stress && stress <= band.stress_3wave[2][i];
      cover.rate += band.strain_rate[0][i] <= rate && rate <= band.strain_rate[2][i];
    }
  }
  const double stress = static_cast<double>(cover.stress) / static_cast<double>(cover.points);
  const double rate = static_cast<double>(cover.rate) / static_cast<double>(cover.points);
  INFO("judged " << cover.judged << ", with a band " << cover.points << ", stress coverage "
                 << stress << ", strain-rate coverage " << rate);
  REQUIRE(cover.points > 100u * kTests / 10);
  CHECK(stress >= kCoverageLow);
  CHECK(stress <= kCoverageHigh);
  CHECK(rate >= kCoverageLow);
  CHECK(rate <= kCoverageHigh);
}

TEST_CASE("A Monte Carlo draw reads the peak stress where its nominal does",
          "[release-only][uncertainty]") {
  // The classic test is in equilibrium over 97 % of its loading, so its peak 3-wave stress is read
  // over the samples in equilibrium. A draw of the declared uncertainties moves the two face forces
  // by 1-2 % against each other, and where R sits near its 5 % bound a few draws fall out of
  // equilibrium over most of the loading. Had such a draw read its own peak over the whole loading,
  // it would be the unloading edge's transient, about twice the peak: a handful of draws in 200
  // then make the standard uncertainty several times the 95 % interval's half-width over 1.96,
  // which for a figure moved smoothly by its inputs are the same number.
  constexpr std::size_t kPeakDraws = 200;
  // A 2.5 % quantile of 200 draws is itself uncertain by about 10 %, the s.d. by 5 %: a normal
  // figure's ratio stays within 1.3 of 1 (the draws' transient gave 6).
  constexpr double kSpreadRatio = 1.3;
  const fs::path file = fs::path(SHPB_SOURCE_DIR) / "experiments/classic-al6061/scene.json";
  const Scene truth = read_scene(file);
  const SimulationResult sim = simulate(truth);
  REQUIRE(sim.stable);
  const std::size_t specimen = *truth.specimen;
  GaugeSignals record;
  record.time_s = sim.gauges.time_s;
  record.dt_s = record.time_s[1] - record.time_s[0];
  MeasurementSpec m;
  m.uncertainty = declared_uncertainty(specimen);
  for (const char* name : {"incident", "transmitted"}) {
    record.gauges.push_back(name);
    record.strain.push_back(sim.gauges.column(name));
    ChannelSpec ch;
    ch.gauge = name;
    ch.unit = SignalUnit::kVolt;
    ch.bridge = BridgeSpec{2, 2.06, 8, 200};
    m.channels.push_back(ch);
  }
  Scene lab = truth;
  lab.measurement = m;
  ProcessingOptions options;
  options.dispersion.correction = false;  // the 1D model does not disperse
  const ProcessedTest nominal =
      process_test(lab, record, resolve_setup(lab, record.gauges), options);
  REQUIRE(nominal.result.peak_in_equilibrium);
  const UncertaintyResult band =
      propagate_uncertainty(lab, m, record, options, nominal.result, {kPeakDraws, 7, 0});
  REQUIRE(band.failed == 0);
  const auto peak =
      std::find_if(band.figures.begin(), band.figures.end(),
                   [](const FigureUncertainty& f) { return f.name == "peak_stress_Pa"; });
  REQUIRE(peak != band.figures.end());
  const double half_width = (peak->high95 - peak->low95) / (2 * 1.959964);
  INFO("peak " << peak->nominal / 1e6 << " MPa, u " << peak->standard_uncertainty / 1e6
               << " MPa, 95 % interval " << peak->low95 / 1e6 << " to " << peak->high95 / 1e6);
  CHECK(peak->standard_uncertainty < kSpreadRatio * half_width);
  CHECK(half_width < kSpreadRatio * peak->standard_uncertainty);
}

}  // namespace tests_analysis_test_uncertainty
