#include "model/laws/bilinear_law.hpp"

#include <cmath>
#include <cstddef>

namespace shpb {

BilinearLaw::BilinearLaw(const MaterialSpec& spec)
    : youngs_modulus_Pa_(spec.youngs_modulus_Pa),
      yield_stress_Pa_(spec.bilinear.yield_stress_Pa),
      plastic_modulus_Pa_(spec.youngs_modulus_Pa * spec.bilinear.tangent_modulus_Pa /
                          (spec.youngs_modulus_Pa - spec.bilinear.tangent_modulus_Pa)),
      initial_temperature_K_(spec.johnson_cook.initial_temperature_K) {}

void BilinearLaw::initialize(std::span<MaterialPointState> states) const {
  for (auto& s : states) s = MaterialPointState{.temperature_K = initial_temperature_K_};
}

void BilinearLaw::update(std::span<const double> strain_next, double /*dt_s*/,
                         std::span<MaterialPointState> states, std::span<double> stress_out) const {
  const double E = youngs_modulus_Pa_;
  const double H = plastic_modulus_Pa_;
  for (std::size_t i = 0; i < states.size(); ++i) {
    MaterialPointState& s = states[i];
    const double trial = E * (strain_next[i] - s.back_strain);
    const double overstress = std::abs(trial) - (yield_stress_Pa_ + H * s.plastic_strain);
    double stress = trial;
    if (overstress > 0) {
      const double dp = overstress / (E + H);  // consistency: |σ| = σ_y0 + H (p + Δp)
      const double d_back = std::copysign(dp, trial);
      stress = trial - E * d_back;
      // Plastic work by the trapezoidal rule: with it, work in = stored + dissipated exactly.
      const double work = 0.5 * (s.stress_Pa + stress) * d_back;
      s.dissipated_J_m3 += work;
      s.heat_J_m3 += work;
      s.plastic_strain += dp;
      s.back_strain += d_back;
    }
    s.strain = strain_next[i];
    s.stress_Pa = stress;
    stress_out[i] = stress;
  }
}

double BilinearLaw::stored_energy_J_m3(const MaterialPointState& state) const {
  return 0.5 * state.stress_Pa * state.stress_Pa / youngs_modulus_Pa_;
}

}  // namespace shpb
