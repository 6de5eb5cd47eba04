#pragma once
// Moving a strain-gauge signal along its bar with Pochhammer–Chree dispersion (Follansbee & Frantz
// 1983; Gong et al. 1990; Tyas & Watson 2001; Tyas & Pope 2005; docs/methods.md §5):
// X(f) → X(f)·H(f)·exp(−i 2π f Δz / c(f)), real-to-complex FFT with zero padding; Δz > 0 moves
// the pulse forward (later, downstream), Δz < 0 backward. DC is untouched. H is a low-pass with a
// smooth raised-cosine roll-off that ends at the cut-off, below the pole of m1.
#include <memory>
#include <span>
#include <vector>

#include "dispersion/dispersion_table.hpp"
#include "dispersion/real_fft.hpp"

namespace shpb {

// The part of a bar the correction needs.
struct BarWaveguide {
  double radius_m = 0;
  double c0_m_s = 0;  // sqrt(E/ρ)
  double poisson = 0.3;
};

enum class AmplitudeFactor {
  kNone,    // surface strain stays surface strain (phase only)
  kStrain,  // × m1: mean axial strain over the cross-section
  kStress,  // × m1·m2: mean axial stress / E
};

// f·a/c0 = 0.2619 (d/Λ ≈ 0.6): a common cut-off below the m1 pole (docs/methods.md §5).
inline constexpr double kDefaultCutoffFaOverC0 = 0.2619;

struct PropagationOptions {
  bool dispersion = true;  // false: pure delay Δz/c0 (a 1D, non-dispersive bar)
  AmplitudeFactor amplitude = AmplitudeFactor::kNone;
  double cutoff_fa_over_c0 = kDefaultCutoffFaOverC0;  // low-pass cut-off (dispersion only)
  double rolloff_fraction = 0.25;  // raised cosine from (1 − this)·cut-off to the cut-off
  double taper_fraction = 0.02;    // cosine taper of each end of the record before padding
};

// The correction for one bar: its dispersion table, options and FFT workspace (planned once per
// padded length; give `plans` to share them with the other corrections of a record).
// `propagate` is the free-standing operation other commands reuse.
class Propagator {
 public:
  Propagator(const DispersionTable& table, const BarWaveguide& bar,
             const PropagationOptions& options, FftPlans* plans = nullptr);
  // Without dispersion (options.dispersion false): the pure delay, no table needed.
  Propagator(const BarWaveguide& bar, const PropagationOptions& options);

  // Propagates `signal` (uniform step dt) by `distance_m`; out has the signal's length and the
  // same time grid. Reuses the FFT plan while the padded length does not change.
  void propagate(std::span<const double> signal, double dt, double distance_m,
                 std::span<double> out);
  std::vector<double> propagate(std::span<const double> signal, double dt, double distance_m);

  // Low-pass gain H at frequency f (1 below the roll-off, 0 above the cut-off).
  double lowpass_gain(double frequency_Hz) const;

 private:
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
