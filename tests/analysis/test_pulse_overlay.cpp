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

}  // namespace

TEST_CASE("The clock of a noisy copy of a simulation is its own, to the predicted scatter",
          "[overlay]") {
  const fs::path dir = shpb_test::scratch_dir("overlay_clock");
  const fs::path copper = fs::path(SHPB_SOURCE_DIR) / "specimens/ofhc-copper.json";
  const fs::path file = dir / "scene.json";
  std::ofstream(file) << shpb_test::synthetic_scene(18.5, copper, "asynchronous").dump(1);
  const shpb::Scene scene = shpb::read_scene(file);
  const shpb::SimulationResult sim = shpb::simulate(scene);
  REQUIRE(sim.stable);

  std::mt19937 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  double sum = 0, sum2 = 0, predicted = 0;
  for (int k = 0; k < kDraws; ++k) {
    shpb::GaugeSignals g;
    g.time_s = sim.gauges.time_s;
    g.dt_s = 1.0 / scene.simulation.sample_rate_Hz;
    for (const char* name : {"incident", "transmitted"}) {
      std::vector<double> x = sim.gauges.column(name);
      double peak = 0;
      for (double v : x) peak = std::max(peak, std::abs(v));
      for (double& v : x) v += kNoise * peak * normal(rng);
      g.gauges.push_back(name);
      g.strain.push_back(x);
    }
    const shpb::PulseOverlay overlay(scene, shpb::find_measured_pulses(scene, g), false);
    const double offset = overlay.overlay(scene, sim).offset_s;
    predicted = overlay.measured().incident_front_sd_s;
    sum += offset, sum2 += offset * offset;
  }
  const double mean = sum / kDraws, rms = std::sqrt(sum2 / kDraws);
  INFO("mean offset " << mean << " s, rms " << rms << " s, predicted sd " << predicted << " s");
  REQUIRE(predicted > 0);
  CHECK(std::abs(rms / predicted - 1) <= kSdTolerance);
  CHECK(std::abs(mean) <= kBiasStandardErrors * predicted / std::sqrt(kDraws));
}
