#pragma once
// The whole reduction of one test (docs/outputs.md `process`): incident pulse found on the incident
// gauge, the three pulses moved to the specimen faces (Pochhammer–Chree or pure delay), cut to a
// common window, reduced (reduction.hpp) and summarised. Library function, reused by `compare`.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "analysis/gauge_signals.hpp"
#include "analysis/reduction.hpp"
#include "dispersion/propagation.hpp"
#include "model/scene.hpp"

namespace shpb {

// What processing needs to know about the bars and gauges, resolved from a scene.
struct KolskySetup {
  std::string incident_gauge, transmitted_gauge;
  double incident_distance_m = 0;     // incident gauge → specimen front face
  double transmitted_distance_m = 0;  // specimen back face → transmitted gauge
  BarSide front, back;
  BarWaveguide front_waveguide, back_waveguide;
  SpecimenGeometry specimen;
  double specimen_transit_s = 0;  // L_s / c0 of the specimen (0 when its material is not given)
  // Striker (the bar left of the incident bar), for the inferred velocity: impedance ratio.
  std::optional<double> striker_impedance_kg_s;
  double incident_impedance_kg_s = 0;
  std::optional<double> striker_velocity_m_s;  // as the scene gives it
  // Travel time per metre of bar beyond 1/c0, from the lab's calibrated reflected time
  // (measurement.reflected_time; 0 without one): what the real bars add to the 1D model's travel.
  double excess_delay_s_per_m = 0;
};

// A calibrated reflected time further than this fraction from 2d/c0 is not the same bar or gauge:
// a wave speed or a gauge position off by more than 5 % is a wrong scene, not a calibration.
inline constexpr double kReflectedTimeRange = 0.05;

// Resolves the set-up: the specimen's neighbours are the incident and transmitter bars; their
// gauges with a signal in `available` are used. Throws InputError naming the scene if impossible.
KolskySetup resolve_setup(const Scene& scene, const std::vector<std::string>& available);

// The curve ends at the strain maximum or where the 3-wave stress falls below half its peak after
// the peak (fracture, or the end of the pulse), whichever comes first.
inline constexpr double kDefaultLoadDrop = 0.5;

struct ProcessingOptions {
  DispersionSpec dispersion;            // correction on/off, amplitude factors, cut-off
  PulseWindows windows;                 // manual windows (gauge clocks) override detection
  std::string scene_file;               // named in error messages
  double load_drop = kDefaultLoadDrop;  // the curve ends where σ falls by this fraction; 0: off
  // A tension test (split Hopkinson tension bar): the signals are given negated, so the
  // reduction's "compression positive" reads "tension positive"; named in warnings.
  bool tension = false;
};

struct WindowReport {
  std::string gauge;
  double start_s = 0, end_s = 0;  // on the gauge's own clock
  bool detected = false;          // false: from the scene's `windows`
};

// Equilibrium over the loaded time (mean force ≥ 20 % of its peak), times on the faces' clock.
struct Equilibrium {
  std::optional<std::pair<double, double>> loaded_s;   // first and last loaded sample
  double fraction = 0;                                 // of the loaded samples with R ≤ 5 %
  std::optional<std::pair<double, double>> longest_s;  // longest run with R ≤ 5 %
  std::optional<double> holds_from_s;  // start of the run that lasts until unloading
};

struct ProcessingResult {
  std::vector<double> time_s;  // at the specimen faces, on the signals' clock
  std::vector<double> incident, reflected, transmitted;  // strains at the faces, tension positive
  Curve curve;
  WindowReport incident_window, reflected_window, transmitted_window;
  double face_start_s = 0, face_end_s = 0;
  double shift_incident_s = 0, shift_reflected_s = 0, shift_transmitted_s = 0;
  std::optional<double> reflected_onset_offset_s;    // detected − expected (alignment check)
  std::optional<double> transmitted_onset_offset_s;  // detected − expected (alignment check)
  double transmitted_rise_s = 0;                     // onset to half peak of the transmitted front
  bool alignment_suspect = false;      // an onset is off: a gauge position or wave speed is wrong
  double incident_plateau_strain = 0;  // compressive strain magnitude at the face
  double inferred_striker_velocity_m_s = 0;
  double plateau_strain_rate_1_s = 0;       // level of the top part of the rate (plateau_level)
  bool strain_rate_has_plateau = false;     // the rate stays at that level long enough to quote it
  double strain_rate_plateau_fraction = 0;  // longest run within ±10 % / samples with rate > 0
  double mean_strain_rate_1_s = 0;          // over the loading, where the rate is positive
  std::size_t loading_end = 0;  // curve samples [0, loading_end) are the loading; the rest is cut
  std::string loading_end_how;
  double peak_stress_Pa = 0;
  double max_strain = 0;
  Equilibrium equilibrium;
  std::optional<double> time_to_equilibrium_s;  // holds_from_s − start of the face window
  double cutoff_Hz = 0;                         // 0 without dispersion correction
  std::vector<std::string> warnings;
};

// Equilibrium holds where R ≤ 5 % (a common criterion, e.g. Gray 2000) while the mean force is
// above 20 % of its peak; it is reached where it then holds until unloading.
inline constexpr double kEquilibriumThreshold = 0.05;

ProcessingResult process_signals(const GaugeSignals& signals, const KolskySetup& setup,
                                 const ProcessingOptions& options);

// A record clipped by its amplifier or digitizer piles up at its extreme level: every sample the
// range cut off lands there, so the level holds at least kClippedPileUp times as many samples as
// the next level inward, and at least kClippedRun of them follow one another. An unclipped
// record only touches its extreme: a noisy or ringing top spreads over the levels below it, so
// its extreme level holds fewer samples than the next one even where a coarse (8-bit) digitizer
// repeats the level for several samples running.
// Also warns of a record too short to hold a pulse (fewer than kMinRecordSamples samples).
inline constexpr std::size_t kClippedRun = 5;
inline constexpr double kClippedPileUp = 2.0;
inline constexpr std::size_t kMinRecordSamples = 16;
std::vector<std::string> signal_warnings(const GaugeSignals& signals);

}  // namespace shpb
