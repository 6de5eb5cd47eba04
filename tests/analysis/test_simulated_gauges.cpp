#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <vector>

#include "analysis/processing.hpp"
#include "solver/simulation.hpp"
#include "specimen_truth.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_analysis_test_simulated_gauges {

using namespace shpb;

using shpb_test::moving_average;

namespace {

// On the loaded plateau after equilibrium, the reduction of the
// simulator's gauges matches the model's own specimen truth (specimen.csv) within 2 % — RMS for
// stress and strain rate (relative to the peak stress / the plateau rate), maximum for strain.
// The truth is averaged over one specimen wave transit L_s/c_s: the length-averaged specimen rate
// rings with the contact interfaces at that period, which a reduction from bar-end motion cannot
// and should not see.
constexpr double kAgreement = 0.02;

double interpolate(const std::vector<double>& t, const std::vector<double>& y, double x) {
  const auto j = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), x) - t.begin());
  if (j == 0) return y.front();
  if (j >= t.size()) return y.back();
  const double a = (x - t[j - 1]) / (t[j] - t[j - 1]);
  return y[j - 1] + a * (y[j] - y[j - 1]);
}

struct Agreement {
  double stress_rms, rate_rms, strain_max;
};

Agreement process_simulation(const Scene& scene) {
  const SimulationResult sim = simulate(scene);
  INFO(sim.failure);
  REQUIRE(sim.stable);
  GaugeSignals g;
  g.time_s = sim.gauges.time_s;
  g.dt_s = g.time_s[1] - g.time_s[0];
  for (const char* name : {"incident", "transmitted"}) {
    g.gauges.push_back(name);
    g.strain.push_back(sim.gauges.column(name));
  }
  ProcessingOptions o;
  o.dispersion.correction = false;  // the 1D model does not disperse
  const ProcessingResult r = process_signals(g, resolve_setup(scene, g.gauges), o);
  const BarSpec& specimen = scene.bars[*scene.specimen];
  const auto& ts = sim.specimen.time_s;
  const double transit = specimen.length_m / specimen.material.wave_speed_m_s();
  const auto half = static_cast<std::size_t>(0.5 * transit / (ts[1] - ts[0]));
  const auto stress = moving_average(sim.specimen.column("stress_Pa"), half);
  const auto rate = moving_average(sim.specimen.column("strain_rate_1_s"), half);
  const auto& strain = sim.specimen.column("strain");
  // The processed strain starts at the window start; the truth's strain there is the offset.
  const double t0 = r.time_s.front();
  const double strain0 = interpolate(ts, strain, t0);
  const double peak_stress = *std::max_element(stress.begin(), stress.end());
  const double peak_strain = *std::max_element(strain.begin(), strain.end());
  const double unloading = r.incident_window.end_s + r.shift_incident_s;
  Agreement a{0, 0, 0};
  std::size_t count = 0;
  for (std::size_t i = 0; i < r.time_s.size(); ++i) {
    const double t = r.time_s[i];
    // Loaded plateau after equilibrium: R ≤ 5 %, mean stress above 20 % of its peak, before the
    // incident pulse ends at the front face.
    if (r.curve.equilibrium_ratio[i] > kEquilibriumThreshold || t > unloading ||
        r.curve.stress_3wave_Pa[i] < 0.2 * r.peak_stress_Pa)
      continue;
    ++count;
    const double ds = (r.curve.stress_3wave_Pa[i] - interpolate(ts, stress, t)) / peak_stress;
    const double dr =
        (r.curve.strain_rate_1_s[i] - interpolate(ts, rate, t)) / r.plateau_strain_rate_1_s;
    a.stress_rms += ds * ds;
    a.rate_rms += dr * dr;
    a.strain_max =
        std::max(a.strain_max,
                 std::abs(r.curve.strain[i] + strain0 - interpolate(ts, strain, t)) / peak_strain);
  }
  // At least half the window must qualify, or the comparison says little.
  REQUIRE(count > r.time_s.size() / 2);
  a.stress_rms = std::sqrt(a.stress_rms / static_cast<double>(count));
  a.rate_rms = std::sqrt(a.rate_rms / static_cast<double>(count));
  return a;
}

}  // namespace

TEST_CASE("Processing the simulator's gauges recovers the specimen truth after equilibrium",
          "[analysis][processing][simulation]") {
  Scene scene =
      read_scene(std::filesystem::path(SHPB_SOURCE_DIR) / "experiments/classic-al6061/scene.json");
  SECTION("Johnson-Cook Al 6061-T6 specimen (experiments/classic-al6061)") {
    const Agreement a = process_simulation(scene);
    CHECK(a.stress_rms < kAgreement);
    CHECK(a.rate_rms < kAgreement);
    CHECK(a.strain_max < kAgreement);
  }
  SECTION("elastic aluminium specimen in the same bars") {
    MaterialSpec aluminium;
    aluminium.name = "elastic aluminium";
    aluminium.density_kg_m3 = 2700;
    aluminium.youngs_modulus_Pa = 70e9;
    aluminium.poisson_ratio = 0.33;
    scene.bars[*scene.specimen].material = aluminium;
    const Agreement a = process_simulation(scene);
    CHECK(a.stress_rms < kAgreement);
    CHECK(a.rate_rms < kAgreement);
    CHECK(a.strain_max < kAgreement);
  }
}

}  // namespace tests_analysis_test_simulated_gauges
