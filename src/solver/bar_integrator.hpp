#pragma once
// The per-bar explicit integrator: central difference in leapfrog form with lumped mass
// (docs/methods.md §1), over contiguous arrays. A step at t_n is split in two so that interfaces
// can add their forces to the end nodes in between:
//   1. assemble_internal_forces: f_n = −K u_n (elastic kernel, or the bar's MaterialLaw with one
//      virtual call per bar per step), over the nodes a wave can have reached;
//   2. (interfaces add contact forces to f_n[0] and f_n[last], see contact_*.hpp)
//   3. advance: v_{n+1/2} = v_{n−1/2} + Δt M⁻¹ f_n (half a step at n = 0), u_{n+1} = u_n + Δt
//   v_{n+1/2}.
// Causal economy (docs/methods.md §7): lumped central difference moves information by exactly one
// node per step, so only the node range [lo, hi] grown by one per step is updated; everything
// outside is exactly at rest relative to the rigid motion.
#include "solver/bar.hpp"

namespace shpb {

// Grows the active range by one node on each side and writes f_n over it. A quiet bar does
// nothing (its forces are zero). Returns the number of nodes in the new range.
void assemble_internal_forces(const BarModel& bar, BarState& s);

// Finite strain: ε_e = ln(1 + Δw_e/h0) of elements [e0, e1] into s.strain_next, each from its
// element's exact anchor by a series (bar_integrator.cpp; a test pins it to std::log1p).
void logarithmic_strains(BarState& s, double inv_h, int e0, int e1);
// J = exp(x) of the elastic volume change x = (1 − 2ν)τ/E, by its series for small x.
double volume_ratio(double x);

// A material-law bar's elements [e0, e1] from its displacements: strains, one law update over a
// step `dt` that led to them, axial forces (and stresses) N_e; what assemble_internal_forces does
// to its elements, for an end segment's on its own clock too (end_segment.hpp).
void law_element_forces(const BarModel& bar, BarState& s, int e0, int e1, double dt);

// Makes node i part of the active range (an interface starts loading it).
void activate_node(const BarModel& bar, BarState& s, int i);

// Non-reflecting end (a cut bar): the dashpot force −Z v_n on the last node, with the full-step
// velocity v_n taken implicitly (exact for a 1D wave leaving the bar); the energy it absorbs is
// added to the bar's dissipation. Call between assemble and advance.
void apply_dashpot(const BarModel& bar, BarState& s);

// Kick and drift over the active range; counts node updates. Returns the updated node count.
long advance(const BarModel& bar, BarState& s);

// Free (internal) force on end node `end` (0 or nodes−1) at time τ within the bar's last step,
// from the interpolated displacements (exact for elastic bars) or the last stress of a
// material-law bar: the predictor of a neighbour's end load (docs/methods.md §3). A finite
// `end_w` puts the end node there instead (an end tied to an interface frame). `law_on_path`: a
// material-law bar's end force is carried from its last assembly to the end element's length at
// τ with the instantaneous stiffness EA/h (the slow side of a tie, §3.4).
double end_free_force_at(const BarModel& bar, const BarState& s, int end, double tau_n, double tau,
                         double end_w, bool law_on_path = false);

// Element stress at t_n (tension positive): true (Cauchy) stress, force over current area.
inline double element_stress(const BarModel& bar, const BarState& s, int e) {
  if (bar.law) return s.stress_Pa[e];
  return bar.youngs_modulus_Pa * (s.w[e + 1] - s.w[e]) / bar.element_length_m;
}
// Engineering stress at t_n: axial force over the initial area (equal to the above in small
// strain).
inline double element_engineering_stress(const BarModel& bar, const BarState& s, int e) {
  if (bar.law) return s.axial_force_N[e] / bar.area_m2;
  return element_stress(bar, s, e);
}

// Energy of the bar at its current instant t_n; call between assemble and advance (the
// full-step velocity v_n = v_{n−1/2} + ½Δt a_n needs f_n).
struct BarEnergy {
  double kinetic_J = 0;
  double strain_J = 0;
  double dissipated_J = 0;  // material dissipation (plastic, viscous) so far
};
BarEnergy bar_energy(const BarModel& bar, const BarState& s);
// Node i's term of bar_energy's kinetic energy (the central difference's discrete one).
double node_kinetic_energy(const BarModel& bar, const BarState& s, int i);

// Full-step velocity v_n of node i (absolute), valid between assemble and advance.
double node_velocity_now(const BarModel& bar, const BarState& s, int i);

}  // namespace shpb
