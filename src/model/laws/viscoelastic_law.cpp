#include "model/laws/viscoelastic_law.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>

namespace shpb {

ViscoelasticLaw::ViscoelasticLaw(const MaterialSpec& spec)
    : long_term_modulus_Pa_(spec.viscoelastic.long_term_modulus_Pa),
      arms_(spec.viscoelastic.arms),
      instantaneous_modulus_Pa_(spec.viscoelastic.long_term_modulus_Pa),
      initial_temperature_K_(spec.johnson_cook.initial_temperature_K) {
  if (arms_.size() > static_cast<std::size_t>(MaterialPointState::kMaxArms))
    throw std::logic_error("viscoelastic law: more Maxwell arms than MaterialPointState holds");
  for (const auto& arm : arms_) instantaneous_modulus_Pa_ += arm.modulus_Pa;
}

void ViscoelasticLaw::initialize(std::span<MaterialPointState> states) const {
  for (auto& s : states) s = MaterialPointState{.temperature_K = initial_temperature_K_};
}

void ViscoelasticLaw::update(std::span<const double> strain_next, double dt_s,
                             std::span<MaterialPointState> states,
                             std::span<double> stress_out) const {
  // Per-step factors of the exact update, shared by every element of the bar.
  constexpr int kMax = MaterialPointState::kMaxArms;
  const int arms = static_cast<int>(arms_.size());
  std::array<double, kMax> decay{}, gain{};
  for (int k = 0; k < arms; ++k) {
    const double x = dt_s / arms_[k].relaxation_time_s;
    decay[k] = std::exp(-x);
    // E_k τ/Δt (1 − e^{−x}); → E_k as Δt → 0 (instantaneous response).
    gain[k] = arms_[k].modulus_Pa * (x > 0 ? -std::expm1(-x) / x : 1.0);
  }
  for (std::size_t i = 0; i < states.size(); ++i) {
    MaterialPointState& s = states[i];
    const double d_strain = strain_next[i] - s.strain;
    const double stored_before = stored_energy_J_m3(s);
    double stress = long_term_modulus_Pa_ * strain_next[i];
    for (int k = 0; k < arms; ++k) {
      s.arm_stress_Pa[k] = decay[k] * s.arm_stress_Pa[k] + gain[k] * d_strain;
      stress += s.arm_stress_Pa[k];
    }
    const double work = 0.5 * (s.stress_Pa + stress) * d_strain;
    s.strain = strain_next[i];
    s.stress_Pa = stress;
    const double dissipated = work - (stored_energy_J_m3(s) - stored_before);
    s.dissipated_J_m3 += dissipated;
    s.heat_J_m3 += dissipated;
    stress_out[i] = stress;
  }
}

double ViscoelasticLaw::stored_energy_J_m3(const MaterialPointState& state) const {
  // Long-term spring plus the spring of every arm: ½ E_inf ε² + Σ σ_k² / (2 E_k).
  double w = 0.5 * long_term_modulus_Pa_ * state.strain * state.strain;
  for (std::size_t k = 0; k < arms_.size(); ++k)
    w += 0.5 * state.arm_stress_Pa[k] * state.arm_stress_Pa[k] / arms_[k].modulus_Pa;
  return w;
}

}  // namespace shpb
