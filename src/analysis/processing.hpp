#pragma once
// The whole reduction of one test (docs/outputs.md `process`): incident pulse found on the incident
// gauge, the three pulses moved to the specimen faces (Pochhammer–Chree or pure delay), cut to a
// common window, reduced (reduction.hpp) and summarised. Library function, reused by `compare`.
#include <optional>
#include <string>
#include <vector>

#include "analysis/reduction.hpp"
#include "core/signal_gauges.hpp"
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
  // Striker (the bar left of the incident bar), for the inferred velocity: impedance ratio.
  std::optional<double> striker_impedance_kg_s;
  double incident_impedance_kg_s = 0;
  std::optional<double> striker_velocity_m_s;  // as the scene gives it
};

// Resolves the set-up: the specimen's neighbours are the incident and transmitter bars; their
// gauges with a signal in `available` are used. Throws InputError naming the scene if impossible.
KolskySetup resolve_setup(const Scene& scene, const std::vector<std::string>& available);

struct ProcessingOptions {
  DispersionSpec dispersion;  // correction on/off, amplitude factors, cut-off
  PulseWindows windows;       // manual windows (gauge clocks) override detection
  std::string scene_file;     // named in error messages
};

struct WindowReport {
  std::string gauge;
  double start_s = 0, end_s = 0;  // on the gauge's own clock
  bool detected = false;          // false: from the scene's `windows`
};

struct ProcessingResult {
  std::vector<double> time_s;  // at the specimen faces, on the signals' clock
  std::vector<double> incident, reflected, transmitted;  // strains at the faces, tension positive
  Curve curve;
  WindowReport incident_window, reflected_window, transmitted_window;
  double face_start_s = 0, face_end_s = 0;
  double shift_incident_s = 0, shift_reflected_s = 0, shift_transmitted_s = 0;
  std::optional<double> reflected_onset_offset_s;  // detected − expected (alignment check)
  double incident_plateau_strain = 0;              // compressive strain magnitude at the face
  double inferred_striker_velocity_m_s = 0;
  double plateau_strain_rate_1_s = 0;
  double peak_stress_Pa = 0;
  double max_strain = 0;
  std::optional<double> time_to_equilibrium_s;
  double cutoff_Hz = 0;  // 0 without dispersion correction
  std::vector<std::string> warnings;
};

// Equilibrium is reached where R ≤ 5 % (a common criterion, e.g. Gray 2000) while the mean force
// is above 20 % of its peak.
inline constexpr double kEquilibriumThreshold = 0.05;

ProcessingResult process_signals(const GaugeSignals& signals, const KolskySetup& setup,
                                 const ProcessingOptions& options);

// A record clipped by its amplifier or digitizer has flat tops at its extremes: at least
// kClippedRun consecutive samples exactly equal to the record's maximum (or minimum). A real
// pulse's plateau carries noise and ringing, so exact repeats of the extreme are the signature.
// Also warns of a record too short to hold a pulse (fewer than kMinRecordSamples samples).
inline constexpr std::size_t kClippedRun = 5;
inline constexpr std::size_t kMinRecordSamples = 16;
std::vector<std::string> signal_warnings(const GaugeSignals& signals);

}  // namespace shpb
