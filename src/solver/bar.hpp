#pragma once
// One bar of the chain: its immutable set-up (mesh, masses, material, own time step) and its
// mutable state. Linear two-node elements with lumped mass (docs/methods.md §1).
//
// Finite strain (docs/methods.md §8; material-law bars unless the scene asks for "kinematics":
// "small"): element e of reference length h0 and area A0 has the current length L = h0 + Δw and
// stretch λ = L/h0; the law takes the logarithmic strain ε = ln λ (tension positive) and returns
// the Kirchhoff stress τ = J σ, the stress work-conjugate to ε per unit reference volume (Simo &
// Hughes 1998, "Computational Inelasticity", §9.2, logarithmic strains), so the laws' energy
// contract holds with the reference volume. The plastic (and viscous) part of ε keeps volume; the
// elastic part ε_e = τ/E changes it by (1 − 2ν) ε_e:
//   J = V/V0 = exp((1 − 2ν) τ/E),  A = A0 J / λ,  true (Cauchy) stress σ = τ / J,
//   axial force N = A σ = τ A0 / λ.
// For metals J − 1 < 0.2 %, so τ and σ differ by less than that. The area is the element's own
// (a barrel-free, uniform section), and the end elements' N is the force the interfaces see.
//
// Displacements are stored RELATIVE to the bar's initial rigid motion, u(x,t) = w(x,t) + V0·τ
// (τ = time since the start of the run): a node no wave has reached has w = 0 and v = 0 exactly,
// so the causal economy (docs/methods.md §7) can skip it and still give bit-identical results.
#include <memory>
#include <string>
#include <vector>

#include "model/material_law.hpp"

namespace shpb {

struct BarModel {
  std::string name;
  int nodes = 0;  // elements + 1
  double element_length_m = 0;
  double area_m2 = 0;
  double density_kg_m3 = 0;
  double youngs_modulus_Pa = 0;  // elastic (instantaneous) modulus
  double wave_speed_m_s = 0;
  double stiffness_N_m = 0;  // EA/h of one element
  double time_step_s = 0;    // this bar's own Δt (adaptive: its floor, at min_stretch)
  double courant = 0;
  double initial_velocity_m_s = 0;  // V0 of the rigid reference motion
  std::vector<double> mass_kg;      // lumped: ρAh/2 at the ends, ρAh inside
  std::vector<double> inverse_mass;
  std::unique_ptr<MaterialLaw> law;  // null: elastic, σ = E ε in the solver's own kernel
  bool finite_strain = false;        // material-law bars: logarithmic strain, current area (above)
  double volume_change_per_stress = 0;  // (1 − 2ν)/E of the law's elastic part, for J
  double min_stretch = 0;  // the stable step holds down to this λ (discretization.hpp)
  // Adaptive step (finite strain, solver/step_control.hpp): the step is planned from the shortest
  // element reached, C h0 λ/(c √φ), never below time_step_s; reference_step_s = C h0/c. A bar
  // with a fixed step has own_step_s (its stable step; time_step_s is the common one in global
  // stepping).
  bool adaptive_step = false;
  double reference_step_s = 0;
  double own_step_s = 0;
  // Interface friction on the specimen's faces (docs/methods.md §8.2): while the bar shortens
  // (its faces slide), its two end nodes take the axial force (φ − 1) N̄, N̄ the mean law axial
  // force of its elements that have entered flow (their law has dissipated) under compression,
  // φ = 1 + friction_factor_per_aspect · d/L of the whole bar's current diameter and length.
  double friction_factor_per_aspect = 0;  // μ/(3√3), μ the mean of the two faces' coefficients
  double diameter_m = 0;
  // Radial inertia (docs/methods.md §8, model/specimen_response.hpp): every element's axial
  // stress gets the closed-form extra ρ a² (ε̈/8 + ε̇²/16) of the whole bar's true strain rate ε̇
  // and current radius a. ε̈ is differenced from step to step and low-passed over
  // inertia_filter_s: the bar ends move in the neighbours' (coarser) steps, and the raw difference
  // of a few specimen steps is their staircase. The radial kinetic energy ρ V a² ε̇²/16 is counted.
  double radial_inertia_density_kg_m3 = 0;  // ρ; 0: off
  double inertia_filter_s = 0;
  // Causal economy (docs/methods.md §7): the right end of the last bar may be cut where its
  // reflections cannot reach anything recorded; the cut end is an exact non-reflecting dashpot.
  int full_nodes = 0;          // nodes of the uncut mesh
  bool dashpot_right = false;  // the right end is a cut with a dashpot of impedance ρcA
  // End segments (solver/end_segment.hpp, docs/methods.md §3.6): the elements next to end 0
  // (left) or 1 (right) that step on a tied neighbour's clock. The bar itself integrates nodes
  // [first_owned_node(), last_owned_node()]; the node where a segment starts (the joint) is its.
  int segment_elements[2] = {0, 0};

