#include "model/laws/johnson_cook_law.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace shpb {

namespace {
// Return mapping stops when the stress residual is this small relative to the trial stress: a few
// hundred ulps, above the round-off of the residual itself (three terms of size |σ_trial|).
constexpr double kReturnRelativeTolerance = 1e-13;
constexpr int kReturnMaxIterations = 100;
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

double johnson_cook_flow_stress(const JohnsonCookParams& jc, double plastic_strain,
                                double strain_rate_1_s, double temperature_K) {
  return (jc.A_Pa + jc.B_Pa * std::pow(plastic_strain, jc.n)) *
         johnson_cook_rate_factor(jc, strain_rate_1_s) *
         johnson_cook_thermal_factor(jc, temperature_K);
}

JohnsonCookLaw::JohnsonCookLaw(const MaterialSpec& spec)
    : jc_(spec.johnson_cook),
      youngs_modulus_Pa_(spec.youngs_modulus_Pa),
      heat_capacity_J_m3K_(spec.density_kg_m3 * spec.johnson_cook.specific_heat_J_kgK) {}

void JohnsonCookLaw::initialize(std::span<MaterialPointState> states) const {
  for (auto& s : states) s = MaterialPointState{.temperature_K = jc_.initial_temperature_K};
}

double JohnsonCookLaw::plastic_increment(double trial_abs, double p, double k) const {
  const double E = youngs_modulus_Pa_;
  auto residual = [&](double dp) {
    return trial_abs - E * dp - (jc_.A_Pa + jc_.B_Pa * std::pow(p + dp, jc_.n)) * k;
  };
  // g(Δp) decreases strictly; g(0) > 0 and g(hi) ≤ 0 because σ_y(p + Δp) ≥ σ_y(p).
  double lo = 0;
  double hi = residual(0) / E;
  if (jc_.B_Pa == 0 || k == 0) return hi;  // perfectly plastic at this rate and temperature
  double dp = hi;
  for (int it = 0; it < kReturnMaxIterations; ++it) {
    const double g = residual(dp);
    if (std::abs(g) <= kReturnRelativeTolerance * trial_abs) return dp;
    if (g > 0)
      lo = dp;
    else
      hi = dp;
    const double q = p + dp;
    const double slope = E + (q > 0 ? jc_.B_Pa * jc_.n * std::pow(q, jc_.n - 1) * k : 0);
    const double newton = dp + g / slope;
    dp = (newton > lo && newton < hi) ? newton : 0.5 * (lo + hi);
  }
  return dp;
}

void JohnsonCookLaw::update(std::span<const double> strain_next, double dt_s,
                            std::span<MaterialPointState> states,
                            std::span<double> stress_out) const {
  const double E = youngs_modulus_Pa_;
  for (std::size_t i = 0; i < states.size(); ++i) {
    MaterialPointState& s = states[i];
    const double trial = E * (strain_next[i] - s.back_strain);
    const double rate = dt_s > 0 ? (strain_next[i] - s.strain) / dt_s : 0.0;
    const double k =
        johnson_cook_rate_factor(jc_, rate) * johnson_cook_thermal_factor(jc_, s.temperature_K);
    const double yield = (jc_.A_Pa + jc_.B_Pa * std::pow(s.plastic_strain, jc_.n)) * k;
    double stress = trial;
    if (std::abs(trial) > yield) {
      const double dp = plastic_increment(std::abs(trial), s.plastic_strain, k);
      const double d_back = std::copysign(dp, trial);
      stress = trial - E * d_back;
      // Trapezoidal plastic work: work in = stored + dissipated exactly, step by step.
      const double work = 0.5 * (s.stress_Pa + stress) * d_back;
      s.dissipated_J_m3 += work;
      s.heat_J_m3 += jc_.taylor_quinney * work;
      if (jc_.adiabatic) s.temperature_K += jc_.taylor_quinney * work / heat_capacity_J_m3K_;
      s.plastic_strain += dp;
      s.back_strain += d_back;
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
