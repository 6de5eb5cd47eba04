// Localized bipenalty with FINITE links (the seed paper's explicit interface solution, docs/methods.md
// §3 steps 1–4), used when the scene gives a penalty parameter explicitly (stiffness_factor,
// stiffness or mass_ratio); without one the rigid-link limit of contact_localized_bipenalty.cpp
// is used. DOFs (u_b1, u_b2, u_f): bar ends and the frame point; localized gaps
//   g1 = u_f − u_b1,   g2 = gap0 + u_b2 − u_f − offset        (g1 + g2 = g − offset)
// potential ½ Σ ε_s,i g_i², penalty kinetic energy ½ Σ ε_m,i ġ_i² (the frame has no mass of its
// own). With one boundary node per bar (B_iᵀ M_i⁻¹ B_i)⁻¹ = m_bi and seed eqs. (10)–(15) are
//   F_b1 = f̃_1 + ε_s,1 g1,   F_f = ε_s,2 g2 − ε_s,1 g1,   F_b2 = f̃_2 − ε_s,2 g2
//   M̂_i = m_bi + ε_m,i,   M^P = Σ ε_m,i − Σ ε_m,i² / M̂_i                      (eq. 10–11)
//   ü_f = (F_f + Σ ε_m,i F_bi / M̂_i) / M^P,   ü_bi = (F_bi + ε_m,i ü_f) / M̂_i   (eq. 12–13)
//   λ_i = m_bi ü_bi − f̃_i  (the force the interface puts on end i; eq. 14–15)
// and the frame is advanced by the same central difference as the bars.
//
// Switching (our addition, as in the limit): contact is predicted one step ahead
// (g + ġΔt ≤ 0) and activated at τ by conserving momentum, M_new v_new = M_old v_old on the 3
// DOFs (the frame row gives v_f as the ε_m-weighted mean of the ends); the frame starts at the
// left end and the remaining gap is kept as link 2's rest offset, so no penetration and no
// potential energy is created. The kinetic energy lost is contact dissipation. The links carry
// only the force of the last half step after activation (velocity-Verlet: the jump is at τ, the
// force acts from τ on). Release when the links' spring force turns tensile (g1 + g2 > 0 with
// equal stiffnesses), keeping velocities: every row of the penalty mass sums to zero, so
// Σ m_bi v_bi, the momentum, is unchanged, and the energy the links held is dissipated.
//
// Stepping: the frame moves with the common step of both neighbours; a finite-link interface
// between bars with different steps is refused at set-up (simulation.cpp): with a non-integer
// step ratio the stiff links are re-excited at every unmatched instant and the run blows up.
#include <cmath>

#include "solver/contact.hpp"

