#include "model/laws/johnson_cook_law.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace shpb {

namespace {
// Return mapping: once the stress residual is below this fraction of the trial stress, one more
// Newton step (quadratic convergence) leaves a residual near 1e-12 or below, so it is taken and
// the iteration stops without another evaluation (one pow per plastic step in the usual case).
constexpr double kReturnFinalStepResidual = 1e-6;
constexpr int kReturnMaxIterations = 100;
// Relative distance |q − base|/base within which q^e comes from the cached base^e by the binomial
// series to x⁵: the remainder |C(e,6)| x⁶ ≤ 1e-18 for |e| ≤ 2, below round-off. A plastic step
// moves p by ~1e-3 of itself or less once an element has yielded for a while (rate × Δt ≪ p).
constexpr double kSeriesRange = 1e-3;
// The same to x¹⁰ over a wider range (the first plastic steps of an element, where p and T* grow
// by several per cent a step): remainder |C(e,11)| x¹¹ ≤ 2e-19 for |e| ≤ 2.
constexpr double kLongSeriesRange = 0.02;
// ln r from a cached ln r0 by the series of ln(1 + x), x = (r − r0)/r0, to x⁶ for |x| ≤ this: the
// remainder x⁷/7 ≤ 2e-22 is below round-off of the rate factor 1 + C ln ε̇*.
constexpr double kLogSeriesRange = 1e-3;
}  // namespace

JohnsonCookLaw::BinomialSeries::BinomialSeries(double e) {
  for (int k = 1; k <= 10; ++k) c[k - 1] = (e - k + 1) / k;
}

double JohnsonCookLaw::BinomialSeries::power(double q, double base, double base_pow, double e) const {
  if (base > 0) {
    const double x = (q - base) / base;
    const double ax = std::abs(x);
    if (ax <= kSeriesRange) {
      double sum = 1 + c[4] * x;
      for (int k = 3; k >= 0; --k) sum = 1 + c[k] * x * sum;
      return base_pow * sum;
    }
    if (ax <= kLongSeriesRange) {
      double sum = 1 + c[9] * x;
      for (int k = 8; k >= 0; --k) sum = 1 + c[k] * x * sum;
      return base_pow * sum;
    }
  }
  return std::pow(q, e);
}

double johnson_cook_rate_factor(const JohnsonCookParams& jc, double strain_rate_1_s) {
  const double ratio = std::abs(strain_rate_1_s) / jc.reference_strain_rate_1_s;
  return ratio > 1 ? 1 + jc.C * std::log(ratio) : 1.0;
}

double johnson_cook_thermal_factor(const JohnsonCookParams& jc, double temperature_K) {
  if (temperature_K <= jc.room_temperature_K) return 1.0;
  if (temperature_K >= jc.melting_temperature_K) return 0.0;
  const double homologous =
      (temperature_K - jc.room_temperature_K) / (jc.melting_temperature_K - jc.room_temperature_K);
  return 1 - std::pow(homologous, jc.m);
}

double johnson_cook_flow_stress(const JohnsonCookParams& jc, double plastic_strain,
                                double strain_rate_1_s, double temperature_K) {
  return (jc.A_Pa + jc.B_Pa * std::pow(plastic_strain, jc.n)) *
         johnson_cook_rate_factor(jc, strain_rate_1_s) *
         johnson_cook_thermal_factor(jc, temperature_K);
}

JohnsonCookLaw::JohnsonCookLaw(const MaterialSpec& spec)
    : jc_(spec.johnson_cook),
      youngs_modulus_Pa_(spec.youngs_modulus_Pa),
      heat_capacity_J_m3K_(spec.density_kg_m3 * spec.johnson_cook.specific_heat_J_kgK),
      hardening_series_(spec.johnson_cook.n),
      thermal_series_(spec.johnson_cook.m) {}

double JohnsonCookLaw::homologous_power(const MaterialPointState& s) const {
  const double T = s.temperature_K, room = jc_.room_temperature_K;
  if (T <= room) return 0.0;
  if (T >= jc_.melting_temperature_K) return 1.0;
  if (T == s.jc_T) return s.jc_T_pow_m;
  const double span = jc_.melting_temperature_K - room;
  const double cached = s.jc_T > room && s.jc_T < jc_.melting_temperature_K ? (s.jc_T - room) / span : 0.0;
  return thermal_series_.power((T - room) / span, cached, s.jc_T_pow_m, jc_.m);
}

void JohnsonCookLaw::initialize(std::span<MaterialPointState> states) const {
  for (auto& s : states) s = MaterialPointState{.temperature_K = jc_.initial_temperature_K};
}

double JohnsonCookLaw::log_rate(double ratio, MaterialPointState& s) const {
  double l;
  const double x = s.jc_rate > 0 ? (ratio - s.jc_rate) / s.jc_rate : 1.0;
  if (std::abs(x) <= kLogSeriesRange)
    l = s.jc_log_rate + x * (1 - x * (1.0 / 2 - x * (1.0 / 3 - x * (1.0 / 4 - x * (1.0 / 5 - x * (1.0 / 6))))));
  else
    l = std::log(ratio);
  s.jc_rate = ratio;
  s.jc_log_rate = l;
  return l;
}

