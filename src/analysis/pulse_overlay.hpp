#pragma once
// A simulated test laid over its measurement, pulse by pulse (what `shpb compare` shows and what
// `shpb fit` minimises; docs/methods.md §5, §9):
//  1. the measured incident, reflected and transmitted pulses are found once;
//  2. the simulation (t = 0 at impact) is put on the measured clock by matching the incident
//     pulses' front times, the mean time they cross the levels between 40 and 60 % of their
//     plateaus (plus an optional extra shift);
//  3. a 1D bar does not disperse and a real one does: each simulated pulse is moved through the
//     Pochhammer–Chree dispersion of the distance it travelled from the impact face (minus the
//     non-dispersive delay the 1D model already has).
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "analysis/kolsky_setup.hpp"
#include "analysis/pulse_window.hpp"
#include "analysis/signal_checks.hpp"
#include "core/time_series.hpp"
#include "dispersion/dispersion_table.hpp"
#include "model/scene.hpp"

namespace shpb {

// The measured side of a test: the two gauges' strains and where their pulses are.
struct MeasuredPulses {
  KolskySetup setup;
  std::vector<double> time_s;
  double dt_s = 0;
  // Strain at the incident and transmitted gauges from their rest levels (rest_signal, then
  // the median before the first pulse).
  std::vector<double> incident, transmitted;
  Baseline incident_baseline, transmitted_baseline;  // level 0: removed; the records' noise
  // Standard deviation of each removed rest level (strain): an offset common to every sample of
  // the record's pulses, that their residuals do not show.
  double incident_rest_sd = 0, transmitted_rest_sd = 0;
  PulseWindow incident_window;
  std::optional<PulseWindow> reflected_window, transmitted_window;
  double incident_plateau = 0;    // |plateau| of the incident pulse, strain
  double struck_end_plateau = 0;  // the same where the striker struck (kolsky_setup.hpp)
  // Standard deviation of the incident pulse's front time (the clock) from the baseline's noise,
  // taken as white: what the record noise alone makes of the alignment.
  double incident_front_sd_s = 0;
  // Samples of the incident front strictly between 40 and 60 % of its plateau: none, and the
  // record does not say where in a sample interval the clocks meet.
  double incident_front_samples = 0;
  // A clipped channel's samples at its clip level (ClippedSamples, signal_checks.hpp), in the units
  // of `incident` and `transmitted`.
  std::optional<ClippedSamples> incident_clipped, transmitted_clipped;
  // A channel turned over, a pulse the record does not hold or cuts short.
  std::vector<std::string> warnings;
};

// The clipped samples of the transmitted or the incident channel, or null when it is not clipped.
inline const ClippedSamples* clipped_channel(const MeasuredPulses& m, bool transmitted) {
  const auto& c = transmitted ? m.transmitted_clipped : m.incident_clipped;
  return c ? &*c : nullptr;
}

// Finds the pulses in `signals`, each record from its rest level before its first pulse and
// turned over when that pulse has the other sign than the test's (as `process` turns it);
// InputError (naming the scene) when there is no incident pulse.
MeasuredPulses find_measured_pulses(const Scene& scene, const GaugeSignals& signals);

// A compared window, in samples of the measured grid.
struct OverlaidPulse {
  std::string gauge, name;  // name: incident | reflected | transmitted
  std::size_t begin = 0, end = 0;
  double distance_m = 0;  // travelled from the impact face to the gauge
  bool transmitted = false;
};

struct Overlay {
  double offset_s = 0;   // measured time = simulated time + offset_s
  double t_sim_end = 0;  // last simulated time, on the simulation's clock
  // Simulated strains on the measured clock: raw (1D) and with each pulse dispersed.
  std::vector<double> raw_incident, raw_transmitted, incident, transmitted;
  std::vector<OverlaidPulse> pulses;  // windows where the simulation exists
  std::vector<std::string> warnings;  // a pulse the simulation ends before
};

// The last measured sample a comparison looks at: the end of the latest widened pulse window
// (what a simulation must cover).
std::size_t last_compared_sample(const MeasuredPulses& measured);

class PulseOverlay {
 public:
  // `dispersion`: move simulated pulses through Pochhammer–Chree dispersion (tables built here).
  PulseOverlay(const Scene& scene, MeasuredPulses measured, bool dispersion);

  const MeasuredPulses& measured() const { return measured_; }
  bool dispersion() const { return front_table_.has_value(); }

  // Lays the simulated gauges (of `scene`) over the measurement, later by `shift_s`, and the
  // transmitted pulse later still by `transmitted_delay_s` (its channel's delay). Each pulse is
  // dispersed with the wave speed of `scene`'s bars (which `fit` may free). Throws NumericalError
  // if the simulation has no incident pulse. Safe to call from several threads at once.
  Overlay overlay(const Scene& scene, const TimeSeries& simulated_gauges, double shift_s = 0,
                  double transmitted_delay_s = 0) const;

 private:
  // A simulated gauge signal y (sample interval dt) as it arrives after `distance_m` of the front
  // (incident) or back (transmitter) bar: moved through Pochhammer–Chree dispersion and advanced by
  // distance/c0, the delay the 1D model already has; on y's own clock (longer by the room the
  // slowest components need).
  std::vector<double> dispersed(const std::vector<double>& y, double dt, double distance_m,
                                bool back, const BarWaveguide& guide) const;

  MeasuredPulses measured_;
  std::optional<DispersionTable> front_table_, back_table_;
};

}  // namespace shpb
