#pragma once
// A single material point driven through the MaterialLaw interface (one element of one bar), as a
// uniaxial test machine would: strain-controlled at a constant rate, or stress-controlled (creep).
#include <memory>
#include <vector>

#include "model/material_law.hpp"

namespace shpb::test {

class MaterialPoint {
 public:
  explicit MaterialPoint(const MaterialSpec& spec) : law_(make_material_law(spec)) {
    law_->initialize(state_);
  }

  // Moves to strain eps over dt; returns σ. Accumulates the trapezoidal work ∫σ dε put in.
  double strain_to(double eps, double dt_s) {
    const double before = state_[0].stress_Pa;
    const double previous = state_[0].strain;
    double stress = 0;
    law_->update(std::span<const double>(&eps, 1), dt_s, state_, std::span<double>(&stress, 1));
    work_J_m3_ += 0.5 * (before + stress) * (eps - previous);
    return stress;
  }

  // Finds the strain at which the law gives stress sigma after dt (the laws here are affine in
  // the end strain over one step when no yielding happens: two trial updates on copies suffice).
  double stress_to(double sigma, double dt_s) {
    auto trial = [&](double eps) {
      std::vector<MaterialPointState> copy = state_;
      double stress = 0;
      law_->update(std::span<const double>(&eps, 1), dt_s, copy, std::span<double>(&stress, 1));
      return stress;
    };
    const double e0 = state_[0].strain;
    const double e1 = e0 + sigma / law_->max_tangent_modulus_Pa();
    const double s0 = trial(e0), s1 = trial(e1);
    const double eps = e0 + (sigma - s0) * (e1 - e0) / (s1 - s0);
    strain_to(eps, dt_s);
    return eps;
  }

  const MaterialPointState& state() const { return state_[0]; }
  const MaterialLaw& law() const { return *law_; }
  double work_J_m3() const { return work_J_m3_; }

 private:
  std::unique_ptr<MaterialLaw> law_;
  std::vector<MaterialPointState> state_ = std::vector<MaterialPointState>(1);
  double work_J_m3_ = 0;
};

}  // namespace shpb::test
