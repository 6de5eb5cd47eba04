// Localized bipenalty with FINITE links (the seed paper's formulation, docs/methods.md §3), used
// when the scene gives a penalty parameter explicitly (stiffness_factor, stiffness, rise_time or
// mass_ratio); without one the rigid-link limit of contact_localized_bipenalty.cpp is used. Each
// side keeps its own time step, at any step ratio.
//
// The seed paper's DOFs are the bar ends and a frame point, (u_b1, u_b2, u_f), with localized
// gaps to the frame, potential ½ Σ ε_s,i g_i² and penalty kinetic energy ½ Σ ε_m,i ġ_i². Written
// per side in the link's extension d_i = u_f − e_i (e_i: end i in the frame's coordinate, the right
// end shifted by gap0 − the rest offset), the kinetic energy is diagonal,
//   T = ½ Σ m_bi ė_i² + ½ Σ ε_m,i ḋ_i²,   V = V_bars + ½ Σ ε_s,i d_i²,
// and the frame becomes two HALF-FRAMES φ_i = e_i + d_i tied by φ_1 = φ_2. A tie force Λ_i on φ_i
// (Λ_1 + Λ_2 = 0) acts on both of its side's DOFs:
//   m_bi ë_i = f̃_i + Λ_i,    ε_m,i d̈_i = Λ_i − ε_s,i d_i,
// so Λ_i is exactly the force the interface puts on bar i (the seed's multiplier λ_i, eq. 14), and
// φ̈_i = a_i + Λ_i/μ_i with a_i = f̃_i/m_bi − ε_s,i d_i/ε_m,i and μ_i = m_bi ε_m,i/(m_bi + ε_m,i)
// (the condensed penalty mass M^P of eq. 10–11 is μ_1 + μ_2). The tie gives
//   ü_f = (μ_1 a_1 + μ_2 a_2)/(μ_1 + μ_2),   Λ_2 = −Λ_1 = μ_1 μ_2 (a_1 − a_2)/(μ_1 + μ_2).
// With one common step this is the seed's explicit scheme in other coordinates (central
// difference commutes with a linear change of variables), so R_i ≤ (2 c_i/h_i)² keeps each bar's
// critical step for any ε_s. In the limit ε_s, ε_m → ∞ at fixed R, d_i → 0, μ_i → m_bi and it is
// the rigid-link limit.
//
// Asynchronous steps (our design, after Dvořák et al. 2023, CMAME 413:116110): each side OWNS its
// link and its half-frame (with its penalty mass) and advances them with its own step Δt_i, by
// the same central difference as its bar; the two half-frames are tied by the rigid frame
// coupling of the limit: the frame is advanced on the union of both sides' instants by
// variable-step leapfrog with ü_f above, a side that is ahead giving its end load and its link
// extension on their linear paths (scheduler.hpp rule 4). A stepping side takes the tie force
// that makes its half-frame (end + link) leave with the frame's velocity,
//   Λ_i = μ_i [(v_f − v_bi − ḋ_i)/Δt_i − a_i],
// which is μ_i (ü_f − a_i) at a common step. Which of end and half-frame carries the other is
// decided by the heavier: with ε_m,i ≥ m_bi (stiff links, e.g. the default ε_s = 10⁴ EA/h) the
// link (d_i, ḋ_i) is integrated and the end is reset behind the frame at its next instant, as in
// the limit; with ε_m,i < m_bi (compliant links, rise_time) the end is left to its bar and d_i is
// measured, frame − end — resetting a heavy end to a light frame made the compliant
// asynchronous run blow up (energy ×10³ at step ratio 2.19). Nothing is applied at an instant a
// side does not own, so the links are not re-excited there. Both links take the same
// R = mass_ratio × min_i R_crit,i (contact.cpp): with compliant links the frame moves on the links
// alone at ω² = Σ ε_s,i / Σ ε_m,i, which the side with the longer step must resolve. Measured
// (study --sweep stability, asynchronous, step ratios 1, π, π²): stable up to C ≈ 1 for
// R ≤ R_crit at every ε_s/k = 10⁻² … 10⁶, and above R_crit the 2/√R step for ε_s ≳ 10 k.
//
// Switching (as in the limit, decided on the force Λ the interface puts on the bars): contact is
// predicted one step ahead (closes_within in contact.hpp: ġ ≤ 0 and g + ġΔ ≤ 0, Δ to the next union
// instant: ends that separate after a release are not closed again) and closes by the impulsive tie
// of the half-frames, which conserves momentum (the penalty mass carries none): both take the
// μ-weighted velocity, end i's velocity jumps by Π_i/m_bi and its link rate by Π_i/ε_m,i; the
// remaining gap is kept as the links' rest offset, so no penetration and no potential energy is
// created, and the kinetic energy lost is contact dissipation. It releases only when the tie force
// Λ turns tensile; a free ring of the link (ε_m d̈ + ε_s d = 0) puts no force on the bars and cannot
// release it, so an interface under compression stays closed. What the links hold at release
// (≈ 0, Λ ≈ 0 there) is dissipated.
#include <cmath>

#include "solver/contact.hpp"

