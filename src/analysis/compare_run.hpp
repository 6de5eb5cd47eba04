#pragma once
// `shpb compare` as a library, around the simulation its command runs (docs/methods.md §4, §5):
//  1. plan_comparison: the measured gauges read, the incident, reflected and transmitted pulses
//     found in them; the striker velocity (given, else measurement.striker_velocity, else inferred
//     from the measured incident plateau, v_bar = c0 ε_I and V = v_bar (Z_s + Z_b)/Z_s) set on
//     the scene, and the duration extended to cover the measured pulses;
//  2. (the caller simulates the planned scene);
//  3. compare_simulation: the simulation put on the measurement's clock by the incident pulses'
//     fronts, each pulse moved through the Pochhammer–Chree dispersion of the distance it
//     travelled (analysis/pulse_overlay.hpp), compared in windows around the measured pulses
//     (analysis/comparison.hpp);
//  4. write_comparison: comparison.csv, signals.csv and summary.json (docs/outputs.md).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "analysis/comparison.hpp"
#include "analysis/gauge_signals.hpp"
#include "analysis/pulse_overlay.hpp"
#include "core/time_series.hpp"
#include "model/scene.hpp"

namespace shpb {

struct ComparePlan {
  Scene scene;  // with the striker velocity used and, if needed, the extended duration
  GaugeSignals measured;
  MeasuredPulses found;
  std::size_t striker = 0;
  double velocity_m_s = 0, inferred_velocity_m_s = 0, scene_velocity_m_s = 0;
  std::string velocity_source;
  std::optional<double> extended_duration_s;
  std::vector<std::string> warnings;
};

// A striker velocity beyond this would yield any bar steel many times over (v_yield = 2 σ_y/(ρ c0)
// is ~100 m/s for maraging steel): not a split Hopkinson bar test.
inline constexpr double kMaxStrikerVelocity_m_s = 1000;

// InputError for a scene without measured signals, striker, incident bar or specimen, or a given
// velocity out of (0, kMaxStrikerVelocity_m_s].
ComparePlan plan_comparison(Scene scene, std::optional<double> striker_velocity_m_s);

// What the caller's simulation gives the summary.
struct SimulationFacts {
  bool stable = true;
  double wall_time_s = 0, energy_error = 0;
  std::vector<std::string> warnings;
};

struct CompareOutcome {
  Overlay overlay;
  std::vector<PulseComparison> results;  // one per compared pulse, as overlay.pulses
  std::vector<std::string> warnings;     // the plan's, the overlay's and the simulation's
};

CompareOutcome compare_simulation(const ComparePlan& plan, const TimeSeries& simulated_gauges,
                                  bool dispersion, const SimulationFacts& simulation);

void write_comparison(const ComparePlan& plan, const CompareOutcome& outcome,
                      const TimeSeries& simulated_gauges, bool dispersion,
                      const SimulationFacts& simulation, const std::filesystem::path& dir);

}  // namespace shpb
