#include "model/laws/johnson_cook_law.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "core/target_clones.hpp"

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
// Elements per block of update(): yield checks, then the block's return mappings.
constexpr std::size_t kYieldBlock = 64;
// A relative offset that no series accepts: the cached pair has no base (pow or log instead).
constexpr double kNoBase = std::numeric_limits<double>::infinity();
// The specimen's default rate filter τ in elastic transits L/c0 (header): measured, 0.5 holds
// the flow stress within 0.02 % of the law over step plans and meshes (docs/methods.md §8).
constexpr double kSpecimenRateFilterTransits = 0.5;
}  // namespace

JohnsonCookLaw::BinomialSeries::BinomialSeries(double e) {
  a[0] = 1;
  for (int k = 1; k <= 10; ++k) a[k] = a[k - 1] * (e - k + 1) / k;
}

// The polynomials are evaluated in Estrin's form (pairs of terms, then powers x², x⁴, x⁸): a few
// multiplications deep instead of a chain of ten, the same sum to round-off. (1 + x)^e / base^e
// to x⁵ and to x¹⁰ from the coefficients a of BinomialSeries.
inline double short_binomial_sum(const double* a, double x) {
  const double x2 = x * x;
  return (1 + a[1] * x) + x2 * ((a[2] + a[3] * x) + x2 * (a[4] + a[5] * x));
}
inline double long_binomial_sum(const double* a, double x) {
  const double x2 = x * x, x4 = x2 * x2;
  const double low = (1 + a[1] * x) + x2 * (a[2] + a[3] * x);
  const double mid = (a[4] + a[5] * x) + x2 * (a[6] + a[7] * x);
  const double high = (a[8] + a[9] * x) + x2 * a[10];
  return low + x4 * (mid + x4 * high);
}

inline double JohnsonCookLaw::BinomialSeries::power(double q, double x, double base_pow,
                                                    double e) const {
  const double ax = std::abs(x);
  if (ax <= kSeriesRange) return base_pow * short_binomial_sum(a, x);
  if (ax <= kLongSeriesRange) return base_pow * long_binomial_sum(a, x);
  return std::pow(q, e);
}

namespace {
// The return mapping of a block of yielding elements at once (JohnsonCookLaw::plastic_increment's
// usual path, element by element in a loop the compiler vectorises): the tangent guess, one
// evaluation, the final Newton step, each power by the binomial series from the element's cached
// pair. ok[j] = 0 where plastic_increment would have done anything else (a first plastic step
// p = 0, a residual above kReturnFinalStepResidual, a Newton step outside the bracket, a series
// out of range): those elements are redone by plastic_increment. Where ok[j] = 1 the operations
// are plastic_increment's, in its order, so the results are bit-identical.
struct ReturnConstants {
  double E, A, B, n;
  const double* a;  // hardening series coefficients
};
SHPB_TARGET_CLONES void block_return(const ReturnConstants& c, int count,
                                     const double* __restrict trial_abs, const double* __restrict p,
                                     const double* __restrict p_n, const double* __restrict inv_p,
                                     const double* __restrict k, double* __restrict dp_out,
                                     double* __restrict p_next_n_out, int* __restrict ok) {
  const double E = c.E, A = c.A, B = c.B, n = c.n;
  for (int j = 0; j < count; ++j) {
    const double g0 = trial_abs[j] - (A + B * p_n[j]) * k[j];
    const double hi0 = g0 / E;
    const double dp = g0 / (E + n * B * p_n[j] * inv_p[j] * k[j]);
    const double q = p[j] + dp;
    const double x = (q - p[j]) * inv_p[j];
    const double ax = std::abs(x);
    // Both series, then a select (branch-free: CMakeLists.txt, -fno-trapping-math).
    const double short_q = short_binomial_sum(c.a, x), long_q = long_binomial_sum(c.a, x);
    const double q_n = p_n[j] * (ax <= kSeriesRange ? short_q : long_q);
    const double inv_q = 1 / q;
    const double g = trial_abs[j] - E * dp - (A + B * q_n) * k[j];
    const double lo = g > 0 ? dp : 0.0, hi = g > 0 ? hi0 : dp;
    const double newton = dp + g / (E + n * B * q_n * inv_q * k[j]);
    const double p_next = p[j] + newton;
    const double x2 = (p_next - q) * inv_q;
    const double ax2 = std::abs(x2);
    dp_out[j] = newton;
    const double short_next = short_binomial_sum(c.a, x2), long_next = long_binomial_sum(c.a, x2);
    p_next_n_out[j] = q_n * (ax2 <= kSeriesRange ? short_next : long_next);
    ok[j] = (p[j] > 0) & (k[j] != 0) & (ax <= kLongSeriesRange) & (ax2 <= kLongSeriesRange) &
            (std::abs(g) <= kReturnFinalStepResidual * trial_abs[j]) & (newton > lo) &
            (newton < hi);
  }
}
}  // namespace

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

