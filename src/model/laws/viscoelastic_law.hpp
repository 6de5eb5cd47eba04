#pragma once
// Generalized Maxwell (Prony series) law, 1D: σ = E_inf ε + Σ_k σ_k, each arm a spring E_k in
// series with a dashpot η_k = E_k τ_k: σ̇_k + σ_k/τ_k = E_k ε̇. With ε̇ constant over a step the arm
// equation integrates exactly (Taylor, Pister & Goudreau 1970, Int. J. Numer. Meth. Eng. 2:45, eq.
// 19; Simo & Hughes 1998 §10.3):
//   σ_k ← e^{−Δt/τ_k} σ_k + E_k (τ_k/Δt)(1 − e^{−Δt/τ_k}) Δε,
// so relaxation and constant-rate histories are reproduced to round-off at any step.
// Viscous dissipation per step = trapezoidal work − change of stored energy (all of it heat).
#include <vector>

#include "model/material_law.hpp"

namespace shpb {

class ViscoelasticLaw final : public MaterialLaw {
 public:
  explicit ViscoelasticLaw(const MaterialSpec& spec);

  void initialize(std::span<MaterialPointState> states) const override;
  void update(std::span<const double> strain_next, double dt_s,
              std::span<MaterialPointState> states, std::span<double> stress_out) const override;
  // Instantaneous (glassy) modulus E_inf + Σ E_k: the stiffest the law can respond.
  double max_tangent_modulus_Pa() const override { return instantaneous_modulus_Pa_; }
  double stored_energy_J_m3(const MaterialPointState& state) const override;

 private:
  double long_term_modulus_Pa_;
  std::vector<MaxwellArm> arms_;
  double instantaneous_modulus_Pa_;
  double initial_temperature_K_;
};

}  // namespace shpb