JohnsonCookLaw::Return JohnsonCookLaw::plastic_increment(double trial_abs, double p, double p_n,
                                                         double k) const {
  const double E = youngs_modulus_Pa_, A = jc_.A_Pa, B = jc_.B_Pa, n = jc_.n;
  // g(Δp) = |σ_trial| − E Δp − (A + B (p + Δp)^n) k decreases strictly and is convex (n ≤ 1);
  // g(0) > 0 and g(hi) ≤ 0 because σ_y(p + Δp) ≥ σ_y(p).
  const double g0 = trial_abs - (A + B * p_n) * k;
  double lo = 0, hi = g0 / E;
  if (B == 0 || k == 0) return {hi, 0, 0};  // perfectly plastic at this rate and temperature
  // First guess: the root of the tangent at Δp = 0 (the elastic-linear-hardening step); by
  // convexity it lies left of the root and Newton then climbs monotonically onto it.
  double dp = p > 0 ? g0 / (E + n * B * p_n / p * k) : hi;
  // Each power comes from the last evaluated pair (Newton's iterates are close to each other).
  double base = p, base_n = p_n;
  for (int it = 0; it < kReturnMaxIterations; ++it) {
    const double q = p + dp;
    const double q_n = hardening_series_.power(q, base, base_n, n);
    base = q;
    base_n = q_n;
    const double g = trial_abs - E * dp - (A + B * q_n) * k;
    if (g > 0)
      lo = dp;
    else
      hi = dp;
    const double newton = dp + g / (E + n * B * q_n / q * k);
    const bool inside = newton > lo && newton < hi;
    if (std::abs(g) <= kReturnFinalStepResidual * trial_abs) return {inside ? newton : dp, q, q_n};
    dp = inside ? newton : 0.5 * (lo + hi);
  }
  return {dp, base, base_n};
}

void JohnsonCookLaw::update(std::span<const double> strain_next, double dt_s,
                            std::span<MaterialPointState> states,
                            std::span<double> stress_out) const {
  const double E = youngs_modulus_Pa_;
  for (std::size_t i = 0; i < states.size(); ++i) {
    MaterialPointState& s = states[i];
    const double trial = E * (strain_next[i] - s.back_strain);
    // Neither p nor T moved since the last update (jc_bound is that update's hardening × thermal
    // factor): below the bound the step is elastic.
    if (s.plastic_strain == s.jc_p && s.temperature_K == s.jc_T && std::abs(trial) <= s.jc_bound) {
      s.strain = strain_next[i];
      s.stress_Pa = trial;
      stress_out[i] = trial;
      continue;
    }
    // p^n and T*^m from the caches (exact pairs), refreshed whenever p or T moved.
    if (s.plastic_strain != s.jc_p) {
      s.jc_p_pow_n = hardening_series_.power(s.plastic_strain, s.jc_p, s.jc_p_pow_n, jc_.n);
      s.jc_p = s.plastic_strain;
    }
    const double p_n = s.jc_p_pow_n;
    const double hardening = jc_.A_Pa + jc_.B_Pa * p_n;
    const double t_m = homologous_power(s);
    s.jc_T = s.temperature_K;
    s.jc_T_pow_m = t_m;
    const double thermal = 1 - t_m;
    s.jc_bound = hardening * thermal;
    double stress = trial;
    // The rate factor is ≥ 1: below hardening × thermal the step is elastic without the log.
    if (std::abs(trial) > hardening * thermal) {
      const double rate = dt_s > 0 ? (strain_next[i] - s.strain) / dt_s : 0.0;
      // The rate factor of johnson_cook_rate_factor, its log from the element's cached pair.
      const double ratio = std::abs(rate) / jc_.reference_strain_rate_1_s;
      const double k = (ratio > 1 ? 1 + jc_.C * log_rate(ratio, s) : 1.0) * thermal;
      if (std::abs(trial) > hardening * k) {
        const Return ret = plastic_increment(std::abs(trial), s.plastic_strain, p_n, k);
        const double dp = ret.dp;
        const double d_back = std::copysign(dp, trial);
        stress = trial - E * d_back;
        // Trapezoidal plastic work: work in = stored + dissipated exactly, step by step.
        const double work = 0.5 * (s.stress_Pa + stress) * d_back;
        s.dissipated_J_m3 += work;
        s.heat_J_m3 += jc_.taylor_quinney * work;
        if (jc_.adiabatic) s.temperature_K += jc_.taylor_quinney * work / heat_capacity_J_m3K_;
        s.plastic_strain += dp;
        s.back_strain += d_back;
        // The last pair Newton evaluated is next to the new p: the next refresh is a short series.
        if (ret.q > 0) {
          s.jc_p = ret.q;
          s.jc_p_pow_n = ret.q_n;
        }
      }
    }
    s.strain = strain_next[i];
    s.stress_Pa = stress;
    stress_out[i] = stress;
  }
}

double JohnsonCookLaw::stored_energy_J_m3(const MaterialPointState& state) const {
  return 0.5 * state.stress_Pa * state.stress_Pa / youngs_modulus_Pa_;
}

}  // namespace shpb
