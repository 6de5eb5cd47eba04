#include "model/laws/elastic_law.hpp"

#include <cstddef>

namespace shpb {

ElasticLaw::ElasticLaw(const MaterialSpec& spec)
    : youngs_modulus_Pa_(spec.youngs_modulus_Pa),
      initial_temperature_K_(spec.johnson_cook.initial_temperature_K) {}

void ElasticLaw::initialize(std::span<MaterialPointState> states) const {
  for (auto& s : states) s = MaterialPointState{.temperature_K = initial_temperature_K_};
}

void ElasticLaw::update(std::span<const double> strain_next, double /*dt_s*/,
                        std::span<MaterialPointState> states, std::span<double> stress_out) const {
  for (std::size_t i = 0; i < states.size(); ++i) {
    states[i].strain = strain_next[i];
    states[i].stress_Pa = youngs_modulus_Pa_ * strain_next[i];
    stress_out[i] = states[i].stress_Pa;
  }
}

double ElasticLaw::stored_energy_J_m3(const MaterialPointState& state) const {
  return 0.5 * state.stress_Pa * state.strain;
}

}  // namespace shpb
