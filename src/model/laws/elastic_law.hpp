#pragma once
// Linear elastic law σ = E ε. Bars use the solver's own elastic kernel; this law exists so that any
// material, elastic ones included, can be driven through the MaterialLaw interface (tests,
// specimens).
#include "model/material_law.hpp"

namespace shpb {

class ElasticLaw final : public MaterialLaw {
 public:
  explicit ElasticLaw(const MaterialSpec& spec);

  void initialize(std::span<MaterialPointState> states) const override;
  void update(std::span<const double> strain_next, double dt_s,
              std::span<MaterialPointState> states, std::span<double> stress_out) const override;
  double max_tangent_modulus_Pa() const override { return youngs_modulus_Pa_; }
  double stored_energy_J_m3(const MaterialPointState& state) const override;

 private:
  double youngs_modulus_Pa_;
  double initial_temperature_K_;
};

}  // namespace shpb