  int elements() const { return nodes - 1; }
  int first_owned_node() const { return segment_elements[0]; }
  int last_owned_node() const { return nodes - 1 - segment_elements[1]; }
  double impedance_kg_s() const { return density_kg_m3 * wave_speed_m_s * area_m2; }
  double total_mass_kg() const { return density_kg_m3 * area_m2 * element_length_m * elements(); }
  // The Courant number c Δt/h of a step Δt on the bar's (initial) elements.
  double courant_at(double step_s) const { return wave_speed_m_s * step_s / element_length_m; }
};

BarModel make_bar_model(std::string name, const MaterialSpec& material, double length_m,
                        double area_m2, int elements, double time_step_s, double velocity_m_s);

// State at the bar's current instant t_n = t_start + n·Δt (leapfrog): w at t_n, v at t_{n−1/2}
// (the velocity that brought the nodes to t_n), the force f at t_n being assembled.
struct BarState {
  std::vector<double> w;              // displacement relative to the rigid motion [m]
  std::vector<double> v;              // relative velocity at t_{n−1/2} [m/s]
  std::vector<double> force;          // nodal force at t_n [N]
  std::vector<double> stress_Pa;      // element true (Cauchy) stress at t_n (material-law bars)
  std::vector<double> axial_force_N;  // element axial force N = A σ at t_n (material-law bars)
  double friction_force_N = 0;        // face friction X of the last step (bar_integrator.cpp)
  double friction_length_m = 0;       // w_last − w_0 at that step (friction work X ΔL)
  double smallest_stretch = 1;        // smallest element λ reached so far (finite strain)
  double largest_stress_Pa = 0;       // largest element |τ| reached so far (finite strain)
  double inertia_rate_1_s = 0;        // whole-bar true strain rate at t_{n−1/2} (compression +)
  double inertia_acceleration_1_s2 = 0;  // its low-passed derivative
  double inertia_stress_Pa = 0;          // the radial-inertia stress applied at t_n (compression +)
  bool inertia_flowing = false;          // the radial-inertia stress is on (bar_integrator.cpp)
  bool inertia_finished = false;         // the loading is over: off for the rest of the run
  std::vector<double> strain_next;       // scratch for material laws: ε at t_n
  std::vector<double> law_stress;        // scratch for material laws: τ at t_n
  // Finite strain: per element the anchor of its logarithmic strain (bar_integrator.cpp):
  // d_a = Δw/h0 there, ln(1 + d_a), 1/(1 + d_a).
  std::vector<double> log_anchor_d, log_anchor_value, log_anchor_inverse;
  std::vector<MaterialPointState> points;  // material-law bars only
  long step = 0;                           // n
  // Steps (scheduler.hpp rule 1): Δt_n from t_n on, Δt_{n−1} that led to t_n (0 at n = 0); the
  // current phase of constant step started at instant phase_step, τ = phase_tau.
  double dt = 0, dt_prev = 0;
  long phase_step = 0;
  double phase_tau = 0;
  double planned_stretch = 1;    // adaptive: the current step holds down to this element stretch
  double planned_stress_Pa = 0;  // ... and up to this element |τ| (geometric stiffening)
  int lo = 0, hi = -1;           // nodes that may differ from rest: [lo, hi] (empty if lo > hi)
  double dissipated_J = 0;       // material dissipation so far
  long long node_updates = 0;    // nodes advanced so far (causal economy counts only active ones)

  bool quiet() const { return lo > hi; }
};

BarState make_bar_state(const BarModel& bar, bool full_model);

// Absolute displacement and velocity of node i at time τ since the start, for a bar whose state
// is at τ_n ≥ τ ≥ τ_{n−1}: the central-difference path is linear within a step, so this
// interpolation is exact (docs/methods.md §3).
inline double node_displacement_at(const BarModel& bar, const BarState& s, int i, double tau_n,
                                   double tau) {
  return s.w[i] - (tau_n - tau) * s.v[i] + bar.initial_velocity_m_s * tau;
}
// Absolute, at t_{n−1/2}.
inline double node_velocity(const BarModel& bar, const BarState& s, int i) {
  return s.v[i] + bar.initial_velocity_m_s;
}

}  // namespace shpb
