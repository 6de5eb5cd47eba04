#pragma once
// The Kolsky bar set-up that processing needs, resolved from a scene: the incident and
// transmitter bars, their gauges and distances to the specimen, the striker; and what an
// incident plateau says of the striker's velocity.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "analysis/pulse_window.hpp"
#include "analysis/reduction.hpp"
#include "dispersion/propagation.hpp"
#include "model/scene.hpp"

namespace shpb {

// What processing needs to know about the bars and gauges, resolved from a scene.
struct KolskySetup {
  std::string incident_gauge, transmitted_gauge;
  double incident_distance_m = 0;        // incident gauge → specimen front face
  double incident_gauge_position_m = 0;  // incident gauge ← the incident bar's struck end
  // Transmitted gauge → the transmitter's far end, when that end closes the chain (a free end that
  // reflects the transmitted pulse back to the gauge).
  std::optional<double> transmitted_far_end_m;
  double transmitted_distance_m = 0;  // specimen back face → transmitted gauge
  BarSide front, back;
  BarWaveguide front_waveguide, back_waveguide;
  SpecimenGeometry specimen;
  double specimen_transit_s = 0;  // L_s / c0 of the specimen (0 when its material is not given)
  std::optional<double> specimen_impedance_kg_s;  // ρ c0 A_s, when its modulus is given
  // Striker (the bar left of the incident bar), for the inferred velocity: impedance ratio.
  std::optional<double> striker_impedance_kg_s;
  // The striker's round trip 2 L_s/c_s, its pulse's length. A striker much stiffer than the
  // incident bar (Z_s ≥ 2 Z_b) gives a decaying staircase, not a plateau (docs/methods.md §4):
  // its first step, one round trip long, sets V.
  std::optional<double> striker_round_trip_s;
  bool striker_staircase = false;
  double incident_impedance_kg_s = 0;
  std::optional<double> striker_velocity_m_s;  // as the scene gives it
  // Travel time per metre of bar beyond 1/c0, from the lab's calibrated reflected time
  // (measurement.reflected_time; 0 without one): what the real bars add to the 1D model's travel.
  double excess_delay_s_per_m = 0;
  // A bar between the striker and the incident bar (a pulse shaper): the incident plateau is then
  // set by the shaper's flow, and the velocity inferred from it means nothing.
  bool pulse_shaper = false;
};

// The striker velocity an incident plateau ε_I implies, striker on the incident bar
// (docs/methods.md §4): the bar's particle velocity v = c0 ε_I = V Z_s/(Z_s + Z_b), so
// V = c0 ε_I (Z_s + Z_b)/Z_s; the striker's impedance Z_s is the incident bar's Z_b when the set-up
// has none. Used by `process`, `compare` and `fit`, with the plateau at the struck end.
double striker_velocity_from_plateau(const KolskySetup& setup, double incident_plateau_strain);

// When the transmitted front of an incident front at its gauge at `incident_s` reaches its own
// gauge in the 1D bars: d/c0 to the specimen, L_s/c_s through it (0 without its modulus), d'/c0'
// on.
double transmitted_arrival_s(const KolskySetup& setup, double incident_s);

// The incident pulse's plateau (pulse_window.hpp plateau_level) where the striker struck: an
// elastic bar's is the gauge's; a viscoelastic bar's pulse has decayed on its way to the gauge and
// is moved back to the struck end as a velocity first (docs/methods.md §5.1). Of a staircase, the
// level of its first step (striker_staircase). `record` is the rest-levelled gauge strain, `w`
// its incident pulse.
double struck_end_plateau(const KolskySetup& setup, std::span<const double> record, double dt,
                          const PulseWindow& w);

// A calibrated reflected time further than this fraction from 2d/c0 is not the same bar or gauge:
// a wave speed or a gauge position off by more than 5 % is a wrong scene, not a calibration.
inline constexpr double kReflectedTimeRange = 0.05;

// Resolves the set-up: the specimen's neighbours are the incident and transmitter bars; their
// gauges with a signal in `available` are used. Throws InputError naming the scene if impossible.
KolskySetup resolve_setup(const Scene& scene, const std::vector<std::string>& available);

// The end of the plateau of the pulse that starts at `onset` and ends at `end`: a staircase's
// first step ends after the striker's round trip.
std::size_t first_step_end(const KolskySetup& setup, std::size_t onset, std::size_t end, double dt);

}  // namespace shpb
