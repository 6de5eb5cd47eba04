#pragma once
// Johnson–Cook viscoplastic law (Johnson & Cook 1983, Proc. 7th Int. Symp. Ballistics, eq. 1),
// 1D uniaxial stress, isotropic hardening:
//   σ_y = (A + B p^n) (1 + C ln ε̇*) (1 − T*^m),  ε̇* = max(|ε̇| / ε̇0, 1),
//   T* = (T − T_room) / (T_melt − T_room), thermal factor 1 below T_room and 0 at or above T_melt.
// ε̇ is the total strain rate of the step, (ε_{n+1} − ε_n)/Δt; flooring ε̇* at 1 keeps the rate
// factor ≥ 1 (no softening below the reference rate, no log of zero on unloading).
// Adiabatic heating dT = β σ dε_p / (ρ c_p) (Taylor–Quinney β); the temperature of a step is the
// one at its start (explicit in T, error O(Δε_p) per step and negligible at specimen step sizes).
// Return mapping: backward Euler on p at the step's rate and temperature, safeguarded Newton.
// Strain-rate filter (`strain_rate_filter` τ > 0; explicit codes offer the same, e.g. OpenRadioss
// /MAT/LAW2's Fsmooth/Fcut): the rate term then sees |ε̇| through a first-order low-pass filter
// τ dε̇_f/dt = |ε̇| − ε̇_f, integrated exactly for a rate held over the step:
// ε̇_f ← ε̇_f + (1 − e^{−Δt/τ})(|ε̇| − ε̇_f), from ε̇_f = 0 at rest. It removes the specimen's
// ringing (periods of a few wave transits, ~1 µs) from the rate term while following the
// loading's rise (tens of µs): docs/methods.md §9. Off unless given, except in the scene's
// specimen (specimen_law_material).
#include "model/material_law.hpp"

namespace shpb {

// The flow stress σ_y of the law above at plastic strain p, strain rate |ε̇| and temperature T.
double johnson_cook_flow_stress(const JohnsonCookParams& jc, double plastic_strain,
                                double strain_rate_1_s, double temperature_K);
// The rate factor 1 + C ln ε̇* (floored) and the thermal factor 1 − T*^m (clamped to [0, 1]).
double johnson_cook_rate_factor(const JohnsonCookParams& jc, double strain_rate_1_s);
double johnson_cook_thermal_factor(const JohnsonCookParams& jc, double temperature_K);

// The material the scene's specimen, of length L, gives its law: a Johnson–Cook law without its
// own `strain_rate_filter` gets τ = L/(2 c0), half the specimen's elastic transit. Its rate term
// then follows the specimen's mean strain rate (what Johnson–Cook constants are fitted to in
// Kolsky tests) instead of the ringing at and below the transit, which the concave log turns
// into a bias that depends on the step plan and the mesh (docs/methods.md §8).
MaterialSpec specimen_law_material(const MaterialSpec& material, double length_m);

class JohnsonCookLaw final : public MaterialLaw {
 public:
  explicit JohnsonCookLaw(const MaterialSpec& spec);

  void initialize(std::span<MaterialPointState> states) const override;
  void update(std::span<const double> strain_next, double dt_s,
              std::span<MaterialPointState> states, std::span<double> stress_out) const override;
  double max_tangent_modulus_Pa() const override { return youngs_modulus_Pa_; }
  double stored_energy_J_m3(const MaterialPointState& state) const override;
  // Return mappings one element at a time (plastic_increment only) instead of several at once:
  // the plain path the vectorised one is tested against.
  void set_block_return(bool on) { block_return_ = on; }

 private:
  // Plastic increment Δp > 0 with |σ_trial| − E Δp = (A + B (p + Δp)^n) k, k = rate × thermal;
  // p_n = p^n (already computed for the yield check) and inv_p = 1/p (0 at p = 0) are passed in.
  // Also returns (p + Δp)^n from the last point Newton evaluated (NaN: none, perfectly plastic).
  struct Return {
    double dp, p_next_n;
  };
  Return plastic_increment(double trial_abs, double p, double p_n, double inv_p, double k) const;
  // ln(|ε̇|/ε̇0) for a ratio > 1, from the state's cached pair when the ratio moved little;
  // refreshes the pair.
  double log_rate(double ratio, MaterialPointState& s) const;
  // T*^m (0 below room temperature, 1 at or above melting) from the state's cached pair;
  // refreshes the pair.
  double homologous_power(MaterialPointState& s) const;

  // Coefficients of the binomial series (1 + x)^e = Σ a_k x^k, a_k = C(e, k) = a_{k−1}(e − k +
  // 1)/k, to x¹⁰: powers near a cached point without pow (see kSeriesRange in the .cpp).
  struct BinomialSeries {
    double a[11];
    explicit BinomialSeries(double e);
    // q^e from base^e = base_pow and x = (q − base)/base (an infinite x: no base, pow).
    double power(double q, double x, double base_pow, double e) const;
  };

  JohnsonCookParams jc_;
  double youngs_modulus_Pa_;
  double heat_per_work_;  // β/(ρ c_p): adiabatic temperature rise per unit plastic work
  double inverse_span_;   // 1/(T_melt − T_room)
  BinomialSeries hardening_series_;  // exponent n
  BinomialSeries thermal_series_;    // exponent m
  bool block_return_ = true;
};

}  // namespace shpb
