// The clock of compare and fit (analysis/pulse_overlay.hpp, docs/methods.md §9): a simulated test
// laid over a noisy copy of its own gauge signals must land on its own clock, with the scatter of
// the offset over noise draws that the front time's standard deviation predicts.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "../fit/synthetic_scene.hpp"
#include "../scratch.hpp"
#include "analysis/gauge_signals.hpp"
#include "analysis/pulse_overlay.hpp"
#include "dispersion/dispersion_table.hpp"
#include "dispersion/propagation.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_analysis_test_pulse_overlay {

namespace fs = std::filesystem;

namespace {

// Noise draws: the root mean square of the offsets over N draws of a Gaussian estimator is within
// a few 1/√(2N) of its standard deviation (N = 200: ±5 % per standard error).
constexpr int kDraws = 200;
// The predicted standard deviation must hold within ±20 % (4 standard errors of the RMS over 200
// draws; the formula linearises the clipped front and ignores the plateau's own noise).
constexpr double kSdTolerance = 0.2;
// The mean offset: no bias beyond 4 standard errors of the mean.
constexpr double kBiasStandardErrors = 4.0;
// 1 % of the peak: the synthetic campaign's record noise.
constexpr double kNoise = 0.01;

// The synthetic 2000 /s OFHC copper test (tests/fit), simulated once.
struct SyntheticRun {
  shpb::Scene scene;
  shpb::SimulationResult sim;
};
SyntheticRun synthetic_run(const std::string& name) {
  const fs::path file = shpb_test::scratch_dir(name) / "scene.json";
  const fs::path copper = fs::path(SHPB_SOURCE_DIR) / "specimens/ofhc-copper.json";
  std::ofstream(file) << shpb_test::synthetic_scene(18.5, copper, "asynchronous").dump(1);
  SyntheticRun r{shpb::read_scene(file), {}};
  r.sim = shpb::simulate(r.scene);
  REQUIRE(r.sim.stable);
  return r;
}
// The simulated test's gauge signals as a record: each gauge's strain on the simulation's grid.
shpb::GaugeSignals record_of(const shpb::Scene& scene, const shpb::SimulationResult& sim) {
  shpb::GaugeSignals g;
  g.time_s = sim.gauges.time_s;
  g.dt_s = 1.0 / scene.simulation.sample_rate_Hz;
  for (const char* name : {"incident", "transmitted"}) {
    g.gauges.push_back(name);
    g.strain.push_back(sim.gauges.column(name));
  }
  return g;
}
// Both clocks are the same record's: what is left is the front-time estimator's interpolation
// between samples, far below a sample interval (100 ns here).
constexpr double kSameClock_s = 5e-9;
}  // namespace

TEST_CASE("The clock of a noisy copy of a simulation is its own, to the predicted scatter",
          "[overlay]") {
  const auto [scene, sim] = synthetic_run("overlay_clock");

  std::mt19937 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  double sum = 0, sum2 = 0, predicted = 0;
  for (int k = 0; k < kDraws; ++k) {
    shpb::GaugeSignals g = record_of(scene, sim);
    for (std::vector<double>& x : g.strain) {
      double peak = 0;
      for (double v : x) peak = std::max(peak, std::abs(v));
      for (double& v : x) v += kNoise * peak * normal(rng);
    }
    const shpb::PulseOverlay overlay(scene, shpb::find_measured_pulses(scene, g), false);
    const double offset = overlay.overlay(scene, sim.gauges).offset_s;
    predicted = overlay.measured().incident_front_sd_s;
    sum += offset, sum2 += offset * offset;
  }
  const double mean = sum / kDraws, rms = std::sqrt(sum2 / kDraws);
  INFO("mean offset " << mean << " s, rms " << rms << " s, predicted sd " << predicted << " s");
  REQUIRE(predicted > 0);
  CHECK(std::abs(rms / predicted - 1) <= kSdTolerance);
  CHECK(std::abs(mean) <= kBiasStandardErrors * predicted / std::sqrt(kDraws));
}