namespace shpb {

namespace {

void open_links(InterfaceState& s) {
  s.force_N = 0;
  s.energy_J = 0;
  for (int i = 0; i < 2; ++i) s.link_d[i] = s.link_v[i] = 0;
}

}  // namespace

ContactResult solve_localized_finite(const InterfaceModel& model, InterfaceState& s, EndState left,
                                     EndState right, double tau, double frame_next_tau) {
  ContactResult r;
  EndState* end[2] = {&left, &right};
  const double* es = model.stiffness_N_m;
  const double* em = model.mass_penalty_kg;
  double mu[2];
  for (int i = 0; i < 2; ++i) mu[i] = end[i]->mass * em[i] / (end[i]->mass + em[i]);
  const double step_after = frame_next_tau - tau;
  double kick = 0.5 * (tau - s.frame_tau + step_after);
  if (!s.active) {
    const double v1 = left.velocity_now(tau), v2 = right.velocity_now(tau);
    if (!closes_within(s.gap_m, v1, v2, step_after)) {
      open_links(s);
      return r;
    }
    // Impulsive tie of the half-frames at τ, on the full-step velocities (the half-step ones are
    // shifted by the same jumps): φ_i answers an impulse with the mass μ_i.
    const double vc = (mu[0] * v1 + mu[1] * v2) / (mu[0] + mu[1]);
    const double impulse[2] = {mu[0] * (vc - v1), -mu[0] * (vc - v1)};
    const double v[2] = {v1, v2};
    r.dv_left = impulse[0] / left.mass;
    r.dv_right = impulse[1] / right.mass;
    for (int i = 0; i < 2; ++i) {
      const double dv = impulse[i] / end[i]->mass, rate = impulse[i] / em[i];
      const double w = v[i] + dv;
      r.dissipated_J += 0.5 * end[i]->mass * (v[i] * v[i] - w * w) - 0.5 * em[i] * rate * rate;
      end[i]->v += dv;
      // Unstretched at τ; an integrated link of a side that is ahead is carried to its pending
      // instant (as its end is, scheduler.hpp rule 6).
      s.link_v[i] = rate;
      s.link_tau[i] = model.end_follows_frame[i] && !end[i]->stepping ? end[i]->next_tau : tau;
      s.link_d[i] = (s.link_tau[i] - tau) * rate;
    }
    s.close_frame(left.u, vc, tau);
    kick = 0.5 * step_after;  // from the full-step velocity: half a kick
  }
  // Link extensions at τ, from the frame and the ends (an ahead end on its linear path), and the
  // half-frames' free accelerations.
  const double uf = s.frame_u + (tau - s.frame_tau) * s.frame_v;
  const double e[2] = {left.u, right.u + model.gap0_m - s.offset};
  double d[2], a[2];
  for (int i = 0; i < 2; ++i) {
    d[i] =
        model.end_follows_frame[i] ? s.link_d[i] - (s.link_tau[i] - tau) * s.link_v[i] : uf - e[i];
    a[i] = end[i]->free_force / end[i]->mass - es[i] * d[i] / em[i];
  }
  const double compression = mu[0] * mu[1] * (a[0] - a[1]) / (mu[0] + mu[1]);  // Λ_2
  if (compression < 0) {
    // Unilateral release: the interface would pull the bars. Velocities are kept; what the links
    // hold is dissipated.
    for (int i = 0; i < 2; ++i)
      r.dissipated_J += 0.5 * (es[i] * d[i] * d[i] + em[i] * s.link_v[i] * s.link_v[i]);
    s.active = false;
    ++s.releases;
    open_links(s);
    return r;
  }
  s.frame_u = uf;
  s.frame_tau = tau;
  s.frame_v_before = s.frame_v;
  s.frame_v += kick * (mu[0] * a[0] + mu[1] * a[1]) / (mu[0] + mu[1]);
  double energy = 0;
  double force[2] = {0, 0};
  for (int i = 0; i < 2; ++i) {
    const EndState& en = *end[i];
    double rate = s.link_v[i];
    if (en.stepping && model.end_follows_frame[i]) {
      // The tie force that makes the half-frame leave with the frame's velocity; the link is
      // integrated with this side's step and its end reset behind it at the next instant.
      force[i] = mu[i] * ((s.frame_v - en.v - s.link_v[i]) / en.kick_s - a[i]);
      s.link_v[i] += en.kick_s * (force[i] - es[i] * d[i]) / em[i];
      s.link_d[i] = d[i] + en.step_s * s.link_v[i];
      s.link_tau[i] = en.next_tau;
      rate = 0.5 * (rate + s.link_v[i]);
    } else if (en.stepping) {
      // The link's rate over this side's last step (the impulse's on the closing step), and the
      // tie force that makes the half-frame leave with the frame's velocity.
      const double before =
          tau > s.link_tau[i] ? (d[i] - s.link_d[i]) / (tau - s.link_tau[i]) : s.link_v[i];
      force[i] = mu[i] * ((s.frame_v - en.v - before) / en.kick_s - a[i]);
      const double after = before + en.kick_s * (force[i] - es[i] * d[i]) / em[i];
      rate = 0.5 * (before + after);
      s.link_d[i] = d[i];
      s.link_v[i] = after;
      s.link_tau[i] = tau;
    }
    energy += 0.5 * (es[i] * d[i] * d[i] + em[i] * rate * rate);
  }
  r.force_left_N = force[0];
  r.force_right_N = force[1];
  s.force_N = compression;
  s.energy_J = energy;
  return r;
}

}  // namespace shpb
