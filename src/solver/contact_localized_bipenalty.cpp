// Localized bipenalty contact (the seed paper's formulation, METHODS.md §3) in 1D: a frame point
// u_f per interface, a localized gap per bar g1 = u_f − u_b1, g2 = gap0 + u_b2 − u_f (each
// measured from its rest offset fixed at activation), each link with its own (ε_s,i, ε_m,i).
// With one boundary node per bar, (B_iᵀ M_i⁻¹ B_i)⁻¹ = m_bi and the explicit interface solution
// (seed eqs. 10–17) reduces to scalars:
//   M̂_i = m_bi + ε_m,i,  M^P = Σ ε_m,i m_bi / M̂_i            (condensed frame mass, eq. 10–11)
//   ü_f = (F_f + Σ ε_m,i F_i / M̂_i) / M^P                     (frame acceleration)
//   ü_bi = (F_i + ε_m,i ü_f) / M̂_i                             (boundary accelerations, eq. 12–13)
//   λ_i = m_bi ü_bi − f̃_i                                      (multiplier = force on bar i, eq. 14)
// with F_1 = f̃_1 + ε_s,1 g1, F_2 = f̃_2 − ε_s,2 g2, F_f = −ε_s,1 g1 + ε_s,2 g2.
//
// What keeps it from ringing (our addition to the published scheme): the contact is switched
// the way a mass matrix change must be, conserving momentum. At activation the two end nodes take
// their momentum-weighted common velocity (the inelastic node-to-node impact; V/2 for equal
// bars, the exact continuum interface velocity) and the frame is placed at the contact point with
// both localized gaps and both link rates zero; the one-step detection penetration is kept as the
// links' rest offset instead of being pushed out. From there the links carry the load quasi-
// statically (g_i ≈ F/ε_s) and the end pair acts like one merged node: a striker/bar pair at
// C = 1 reproduces the tied bar. The contact is released (unilateral) when the compressive force
// turns tensile, keeping the node velocities. The kinetic energy lost at activation (½ μ ġ², μ
// the reduced end-node mass) and the link energy at release are contact dissipation.
//
// The frame is advanced on the union of its neighbours' instants (Dvořák et al. 2023, CMAME
// 413:116110) by variable-step leapfrog: v_{k+1/2} = v_{k−1/2} + ½(Δ_{k−1} + Δ_k) ü_f.
#include "solver/contact.hpp"

namespace shpb {

ContactResult solve_localized_bipenalty(const InterfaceModel& model, InterfaceState& s,
                                        EndState left, EndState right, double tau,
                                        double frame_next_tau) {
  ContactResult r;
  const double m1 = left.mass, m2 = right.mass;
  double step_before = tau - s.frame_tau;
  const double step_after = frame_next_tau - tau;
  if (!s.active) {
    if (s.gap_m > 0) {
      s.force_N = 0;
      s.energy_J = 0;
      return r;
    }
    // Momentum-consistent activation: p = M_old v_old = M_new v_new with ε_m ≫ m_b.
    const double vc = (m1 * left.v + m2 * right.v) / (m1 + m2);
    r.dv_left = vc - left.v;
    r.dv_right = vc - right.v;
    r.dissipated_J = 0.5 * m1 * r.dv_left * r.dv_left + 0.5 * m2 * r.dv_right * r.dv_right;
    left.v = right.v = vc;
    s.active = true;
    s.frame_u = left.u;
    s.frame_v = vc;
    s.frame_tau = tau;
    s.offset[0] = 0;
    s.offset[1] = s.gap_m;  // rest offset: the detected penetration, so g2 = 0 now
    step_before = step_after;
  }
  const double uf = s.frame_u + (tau - s.frame_tau) * s.frame_v;
  const double g1 = uf - left.u - s.offset[0];
  const double g2 = model.gap0_m + right.u - uf - s.offset[1];
  const double es1 = model.stiffness_N_m[0], es2 = model.stiffness_N_m[1];
  const double em1 = model.mass_penalty_kg[0], em2 = model.mass_penalty_kg[1];
  const double F1 = left.free_force + es1 * g1;
  const double F2 = right.free_force - es2 * g2;
  const double Ff = -es1 * g1 + es2 * g2;
  const double M1 = m1 + em1, M2 = m2 + em2;
  const double condensed = em1 * m1 / M1 + em2 * m2 / M2;
  const double af = (Ff + em1 * F1 / M1 + em2 * F2 / M2) / condensed;
  const double a1 = (F1 + em1 * af) / M1;
  const double a2 = (F2 + em2 * af) / M2;
  const double on_left = m1 * a1 - left.free_force;
  const double on_right = m2 * a2 - right.free_force;

  // Compression-positive force as seen by the side(s) that use it now.
  double compression;
  if (left.stepping && right.stepping) compression = 0.5 * (on_right - on_left);
  else if (left.stepping) compression = -on_left;
  else compression = on_right;

  const double g1dot = s.frame_v - left.v, g2dot = right.v - s.frame_v;
  const double link_energy = 0.5 * (es1 * g1 * g1 + es2 * g2 * g2) +
                             0.5 * (em1 * g1dot * g1dot + em2 * g2dot * g2dot);
  if (compression < 0) {
    // Unilateral release: the links would pull. Velocities are kept; the link energy is lost.
    s.active = false;
    s.force_N = 0;
    s.energy_J = 0;
    r.dissipated_J += link_energy;
    return r;
  }
  if (left.stepping) r.force_left_N = on_left;
  if (right.stepping) r.force_right_N = on_right;
  s.force_N = compression;
  s.energy_J = link_energy;
  s.frame_v += 0.5 * (step_before + step_after) * af;
  s.frame_u = uf;
  s.frame_tau = tau;
  s.frame_dt = step_after;
  return r;
}

}  // namespace shpb
