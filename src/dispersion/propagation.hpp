#pragma once
// Moving a strain-gauge signal along its bar with Pochhammer–Chree dispersion (Follansbee & Frantz
// 1983; Gong et al. 1990; Tyas & Watson 2001; Tyas & Pope 2005; docs/methods.md §5):
// X(f) → X(f)·H(f)·exp(−i 2π f Δz / c(f)), real-to-complex FFT with zero padding; Δz > 0 moves
// the pulse forward (later, downstream), Δz < 0 backward. DC is untouched (an elastic bar's). H is
// a low-pass with a smooth raised-cosine roll-off that ends at the cut-off, below the pole of m1.
#include <complex>
#include <limits>
#include <memory>
#include <span>
#include <vector>

#include "dispersion/dispersion_table.hpp"
#include "dispersion/real_fft.hpp"

namespace shpb {

// One Maxwell arm of a viscoelastic bar, its modulus as a fraction of the instantaneous one.
struct RelaxationArm {
  double fraction = 0;  // E_k / E0
  double relaxation_time_s = 0;
};

// The part of a bar the correction needs. A viscoelastic (polymer) bar also carries its
// relaxation spectrum relative to its instantaneous modulus E0 = ρ c0² (generalized Maxwell,
// docs/methods.md §5.1): E*(ω)/E0 = e∞ + Σ e_k iωτ_k/(1 + iωτ_k); no arms: an elastic bar.
struct BarWaveguide {
  double radius_m = 0;
  double c0_m_s = 0;  // sqrt(E/ρ), E the instantaneous modulus
  double poisson = 0.3;
  double long_term_fraction = 1;  // e∞ = E∞ / E0
  std::vector<RelaxationArm> arms;

  bool viscoelastic() const { return !arms.empty(); }
  // The slowest phase velocity over c0: √e∞, the law's static speed (1 in an elastic bar).
  double slowest_speed_fraction() const;
  std::complex<double> relative_modulus(double omega) const;  // E*(ω)/E0
  // The highest f·a over the law's phase velocity at the frequencies up to a cut-off of f·a/c0 =
  // `cutoff_fa_over_c0`: how far the first mode's table is read (the cut-off itself in an
  // elastic bar).
  double mode_reach(double cutoff_fa_over_c0) const;
  // The attenuation of a harmonic wave at ω, −ω Im(1/c*) [1/m] (0 in an elastic bar).
  double attenuation_per_m(double omega) const;
};

// Moving a pulse back through a viscoelastic bar grows each component by exp(α(f)|Δz|), up to
// exp(α∞|Δz|): this much at most before it is cut (docs/methods.md §5.1): a record's noise, 10⁻⁴ to
// 10⁻³ of its pulse (a 12–16 bit digitizer), then stays below a tenth of the pulse.
inline constexpr double kMaxLawGain = 100;

// The frequency at which moving a pulse by `distance_m` through the bar's law grows it by
// kMaxLawGain: the law's band limit for that move; infinity when it never does (an elastic bar,
// a law of small α∞|Δz|).
double law_band_limit_Hz(const BarWaveguide& bar, double distance_m);

enum class AmplitudeFactor {
  kNone,    // surface strain stays surface strain (phase only)
  kStrain,  // × m1: mean axial strain over the cross-section
  kStress,  // × m1·m2: mean axial stress / E
};

// f·a/c0 = 0.2619 (d/Λ ≈ 0.6): a common cut-off below the m1 pole (docs/methods.md §5).
inline constexpr double kDefaultCutoffFaOverC0 = 0.2619;

// What a pulse moved along a viscoelastic bar is returned as (docs/methods.md §5.1): its strain, or
// the strain an elastic bar of modulus E0 would have at the same particle velocity (c*(ω)/c0 × ε,
// for the faces' velocities) or at the same stress (E*(ω)/E0 × ε, for their forces). In an elastic
// bar the three are one.
enum class WaveQuantity { kStrain, kVelocity, kForce };

struct PropagationOptions {
  bool dispersion = true;  // false: pure delay Δz/c0 (a 1D, non-dispersive bar)
  AmplitudeFactor amplitude = AmplitudeFactor::kNone;
  WaveQuantity quantity = WaveQuantity::kStrain;      // a viscoelastic bar's only
  double cutoff_fa_over_c0 = kDefaultCutoffFaOverC0;  // low-pass cut-off (dispersion only)
  // A viscoelastic bar's low-pass (law_band_limit_Hz), with or without dispersion; its roll-off
  // as the cut-off's.
  double law_cutoff_Hz = std::numeric_limits<double>::infinity();
  double rolloff_fraction = 0.25;  // raised cosine from (1 − this)·cut-off to the cut-off
  double taper_fraction = 0.02;    // cosine taper of each end of the record before padding
};

// How far a correction with `options` reads the first mode's table: f·a over the law's phase
// velocity up to the lower of the cut-off and the law's band limit (BarWaveguide::mode_reach).
double mode_reach(const BarWaveguide& bar, const PropagationOptions& options);

// The correction for one bar: its dispersion table, options and FFT workspace (planned once per
// padded length; give `plans` to share them with the other corrections of a record).
// `propagate` is the free-standing operation other commands reuse.
class Propagator {
 public:
  Propagator(const DispersionTable& table, const BarWaveguide& bar,
             const PropagationOptions& options, FftPlans* plans = nullptr);
  // Without dispersion (options.dispersion false): the pure delay, no table needed (a viscoelastic
  // bar: its law's propagation alone).
  Propagator(const BarWaveguide& bar, const PropagationOptions& options);

