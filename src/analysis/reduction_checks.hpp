#pragma once
// The quality judgements of one reduction (processing.hpp, process_signals): whether the onsets
// agree with the geometry, whether the record resolves the front, the strain and the stress,
// whether the strain rate has a plateau, equilibrium, and the warnings a reader of the curve needs.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "analysis/kolsky_setup.hpp"
#include "analysis/processing.hpp"
#include "analysis/reduction.hpp"
#include "model/scene.hpp"

namespace shpb {

// The transmitted pulse rises over a few transits of the specimen (ring-up, Davies & Hunter).
inline constexpr double kRingUpTransits = 4;
// A strain-rate plateau: within ±10 % of its level (a constant-rate test is called so within
// about that) for at least 30 % of the loading.
inline constexpr double kPlateauBand = 0.10;
inline constexpr double kPlateauMinFraction = 0.30;

// How far an onset may lie from the geometric one with nothing mistimed: a few samples or a
// fraction of its pulse's travel time from the specimen face to its gauge.
double alignment_tolerance_s(double dt, double travel_s);

// A detected onset further from the geometric one than a few samples or 2 % of the travel time
// means a gauge position or a wave speed in the scene is wrong: the reflected pulse has travelled
// 2 d_I (so its offset δ_R = 2 e_I/c0), the transmitted one d_I + d_T (δ_T − δ_R/2 = e_T/c0).
// An incident gauge or bar mistimed moves the transmitted onset (timed from the same incident
// pulse) by half the reflected offset. A reflected offset the transmitted onset does not share,
// while that is on its geometric time, is the reflected pulse's own shape instead: its foot lies
// where the specimen starts to reflect (a thin, stiff wafer under a shaped ramp reflects next to
// nothing until it yields), and no gauge is suspected.
void check_alignment(ProcessingResult& r, const KolskySetup& k, double dt,
                     std::vector<std::string>& warnings);

// The 3-wave strain rate is the difference of the face velocities over L_s (docs/methods.md §6).
// A specimen much stiffer than the bars that stays elastic (a thin metal wafer) moves with them:
// its faces move relative to each other at a small fraction of c0 ε_I, and that fraction divides
// every error of the pulses' amplitudes. The stress, from the forces, is unaffected.
void check_strain_resolution(const Curve& c, const std::vector<double>& t, std::size_t n,
                             const KolskySetup& k, const ProcessingOptions& o, ProcessingResult& r);

// Says when a polymer bar's low-pass leaves the inferred striker velocity low (the rule:
// kStrikerPulseCycles, reduction_checks.cpp).
void check_struck_end_band(const KolskySetup& k, ProcessingResult& r);

// The incident pulse rising from the rest band to half its peak within a sample interval: the
// record does not say where in that interval the front lies, so the strain the specimen took while
// it rose is known to about ±½ dt × the rate (the trapezoid rule over the window, which opens at
// rest, takes the middle; docs/methods.md §6). That offset is every strain's on the curve.
void check_front_resolution(const std::vector<double>& rate, double dt, ProcessingResult& r);

// The records' noise (σ of their quiet starts, as the pulse search takes it) reaches the primary
// stress sample by sample multiplied by the bar/specimen area ratio: the 3-wave stress carries
// √(2 (E_f A_f σ_I)² + (E_b A_b σ_T)²) / 2A_s (the incident gauge gives the incident and the
// reflected pulse), the 1-wave E_b A_b σ_T / A_s (docs/methods.md §6).
void check_stress_noise(double incident_noise, double transmitted_noise, const KolskySetup& k,
                        bool one_wave, ProcessingResult& r);

// A plateau of the strain rate: the longest run of samples within ±10 % of the plateau level
// (plateau_level) spans at least 30 % of the loading (the samples with a positive rate). Without
// one, no plateau rate is quoted, only the mean over the loading.
void judge_strain_rate(const std::vector<double>& rate, std::size_t n, ProcessingResult& r);

// The 1-wave (transmitted) and 2-wave (incident + reflected) stresses of one specimen agree
// within tens of percent once it is loaded; a larger disagreement is said with its size, and with
// a cause only where the record shows one: a first pulse of the other polarity than the test's,
// or a reflected onset off its geometric position by enough to move the 2-wave stress.
// Loaded: where the 1-wave stress is at least 20 % of its peak (the front face's start-up
// ringing, large on a thin specimen, would otherwise set the scale).
void check_one_and_two_wave(const Curve& c, std::size_t n, const ProcessingResult& r,
                            const ProcessingOptions& o, std::vector<std::string>& warnings);

// The 1-wave strain rate is the 3-wave one with the incident pulse eliminated by the faces'
// equilibrium P1 = P2 (docs/methods.md §6): it differs from it by exactly c_f (P2 − P1)/(E_f A_f
// L_s), which is G (P2 − P1)/P̄ of the rate, G = c_f P̄/(E_f A_f L_s ε̇) the particle velocity of the
// specimen's force in the incident bar over the faces' relative velocity. A specimen whose
// transmitted pulse is large against its reflected one (near the bar's impedance, or strong
// against its rate) turns a force mismatch the equilibrium criterion passes into several times as
// much in its rate. With a 1-wave primary, a median difference beyond kOneWaveRateError of the
// mean rate over the loaded samples is said, naming R, G and the 3-wave reduction, which needs no
// equilibrium.
inline constexpr double kOneWaveRateError = 0.05;
void check_one_wave_rate(const Curve& c, const KolskySetup& k, ProcessingResult& r);

// The inertia correction (measurement.corrections.inertia, docs/methods.md §8.3) takes the
// specimen to strain uniformly, its velocity linear from face to face, so that its faces' forces
// differ by its mass times the mean of its faces' accelerations, m (v̇1 + v̇2)/2, which it removes.
// Where the uncorrected faces' forces agree (R ≤ kEquilibriumThreshold) and the corrected 1- and
// 2-wave stresses do not (their R, a median over those loaded samples, above the same criterion),
// the specimen's mass is not accelerating as its faces' mean: it strains unevenly (a strain
// increment crosses it slowly against the rise: a long elastic transit, or the slow plastic wave
// of a flat stress–strain curve) and the corrected face stresses stray from the 3-wave one, the
// faces' average, which does not depend on the specimen's acceleration as a whole. That is said.
void check_inertia_corrected_faces(const Curve& c, const KolskySetup& k, const ProcessingOptions& o,
                                   ProcessingResult& r);

// One gauge sees the incident and the reflected pulse pass in turn. A pulse longer than its round
// trip 2d/c0 to the specimen and back (a long striker, a gauge near the specimen, a polymer bar's
// creep tail) still passes when its reflection arrives, and the record holds their sum: the
// reflected pulse, the 2-wave stress and the strain carry what overlaps (docs/methods.md §6).
// Overlapping by more than this many samples is said.
inline constexpr double kOverlapSamples = 2;
void warn_incident_overlap(const KolskySetup& k, double dt, ProcessingResult& r);

// The 3-wave stress is the specimen's stress only where the two face forces agree: at the
// ring-up and on the unloading edge the front face's force (the sum of two large pulses whose
// fronts a sample or a model's element apart do not cancel) rises far above the back face's and
// above the specimen's stress (a copper specimen of 5 mm x 5 mm: 1.36 x its peak, at the incident
// pulse's falling edge). Once the specimen reaches equilibrium that lasts until unloading, or is
// in equilibrium over most of its loading (a record that ends before the unloading), it is in
// equilibrium for its peak: the headline peak is the transmitted face's (processing.hpp,
// headline_peak_stress), and the 3-wave peak is read over the loaded samples in equilibrium
// (R ≤ 5 %), the loading's largest value kept beside it. Otherwise the peak is the loading's, said
// with the fraction of the loading in equilibrium: outside it the stresses are the face forces
// over the area, not a material's stress. A Monte Carlo draw takes its nominal's decision
// (ProcessingOptions::peak_in_equilibrium).
inline constexpr double kMostlyInEquilibrium = 0.5;
void settle_peak_stress(const ProcessingOptions& options, ProcessingResult& r);

// Loaded: from the first to the last sample where the mean force is at least 20 % of its peak.
// Among those, the fraction with R ≤ 5 %, the longest run of them, and the run that reaches the
// unloading (equilibrium that holds until unloading): the sample `unloading` where the incident
// pulse's falling edge, less the specimen's ring-down, reaches the front face, or the last loaded
// sample before it. The front face unloads first, so R rises on that edge in every test. A run
// shorter than `ring_down` samples is not equilibrium. The largest 3-wave stress among the loaded
// samples with R ≤ 5 % is the peak in equilibrium.
Equilibrium judge_equilibrium(const Curve& c, const std::vector<double>& t, std::size_t n,
                              double peak_force, std::size_t unloading, std::size_t ring_down);

// What a time shift of a pulse at the faces does to the stress: the largest change of the 3-wave
// stress, ½ E_f A_f |Δε| / A_s, over the transmitted face's loading (1-wave stress ≥ 20 % of its
// peak), as a fraction of the 1-wave peak (docs/methods.md §6).
class ShiftStressError {
 public:
  ShiftStressError(const ProcessingResult& r, const KolskySetup& k, double dt);
  bool has_scale() const { return s1_peak_ > 0; }
  double operator()(const std::vector<double>& pulse, const BarSide& bar, double shift_s) const;

 private:
  static double max_of(const std::vector<double>& v);
  const KolskySetup& k_;
  double dt_, s1_peak_;
  std::vector<char> loaded_;
};

// The reflected pulse's onset offset, when it is not applied and changes the stress by more than
// kShiftStressError: said, beside the gauge-position warning check_alignment may have given.
void warn_reflected_offset(const ShiftStressError& stress_change, const KolskySetup& k, double dt,
                           const ProcessingOptions& options, ProcessingResult& r);

// A hand-set reflected or transmitted window is a time shift: one whose start is far from the
// detected onset moves the pulse by that much (docs/scene-format.md).
void warn_window_shift(const ShiftStressError& stress_change, const std::vector<double>& t,
                       double dt, const std::optional<TimeWindow>& w, const std::string& name,
                       const std::optional<double>& onset_s, const std::vector<double>& pulse,
                       const BarSide& bar, ProcessingResult& r);

}  // namespace shpb
