#pragma once
// Bilinear elastic–plastic law with linear isotropic hardening, 1D uniaxial stress.
// Yield stress σ_y(p) = σ_y0 + H p, plastic modulus H = E E_t / (E − E_t), so that the monotonic
// stress–strain curve after yield has slope E_t. Backward-Euler radial return (Simo & Hughes 1998,
// "Computational Inelasticity", Box 1.4), exact for this law in 1D whatever the step.
#include "model/material_law.hpp"

namespace shpb {

class BilinearLaw final : public MaterialLaw {
 public:
  explicit BilinearLaw(const MaterialSpec& spec);

  void initialize(std::span<MaterialPointState> states) const override;
  void update(std::span<const double> strain_next, double dt_s,
              std::span<MaterialPointState> states, std::span<double> stress_out) const override;
  double max_tangent_modulus_Pa() const override { return youngs_modulus_Pa_; }
  double stored_energy_J_m3(const MaterialPointState& state) const override;

 private:
  double youngs_modulus_Pa_;
  double yield_stress_Pa_;
  double plastic_modulus_Pa_;  // H
  double initial_temperature_K_;
};

}  // namespace shpb