  // Propagates `signal` (uniform step dt) by `distance_m`; out has the signal's length and the
  // same time grid. Reuses the FFT plan while the padded length does not change. `delay_s` delays
  // the result further by that time, as a phase (exact for the band passed, where interpolating
  // between samples low-passes: a channel's delay, docs/methods.md §11).
  void propagate(std::span<const double> signal, double dt, double distance_m,
                 std::span<double> out, double delay_s = 0);
  std::vector<double> propagate(std::span<const double> signal, double dt, double distance_m);

  // How much earlier than a pure delay by distance/c0 the dispersion-corrected signal already
  // depends on the record's last samples: the end's taper and the slowest passed component's extra
  // travel over the distance (0 without the correction; a polymer bar's law, whose slow speeds
  // are its creep, is not counted). A record that ends while its pulse is still on is read that
  // much short of its end once moved (methods.md §6).
  double end_reach_s(std::size_t samples, double dt, double distance_m) const;

  // Low-pass gain H at frequency f (1 below the roll-off, 0 above the cut-off).
  double lowpass_gain(double frequency_Hz) const;
  // A viscoelastic bar's low-pass at options.law_cutoff_Hz (1 below its roll-off).
  double law_gain(double frequency_Hz) const;

 private:
  // The transfer function of a viscoelastic bar at ω > 0 (docs/methods.md §5.1).
  std::complex<double> viscoelastic_transfer(double frequency_Hz, double distance_m) const;
  // The slowest phase velocity any passed component travels at.
  double slowest_speed_m_s() const;
  // The samples of each end tapered to zero before the transform.
  std::size_t taper_samples(std::size_t samples, double dt) const;

  const DispersionTable* table_;
  BarWaveguide bar_;
  PropagationOptions options_;
  FftPlans own_plans_;
  FftPlans* shared_plans_;  // null: own_plans_
};

// One-off convenience: tabulates the bar's mode (≈ 16 ms) and plans an FFT for this call. For
// several pulses of one bar, keep a DispersionTable and a Propagator instead.
std::vector<double> propagate(std::span<const double> signal, double dt, double distance_m,
                              const BarWaveguide& bar, const PropagationOptions& options = {});

// Pure delay by distance/c0 with linear interpolation between samples (no ringing); the
// non-dispersive counterpart used for signals of a 1D model.
void delay_by_interpolation(std::span<const double> signal, double delay_samples,
                            std::span<double> out);

}  // namespace shpb
