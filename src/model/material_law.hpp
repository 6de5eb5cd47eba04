#pragma once
// 1D uniaxial-stress material laws used by a bar's elements. One virtual call per bar per step:
// a law updates all elements of a bar at once over contiguous arrays (no per-element dispatch).
// Elastic bars do not use this at all: the solver's elastic kernel is σ = E ε.
#include <memory>
#include <span>

#include "model/material.hpp"

namespace shpb {

// Per-element state, tension positive (docs/outputs.md (conventions)). Strain is what the bar feeds
// the law: logarithmic with finite strain (solver/bar.hpp; the stress is then Kirchhoff), else
// engineering.
struct MaterialPointState {
  static constexpr int kMaxArms = 8;
  double strain = 0;           // ε at the last update
  double stress_Pa = 0;        // σ at the last update
  double plastic_strain = 0;   // equivalent (accumulated) plastic strain
  double back_strain = 0;      // signed plastic strain ε_p (for return mapping)
  double temperature_K = 0;    // current temperature (adiabatic heating)
  double dissipated_J_m3 = 0;  // plastic + viscous work per unit volume, cumulative
  double heat_J_m3 = 0;        // part of it turned into heat (β × plastic work)
  // ENERGY CONTRACT (for the solver, "sim"): every law books, step by step,
  //   ½(σ_n + σ_{n+1})(ε_{n+1} − ε_n) = Δ stored_energy_J_m3(state) + Δ dissipated_J_m3
  // exactly (to round-off). So a bar's strain_J = Σ stored_energy_J_m3 × element volume and its
  // dissipated_J = Σ dissipated_J_m3 × element volume close the energy balance with the trapezoidal
  // internal work. heat_J_m3 ≤ dissipated_J_m3 is the heat part (the rest is stored cold work,
  // still unrecoverable, hence counted as dissipated).
  double arm_stress_Pa[kMaxArms] = {};  // Maxwell arm stresses (viscoelastic)
  // Johnson–Cook caches (johnson_cook_law.cpp), each a true pair (x, f(x)) from the start:
  // jc_p_pow_n = jc_p^n and jc_T_pow_m = T*(jc_T)^m, so a step near the cached point needs no pow
  // (nor log, for the rate pair); the reciprocals make a step's relative offset a product.
  double jc_p = 0, jc_p_pow_n = 0;
  double jc_T = 0, jc_T_pow_m = 0, jc_T_inv = 0;  // jc_T_inv = 1/(jc_T − T_room) (0: no base)
  double jc_rate = 0, jc_log_rate = 0, jc_rate_inv = 0;  // ln and 1/ of the rate ratio |ε̇|/ε̇0
  double jc_filtered_rate = 0;  // |ε̇| through the law's strain-rate filter (1/s), when on
  double jc_bound = -1;  // (A + B jc_p^n)(1 − T*(jc_T)^m): elastic below it (none yet: −1)
};

class MaterialLaw {
 public:
  virtual ~MaterialLaw() = default;

  // Sets every state to the unstrained, unstressed state at the initial temperature.
  virtual void initialize(std::span<MaterialPointState> states) const = 0;

  // Advances every element from its stored strain to strain_next[i] over dt_s (strain rate
  // (strain_next − strain)/dt), writes σ into stress_out[i] and updates the state.
  virtual void update(std::span<const double> strain_next, double dt_s,
                      std::span<MaterialPointState> states, std::span<double> stress_out) const = 0;

  // Largest tangent modulus the law can ever show (the elastic modulus for every law here):
  // the specimen's stable step is fixed at this elastic bound. Why not follow the current
  // tangent: every law here unloads (or, viscoelastic, responds instantly) with this modulus at
  // any step, so a step sized on a softer plastic tangent would go unstable the moment an element
  // unloads; and the specimen is a few dozen elements, so the fixed step costs next to nothing.
  virtual double max_tangent_modulus_Pa() const = 0;

  // Recoverable (elastic) strain energy per unit volume held in a state.
  virtual double stored_energy_J_m3(const MaterialPointState& state) const = 0;
};

std::unique_ptr<MaterialLaw> make_material_law(const MaterialSpec& spec);

}  // namespace shpb
