#include "solver/bar_integrator.hpp"

#include <algorithm>
#include <cmath>

namespace shpb {

namespace {
// The two per-node loops below are compiled twice, for AVX2 and for the baseline x86-64, and the
// loader picks the one the CPU runs (GCC/Clang function multiversioning): twice the doubles per
// instruction, the same IEEE operations in the same order (no FMA contraction), so bit-identical
// results on every machine.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(__SANITIZE_ADDRESS__)
#define SHPB_NODE_LOOP __attribute__((target_clones("avx2", "default")))
#else
#define SHPB_NODE_LOOP
#endif

// Elastic kernel: f_i = k (w_{i+1} − 2 w_i + w_{i−1}) with one-sided ends (free ends).
SHPB_NODE_LOOP void elastic_forces(const double* w, double* f, double k, int lo, int hi, int last) {
  int a = lo, b = hi;
  if (a == 0) {
    f[0] = last > 0 ? k * (w[1] - w[0]) : 0.0;
    a = 1;
  }
  if (b == last && last > 0) {
    f[last] = k * (w[last - 1] - w[last]);
    b = last - 1;
  }
  for (int i = a; i <= b; ++i) f[i] = k * (w[i + 1] - 2.0 * w[i] + w[i - 1]);
}

// Leapfrog kick and drift over [lo, hi] (bar_integrator.hpp, step 3).
SHPB_NODE_LOOP void kick_drift(double* __restrict w, double* __restrict v, const double* __restrict f,
                               const double* __restrict inv_m, double kick, double dt, int lo, int hi) {
  for (int i = lo; i <= hi; ++i) {
    v[i] += kick * f[i] * inv_m[i];
    w[i] += dt * v[i];
  }
}

// Material-law kernel: element strains → one law update for the range → nodal forces
// f_i = A (σ_i − σ_{i−1}).
void law_forces(const BarModel& bar, BarState& s, int lo, int hi, double dt) {
  const int last = bar.nodes - 1;
  const int e0 = std::max(lo - 1, 0), e1 = std::min(hi, last - 1);
  const double inv_h = 1.0 / bar.element_length_m;
  for (int e = e0; e <= e1; ++e) s.strain_next[e] = (s.w[e + 1] - s.w[e]) * inv_h;
  const std::size_t n = static_cast<std::size_t>(e1 - e0 + 1);
  bar.law->update(std::span<const double>(s.strain_next.data() + e0, n), dt,
                  std::span<MaterialPointState>(s.points.data() + e0, n),
                  std::span<double>(s.stress_Pa.data() + e0, n));
  const double A = bar.area_m2;
  const double* sigma = s.stress_Pa.data();
  double* f = s.force.data();
  int a = lo, b = hi;
  if (a == 0) f[a++] = A * (sigma[0] - 0.0);          // free left end
  if (b == last && b >= a) f[b--] = A * (0.0 - sigma[last - 1]);  // free right end
  for (int i = a; i <= b; ++i) f[i] = A * (sigma[i] - sigma[i - 1]);
}
}  // namespace

void activate_node(const BarModel&, BarState& s, int i) {
  if (s.quiet()) {
    s.lo = s.hi = i;
    return;
  }
  s.lo = std::min(s.lo, i);
  s.hi = std::max(s.hi, i);
}

void assemble_internal_forces(const BarModel& bar, BarState& s) {
  if (s.quiet()) return;
  const int last = bar.nodes - 1;
  s.lo = std::max(s.lo - 1, 0);
  s.hi = std::min(s.hi + 1, last);
  if (bar.law) {
    // The law advances from its stored state over the step that led to t_n.
    law_forces(bar, s, s.lo, s.hi, bar.time_step_s);
  } else {
    elastic_forces(s.w.data(), s.force.data(), bar.stiffness_N_m, s.lo, s.hi, last);
  }
}

void apply_dashpot(const BarModel& bar, BarState& s) {
  const int last = bar.nodes - 1;
  if (!bar.dashpot_right || s.quiet() || s.hi < last) return;
  const double half = s.step == 0 ? 0.0 : 0.5 * bar.time_step_s;
  const double Z = bar.impedance_kg_s(), m = bar.mass_kg[last];
  // v_n = v_{n−1/2} + ½Δt (f − Z v_n)/m, solved for v_n.
  const double vn = (s.v[last] + half * s.force[last] / m) / (1 + half * Z / m);
  s.force[last] -= Z * vn;
  s.dissipated_J += Z * vn * vn * (s.step == 0 ? 0.5 : 1.0) * bar.time_step_s;
}

long advance(const BarModel& bar, BarState& s) {
  const double dt = bar.time_step_s;
  const double kick = s.step == 0 ? 0.5 * dt : dt;
  const long count = s.quiet() ? 0 : s.hi - s.lo + 1;
  if (count > 0) kick_drift(s.w.data(), s.v.data(), s.force.data(), bar.inverse_mass.data(), kick, dt, s.lo, s.hi);
  ++s.step;
  return count;
}

double end_free_force_at(const BarModel& bar, const BarState& s, int end, double tau_n,
                         double tau, double end_w) {
  const int last = bar.nodes - 1;
  if (bar.law) return end == 0 ? bar.area_m2 * s.stress_Pa[0] : -bar.area_m2 * s.stress_Pa[last - 1];
  const int other = end == 0 ? 1 : last - 1;
  const double back = tau_n - tau;
  const double w_end = std::isnan(end_w) ? s.w[end] - back * s.v[end] : end_w;
  const double w_other = s.w[other] - back * s.v[other];
  return bar.stiffness_N_m * (w_other - w_end);
}

double node_velocity_now(const BarModel& bar, const BarState& s, int i) {
  const double half = s.step == 0 ? 0.0 : 0.5 * bar.time_step_s * s.force[i] * bar.inverse_mass[i];
  const bool active = !s.quiet() && i >= s.lo && i <= s.hi;
  return bar.initial_velocity_m_s + (active ? s.v[i] + half : 0.0);
}

BarEnergy bar_energy(const BarModel& bar, const BarState& s) {
  BarEnergy e;
  const double V = bar.initial_velocity_m_s;
  double moving_mass = bar.total_mass_kg();
  if (!s.quiet()) {
    const double half = s.step == 0 ? 0.0 : 0.5 * bar.time_step_s;
    for (int i = s.lo; i <= s.hi; ++i) {
      const double vn = V + s.v[i] + half * s.force[i] * bar.inverse_mass[i];
      e.kinetic_J += 0.5 * bar.mass_kg[i] * vn * vn;
      moving_mass -= bar.mass_kg[i];
    }
    const int e0 = std::max(s.lo - 1, 0), e1 = std::min(s.hi, bar.nodes - 2);
    if (bar.law) {
      const double volume = bar.area_m2 * bar.element_length_m;
      for (int k = 0; k < bar.elements(); ++k) {
        e.strain_J += volume * bar.law->stored_energy_J_m3(s.points[k]);
        e.dissipated_J += volume * s.points[k].dissipated_J_m3;
      }
    } else {
      for (int k = e0; k <= e1; ++k) {
        const double d = s.w[k + 1] - s.w[k];
        e.strain_J += 0.5 * bar.stiffness_N_m * d * d;
      }
    }
  }
  e.kinetic_J += 0.5 * moving_mass * V * V;  // nodes outside the range move rigidly
  return e;
}

}  // namespace shpb
