// Localized bipenalty contact, the DEFAULT: the rigid-link limit of the seed paper's formulation,
// used when the scene gives no penalty parameter (with one, contact_localized_finite.cpp solves
// the finite links). Why the limit is the default: measured plateau std 0.05 % at C = 0.995 with
// any stepping, asynchronous included, and no penalty value to choose (finite links at the
// default ε_s = 10⁴ EA/h give the same gauges to 0.1 %).
//
// The seed paper's formulation (docs/methods.md §3) in 1D: a frame point
// u_f per interface, a localized gap per bar g1 = u_f − u_b1, g2 = gap0 + u_b2 − u_f, each link
// with its own (ε_s,i, ε_m,i = ε_s,i/R_i). With one boundary node per bar, (B_iᵀ M_i⁻¹ B_i)⁻¹ =
// m_bi and the explicit interface solution (seed eqs. 10–17) is, in scalars,
//   M̂_i = m_bi + ε_m,i,   M^P = Σ ε_m,i m_bi / M̂_i                 (condensed frame mass)
//   ü_f = (F_f + Σ ε_m,i F_i / M̂_i) / M^P,   ü_bi = (F_i + ε_m,i ü_f) / M̂_i
//   λ_i = m_bi ü_bi − f̃_i                                            (multiplier: force on bar i)
// with F_1 = f̃_1 + ε_s,1 g1, F_2 = f̃_2 − ε_s,2 g2.
//
// Why a plain bipenalty interface rings, and what we do instead (our addition): the mass penalty
// ε_m ≈ 2500 ρAh dwarfs the end-node masses, so the gap mode has frequency ≈ √R ≈ 2/Δt and enormous
// inertia: started by a relative velocity or a penetration at switch-on, it rings at the Nyquist
// rate for ever (the ringing plateau of docs/methods.md §2). A mass matrix change must conserve
// momentum, p = M_old v_old = M_new v_new: for ε_m ≫ m_b that is the inelastic node-to-node impact,
// both ends take their momentum-weighted velocity (V/2 for equal bars: the exact continuum
// interface velocity), the frame is placed at the contact point with both localized gaps and link
// rates zero; contact is predicted one step ahead (closes_within: g + ġΔ ≤ 0) so that no
// penetration is created, the small remaining gap being kept as the links' rest offset. From that
// state the links are loaded quasi-statically, g_i = −λ_i/ε_s,i, a fraction ~1/ε_s-factor (10⁻⁴ at
// the default) of an element's stretch: the equations above then hold in their limit ε_s, ε_m → ∞
// at fixed R, M^P → m_b1 + m_b2, ü_bi → ü_f, λ_i = m_bi ü_f − f̃_i, which is what is solved here —
// the end pair moves as one merged node and a same-Δt striker/bar pair reproduces the tied bar
// (exact at C = 1).
//
// Asynchronous steps (after Dvořák et al. 2023, CMAME 413:116110): the frame carries the
// condensed mass m_b1 + m_b2 and is advanced on the union of its neighbours' instants by
// variable-step leapfrog, v_{k+1/2} = v_{k−1/2} + ½(Δ_{k−1} + Δ_k) ü_f, ü_f = (f̃_1 + f̃_2)/(m_b1 +
// m_b2), both end loads taken at the instant (a neighbour that is ahead gives the load of its end
// element with its inner node interpolated on its linear path and its end at the frame). A
// stepping end is reset to the frame's displacement before its forces are assembled and leaves
// with the frame's velocity: λ_i is the force that makes it so over its own step. Release
// (unilateral) when the merged-node contact force (m_b2 f̃_1 − m_b1 f̃_2)/(m_b1 + m_b2) turns
// tensile, keeping velocities; the kinetic energy lost at activation, ½ μ ġ² with μ the reduced
// end-node mass, is contact dissipation (≈ h/(4L_s) of a striker's energy).
#include <cmath>

#include "solver/contact.hpp"

namespace shpb {

ContactResult solve_localized_bipenalty(const InterfaceModel& model, InterfaceState& s,
                                        EndState left, EndState right, double tau,
                                        double frame_next_tau) {
  // A bonded interface (`contact.method: "bonded"`, a specimen glued or threaded into the bars of
  // a tension bar) is the same rigid link made bilateral: it closes while the faces touch, whatever
  // their relative velocity, and never releases.
  const bool bonded = model.method == ContactMethod::kBonded;
  ContactResult r;
  const double m1 = left.mass, m2 = right.mass, mass = m1 + m2;
  const double step_after = frame_next_tau - tau;
  double kick = 0.5 * (tau - s.frame_tau + step_after);
  if (!s.active) {
    // Ends that separate stay open (measured: closing on the rest offset's penetration gave
    // 450–800 closings in the asynchronous tail instead of 4).
    const double v1 = left.velocity_now(tau), v2 = right.velocity_now(tau);
    const bool stays_open = !closes_within(s.gap_m, v1, v2, step_after);
    if (stays_open && !(bonded && s.gap_m <= 0)) {
      s.force_N = 0;
      s.energy_J = 0;
      return r;
    }
    // Momentum-consistent activation at τ: p = M_old v_old = M_new v_new with ε_m ≫ m_b, on the
    // full-step velocities (the half-step ones are shifted by the same jump).
    const double vc = (m1 * v1 + m2 * v2) / mass;
    r.dv_left = vc - v1;
    r.dv_right = vc - v2;
    r.dissipated_J = 0.5 * m1 * r.dv_left * r.dv_left + 0.5 * m2 * r.dv_right * r.dv_right;
    left.v += r.dv_left;
    right.v += r.dv_right;
    s.close_frame(left.u, vc, tau);
    kick = 0.5 * step_after;  // from the full-step velocity: half a kick
  }
  // Merged-node contact force, compression positive.
  const double compression = (m2 * left.free_force - m1 * right.free_force) / mass;
  if (compression < 0 && !bonded) {
    // Unilateral release: the interface would pull. Velocities are kept.
    s.active = false;
    ++s.releases;
    s.force_N = 0;
    s.energy_J = 0;
    return r;
  }
  s.frame_u += (tau - s.frame_tau) * s.frame_v;
  s.frame_tau = tau;
  s.frame_v_before = s.frame_v;
  s.frame_v += kick * (left.free_force + right.free_force) / mass;
  // λ_i: the force that makes a stepping end leave with the frame's velocity.
  if (left.stepping) r.force_left_N = m1 * (s.frame_v - left.v) / left.kick_s - left.free_force;
  if (right.stepping)
    r.force_right_N = m2 * (s.frame_v - right.v) / right.kick_s - right.free_force;
  s.force_N = compression;
  s.energy_J = 0;  // rigid links in the limit: no energy held
  return r;
}

}  // namespace shpb