MaterialSpec specimen_law_material(const MaterialSpec& material, double length_m) {
  MaterialSpec fed = material;
  if (fed.model == MaterialModel::kJohnsonCook && !fed.johnson_cook.strain_rate_filter_s)
    fed.johnson_cook.strain_rate_filter_s =
        kSpecimenRateFilterTransits * length_m / material.wave_speed_m_s();
  return fed;
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
      heat_per_work_(spec.johnson_cook.taylor_quinney /
                     (spec.density_kg_m3 * spec.johnson_cook.specific_heat_J_kgK)),
      inverse_span_(
          1 / (spec.johnson_cook.melting_temperature_K - spec.johnson_cook.room_temperature_K)),
      hardening_series_(spec.johnson_cook.n),
      thermal_series_(spec.johnson_cook.m) {}

double JohnsonCookLaw::homologous_power(MaterialPointState& s) const {
  const double T = s.temperature_K, room = jc_.room_temperature_K, melt = jc_.melting_temperature_K;
  double t_m;
  if (T <= room) {
    t_m = 0.0;
  } else if (T >= melt) {
    t_m = 1.0;
  } else {
    if (T == s.jc_T) return s.jc_T_pow_m;
    // x = (T* − T*_0)/T*_0 = (T − T_0)/(T_0 − T_room).
    const double x = s.jc_T_inv > 0 ? (T - s.jc_T) * s.jc_T_inv : kNoBase;
    t_m = thermal_series_.power((T - room) * inverse_span_, x, s.jc_T_pow_m, jc_.m);
  }
  s.jc_T = T;
  s.jc_T_pow_m = t_m;
  s.jc_T_inv = T > room && T < melt ? 1 / (T - room) : 0.0;
  return t_m;
}

void JohnsonCookLaw::initialize(std::span<MaterialPointState> states) const {
  for (auto& s : states) s = MaterialPointState{.temperature_K = jc_.initial_temperature_K};
}

double JohnsonCookLaw::log_rate(double ratio, MaterialPointState& s) const {
  double l;
  const double x = s.jc_rate > 0 ? (ratio - s.jc_rate) * s.jc_rate_inv : kNoBase;
  if (std::abs(x) <= kLogSeriesRange) {
    // ln(1 + x) = x − x²/2 + x³/3 − x⁴/4 + x⁵/5 − x⁶/6, in Estrin's form.
    const double x2 = x * x;
    l = s.jc_log_rate +
        (x * (1 - 0.5 * x) + x2 * x * ((1.0 / 3 - 0.25 * x) + x2 * (0.2 - x * (1.0 / 6))));
  } else {
    l = std::log(ratio);
  }
  s.jc_rate = ratio;
  s.jc_rate_inv = 1 / ratio;
  s.jc_log_rate = l;
  return l;
}

JohnsonCookLaw::Return JohnsonCookLaw::plastic_increment(double trial_abs, double p, double p_n,
                                                         double inv_p, double k) const {
  const double E = youngs_modulus_Pa_, A = jc_.A_Pa, B = jc_.B_Pa, n = jc_.n;
  // g(Δp) = |σ_trial| − E Δp − (A + B (p + Δp)^n) k decreases strictly and is convex (n ≤ 1);
  // g(0) > 0 and g(hi) ≤ 0 because σ_y(p + Δp) ≥ σ_y(p).
  const double g0 = trial_abs - (A + B * p_n) * k;
  double lo = 0, hi = g0 / E;
  if (B == 0 || k == 0) return {hi, std::numeric_limits<double>::quiet_NaN()};  // perfectly plastic
  // First guess: the root of the tangent at Δp = 0 (the elastic-linear-hardening step); by
  // convexity it lies left of the root and Newton then climbs monotonically onto it.
  double dp = p > 0 ? g0 / (E + n * B * p_n * inv_p * k) : hi;
  // Each power comes from the last evaluated pair (Newton's iterates are close to each other).
  double base = p, base_n = p_n, inv_base = inv_p;
  for (int it = 0; it < kReturnMaxIterations; ++it) {
    const double q = p + dp;
    const double q_n =
        hardening_series_.power(q, base > 0 ? (q - base) * inv_base : kNoBase, base_n, n);
    const double inv_q = 1 / q;
    base = q;
    base_n = q_n;
    inv_base = inv_q;
    const double g = trial_abs - E * dp - (A + B * q_n) * k;
    if (g > 0)
      lo = dp;
    else
      hi = dp;
    const double newton = dp + g / (E + n * B * q_n * inv_q * k);
    const bool inside = newton > lo && newton < hi;
    if (std::abs(g) <= kReturnFinalStepResidual * trial_abs) {
      dp = inside ? newton : dp;
      break;
    }
    dp = inside ? newton : 0.5 * (lo + hi);
  }
  const double p_next = p + dp;
  return {dp, hardening_series_.power(p_next, (p_next - base) * inv_base, base_n, n)};
}

void JohnsonCookLaw::update(std::span<const double> strain_next, double dt_s,
                            std::span<MaterialPointState> states,
                            std::span<double> stress_out) const {
  const double E = youngs_modulus_Pa_;
  // |ε̇|/ε̇0 per unit strain increment (a multiplication in the loop, not two divisions).
  const double ratio_per_strain = dt_s > 0 ? 1 / (dt_s * jc_.reference_strain_rate_1_s) : 0.0;
  // The strain-rate filter's gain per step (header); every element's filter advances every step,
  // elastic or not.
  const double filter_s = jc_.strain_rate_filter_s.value_or(0);
  const bool filtered = filter_s > 0;
  const double gain = filtered ? -std::expm1(-dt_s / filter_s) : 0.0;
  const double rate_per_strain = dt_s > 0 ? 1 / dt_s : 0.0;
  // Elements go in blocks: first the yield checks of the block, then the return mappings of its
  // yielding elements, gathered into arrays, several at once (block_return, vectorised), the
  // few it leaves to plastic_increment one by one.
  std::size_t index[kYieldBlock];
  int ok[kYieldBlock];
  double trial_of[kYieldBlock], trial_abs[kYieldBlock], p_of[kYieldBlock], p_n_of[kYieldBlock],
      inv_p_of[kYieldBlock], k_of[kYieldBlock], dp_of[kYieldBlock], p_next_n_of[kYieldBlock];
  const ReturnConstants constants{E, jc_.A_Pa, jc_.B_Pa, jc_.n, hardening_series_.a};
  for (std::size_t first = 0; first < states.size(); first += kYieldBlock) {
    const std::size_t last = std::min(states.size(), first + kYieldBlock);
    std::size_t count = 0;
    for (std::size_t i = first; i < last; ++i) {
      MaterialPointState& s = states[i];
      const double trial = E * (strain_next[i] - s.back_strain);
      if (filtered)
        s.jc_filtered_rate +=
            gain * (std::abs(strain_next[i] - s.strain) * rate_per_strain - s.jc_filtered_rate);
      // Neither p nor T moved since the last update (jc_bound is that update's hardening ×
      // thermal factor): below the bound the step is elastic.
      if (s.plastic_strain == s.jc_p && s.temperature_K == s.jc_T &&
          std::abs(trial) <= s.jc_bound) {
        s.strain = strain_next[i];
        s.stress_Pa = trial;
        stress_out[i] = trial;
        continue;
      }
      // p^n and T*^m from the caches (exact pairs), refreshed whenever p or T moved.
      const double p = s.plastic_strain;
      if (p != s.jc_p) {
        s.jc_p_pow_n = hardening_series_.power(p, s.jc_p > 0 ? (p - s.jc_p) / s.jc_p : kNoBase,
                                               s.jc_p_pow_n, jc_.n);
        s.jc_p = p;
      }
      const double p_n = s.jc_p_pow_n;
      const double hardening = jc_.A_Pa + jc_.B_Pa * p_n;
      const double thermal = 1 - homologous_power(s);
      s.jc_bound = hardening * thermal;
      // The rate factor is ≥ 1: below hardening × thermal the step is elastic without the log.
      if (std::abs(trial) > hardening * thermal) {
        const double inv_p = p > 0 ? 1 / p : 0.0;
        // The rate factor of johnson_cook_rate_factor, its log from the element's cached pair.
        const double ratio = filtered ? s.jc_filtered_rate / jc_.reference_strain_rate_1_s
                                      : std::abs(strain_next[i] - s.strain) * ratio_per_strain;
        const double k = (ratio > 1 ? 1 + jc_.C * log_rate(ratio, s) : 1.0) * thermal;
        if (std::abs(trial) > hardening * k) {
          index[count] = i;
          trial_of[count] = trial;
          trial_abs[count] = std::abs(trial);
          p_of[count] = p;
          p_n_of[count] = p_n;
          inv_p_of[count] = inv_p;
          k_of[count] = k;
          ++count;
          continue;
        }
      }
      s.strain = strain_next[i];
      s.stress_Pa = trial;
      stress_out[i] = trial;
    }
    const bool block = block_return_ && jc_.B_Pa != 0;
    if (block)
      block_return(constants, static_cast<int>(count), trial_abs, p_of, p_n_of, inv_p_of, k_of,
                   dp_of, p_next_n_of, ok);
    for (std::size_t c = 0; c < count; ++c) {
      if (!block || !ok[c]) {
        const Return ret =
            plastic_increment(trial_abs[c], p_of[c], p_n_of[c], inv_p_of[c], k_of[c]);
        dp_of[c] = ret.dp;
        p_next_n_of[c] = ret.p_next_n;
      }
      MaterialPointState& s = states[index[c]];
      const double dp = dp_of[c], trial = trial_of[c];
      const double d_back = std::copysign(dp, trial);
      const double stress = trial - E * d_back;
      // Trapezoidal plastic work: work in = stored + dissipated exactly, step by step.
      const double work = 0.5 * (s.stress_Pa + stress) * d_back;
      s.dissipated_J_m3 += work;
      s.heat_J_m3 += jc_.taylor_quinney * work;
      if (jc_.adiabatic) s.temperature_K += work * heat_per_work_;
      s.plastic_strain = p_of[c] + dp;
      s.back_strain += d_back;
      if (!std::isnan(p_next_n_of[c])) {
        s.jc_p = s.plastic_strain;
        s.jc_p_pow_n = p_next_n_of[c];
      }
      s.strain = strain_next[index[c]];
      s.stress_Pa = stress;
      stress_out[index[c]] = stress;
    }
  }
}

double JohnsonCookLaw::stored_energy_J_m3(const MaterialPointState& state) const {
  return 0.5 * state.stress_Pa * state.stress_Pa / youngs_modulus_Pa_;
}

}  // namespace shpb