TEST_CASE("Dispersed bars: the clock aligns the dispersed simulated incident pulse", "[overlay]") {
  // A record whose incident pulse has dispersed over the bar from the impact face to the gauge, as
  // a real one has: the simulation, dispersed over the same distance, lies on it on its own clock
  // (the 1D pulse's front, undispersed, would put it later by the dispersion's delay of the front).
  const auto [scene, sim] = synthetic_run("overlay_dispersed");
  shpb::GaugeSignals g = record_of(scene, sim);
  const shpb::MeasuredPulses plain = shpb::find_measured_pulses(scene, g);
  const shpb::KolskySetup& setup = plain.setup;
  const double distance = scene.bars[*scene.specimen - 1].length_m - setup.incident_distance_m;
  const shpb::DispersionTable table =
      shpb::DispersionTable::up_to(setup.front_waveguide.poisson, shpb::kDefaultCutoffFaOverC0);
  shpb::Propagator prop(table, setup.front_waveguide, shpb::PropagationOptions{});
  std::vector<double>& x = g.strain[0];
  const std::size_t n = x.size();
  x.resize(2 * n, 0.0);
  const std::vector<double> moved = prop.propagate(x, g.dt_s, distance);
  // The delay d/c0 of the 1D model is kept: advanced by it to the nearest sample, so the record
  // is later than the simulation's dispersed pulse by the remaining fraction of a sample.
  const double delay_samples = distance / setup.front_waveguide.c0_m_s / g.dt_s;
  const auto advance = static_cast<std::size_t>(std::lround(delay_samples));
  const double expected = (delay_samples - static_cast<double>(advance)) * g.dt_s;
  x.assign(moved.begin() + static_cast<long>(advance),
           moved.begin() + static_cast<long>(advance + n));
  const shpb::PulseOverlay overlay(scene, shpb::find_measured_pulses(scene, g), true);
  const double offset = overlay.overlay(scene, sim.gauges).offset_s;
  INFO("offset " << offset << " s, expected " << expected << " s");
  CHECK(std::abs(offset - expected) <= kSameClock_s);
}

TEST_CASE("A calibrated reflected time delays the reflected and transmitted pulses by its excess",
          "[overlay]") {
  auto [scene, sim] = synthetic_run("overlay_reflected_time");
  const shpb::GaugeSignals g = record_of(scene, sim);
  const shpb::KolskySetup setup = shpb::find_measured_pulses(scene, g).setup;
  // The real bar takes 20 samples (2 µs) longer for the round trip than 2d/c0.
  const double dt = g.dt_s, excess = 20 * dt;
  const double d = setup.incident_distance_m, d_t = setup.transmitted_distance_m;
  if (!scene.measurement) scene.measurement.emplace();
  scene.measurement->reflected_time_s = 2 * d / setup.front.c0_m_s + excess;
  const shpb::MeasuredPulses m = shpb::find_measured_pulses(scene, g);
  const shpb::Overlay o = shpb::PulseOverlay(scene, m, false).overlay(scene, sim.gauges);
  REQUIRE(o.offset_s == 0);  // the incident pulse is unchanged: the same clock
  // Over each pulse's window the laid-over signal is the simulation later by the excess: 2d for
  // the reflected pulse, d + d' of bar for the transmitted one.
  const auto later = [&](const std::vector<double>& laid, const std::vector<double>& own,
                         const shpb::PulseWindow& w, double delay_s) {
    double worst = 0, peak = 0;
    for (std::size_t k = w.onset; k < w.end; ++k) {
      const double t = static_cast<double>(k) - delay_s / dt;
      const auto i = static_cast<std::size_t>(std::floor(t));
      const double f = t - static_cast<double>(i);
      worst = std::max(worst, std::abs(laid[k] - ((1 - f) * own[i] + f * own[i + 1])));
      peak = std::max(peak, std::abs(own[k]));
    }
    return worst / peak;
  };
  REQUIRE(m.reflected_window);
  REQUIRE(m.transmitted_window);
  // Linear interpolation of the same samples: equal to round-off.
  constexpr double kRoundOff = 1e-12;
  CHECK(later(o.incident, sim.gauges.column("incident"), *m.reflected_window, excess) <= kRoundOff);
  CHECK(later(o.transmitted, sim.gauges.column("transmitted"), *m.transmitted_window,
              excess * (d + d_t) / (2 * d)) <= kRoundOff);
  // A round trip 5 % off 2d/c0 is not a calibration of this bar: refused, naming the key.
  scene.measurement->reflected_time_s = 1.06 * 2 * d / setup.front.c0_m_s;
  CHECK_THROWS_WITH(shpb::find_measured_pulses(scene, g),
                    Catch::Contains("measurement.reflected_time"));
}

}  // namespace tests_analysis_test_pulse_overlay