namespace shpb {

namespace {

void open_links(InterfaceState& s) {
  s.force_N = 0;
  s.energy_J = 0;
}

// ½ Σ ε_s,i g_i² + ½ Σ ε_m,i (v_f − v_bi)²: what the links hold.
double link_energy(const InterfaceModel& m, const InterfaceState& s, double g1, double g2,
                   double v1, double v2) {
  const double r1 = s.frame_v - v1, r2 = s.frame_v - v2;
  return 0.5 * (m.stiffness_N_m[0] * g1 * g1 + m.stiffness_N_m[1] * g2 * g2 +
                m.mass_penalty_kg[0] * r1 * r1 + m.mass_penalty_kg[1] * r2 * r2);
}

}  // namespace

ContactResult solve_localized_finite(const InterfaceModel& model, InterfaceState& s,
                                     const EndState& left, const EndState& right, double tau) {
  ContactResult r;
  const double m1 = left.mass, m2 = right.mass;
  const double es1 = model.stiffness_N_m[0], es2 = model.stiffness_N_m[1];
  const double em1 = model.mass_penalty_kg[0], em2 = model.mass_penalty_kg[1];
  const double dt = left.stepping ? left.step_s : right.step_s;
  double v1 = left.velocity_now(), v2 = right.velocity_now();
  // Share of λ that acts over the bars' coming kick (½Δt of it on the activation step).
  double share1 = 1, share2 = 1;
  double frame_kick = dt;
  if (!s.active) {
    if (s.gap_m + (v2 - v1) * dt > 0) {
      open_links(s);
      return r;
    }
    // Momentum-consistent activation, M_new v_new = (m1 v1, m2 v2, 0): with the frame row
    // v_f = (ε_m,1 v_b1 + ε_m,2 v_b2)/(ε_m,1 + ε_m,2), rows b_i give v_bi = (m_i v_i + ε_m,i v_f)/M̂_i,
    // a 1-unknown linear equation for v_f.
    const double mh1 = m1 + em1, mh2 = m2 + em2;
    const double vf = (em1 * m1 * v1 / mh1 + em2 * m2 * v2 / mh2) /
                      (em1 * m1 / mh1 + em2 * m2 / mh2);
    const double w1 = (m1 * v1 + em1 * vf) / mh1, w2 = (m2 * v2 + em2 * vf) / mh2;
    r.dv_left = w1 - v1;
    r.dv_right = w2 - v2;
    const double before = 0.5 * (m1 * v1 * v1 + m2 * v2 * v2);
    const double after = 0.5 * (m1 * w1 * w1 + m2 * w2 * w2 + em1 * (vf - w1) * (vf - w1) +
                                em2 * (vf - w2) * (vf - w2));
    r.dissipated_J = before - after;
    v1 = w1;
    v2 = w2;
    s.active = true;
    ++s.activations;
    s.frame_u = left.u;
    s.frame_v = vf;  // full-step velocity at τ: half a kick below
    s.frame_tau = tau;
    s.offset = s.gap_m;
    frame_kick = 0.5 * dt;
    share1 = 0.5 * dt / left.kick_s;
    share2 = 0.5 * dt / right.kick_s;
  }
  s.frame_u += (tau - s.frame_tau) * s.frame_v;
  s.frame_tau = tau;
  const double g1 = s.frame_u - left.u;
  const double g2 = model.gap0_m + right.u - s.frame_u - s.offset;
  if (es1 * g1 + es2 * g2 > 0) {
    // Unilateral release: the links would pull. What they held is dissipated (link rates on
    // the half-step velocities of the frame and the ends, which sit at the same instant).
    r.dissipated_J += link_energy(model, s, g1, g2, left.v, right.v);
    s.active = false;
    ++s.releases;
    open_links(s);
    return r;
  }
  // Seed eqs. (10)–(15) for one boundary node per bar.
  const double Fb1 = left.free_force + es1 * g1, Fb2 = right.free_force - es2 * g2;
  const double Ff = es2 * g2 - es1 * g1;
  const double mh1 = m1 + em1, mh2 = m2 + em2;
  const double mp = em1 * m1 / mh1 + em2 * m2 / mh2;  // M^P = Σ ε_m,i − Σ ε_m,i²/M̂_i
  const double af = (Ff + em1 * Fb1 / mh1 + em2 * Fb2 / mh2) / mp;
  const double lambda1 = m1 * (Fb1 + em1 * af) / mh1 - left.free_force;
  const double lambda2 = m2 * (Fb2 + em2 * af) / mh2 - right.free_force;
  if (left.stepping) r.force_left_N = share1 * lambda1;
  if (right.stepping) r.force_right_N = share2 * lambda2;
  s.force_N = 0.5 * (lambda2 - lambda1);
  // Energy at τ on full-step velocities: the frame's, and the ends' with λ's half kick (none on
  // the activation step, whose velocities are already those at τ).
  const double half = frame_kick == dt ? 0.5 * dt : 0.0;
  s.frame_v += half * af;
  s.energy_J = link_energy(model, s, g1, g2, v1 + half * lambda1 / m1, v2 + half * lambda2 / m2);
  s.frame_v += (frame_kick - half) * af;
  return r;
}

}  // namespace shpb
