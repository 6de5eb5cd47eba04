#include "solver/bar_integrator.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/target_clones.hpp"
#include "model/specimen_response.hpp"

namespace shpb {

namespace {
// The per-node loops below are multiversioned for AVX2 (core/target_clones.hpp).

// Elastic kernel: f_i = k (w_{i+1} − 2 w_i + w_{i−1}) with one-sided ends (free ends).
SHPB_TARGET_CLONES void elastic_forces(const double* w, double* f, double k, int lo, int hi,
                                       int last) {
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
SHPB_TARGET_CLONES void kick_drift(double* __restrict w, double* __restrict v,
                                   const double* __restrict f, const double* __restrict inv_m,
                                   double kick, double dt, int lo, int hi) {
  for (int i = lo; i <= hi; ++i) {
    v[i] += kick * f[i] * inv_m[i];
    w[i] += dt * v[i];
  }
}

// Logarithmic strain ε_e = ln(1 + d_e), d_e = Δw_e/h0 (finite strain, bar.hpp), without a log
// per element and step: each element keeps an anchor (d_a, ln(1 + d_a) from std::log1p, 1/(1 +
// d_a)) and ln(1 + d) = ln(1 + d_a) + ln(1 + x), x = (d − d_a)/(1 + d_a), by the series of ln(1 +
// x) to x⁶ while |x| ≤ kLogAnchorRange (remainder x⁷/7 ≤ 2e-22: round-off); an element that moved
// farther is re-anchored at d exactly. The anchor is an exact pair (never a running sum): no drift.
// At SHPB rates an element moves ~1e-5 of its length per step, so one log per ~100 steps.
constexpr double kLogAnchorRange = 1e-3;
SHPB_TARGET_CLONES void log_strains(const double* __restrict w, double* __restrict strain,
                                    const double* __restrict anchor_d,
                                    const double* __restrict anchor_log,
                                    const double* __restrict anchor_inverse, double inv_h, int e0,
                                    int e1, int* far) {
  int outside = 0;
  for (int e = e0; e <= e1; ++e) {
    const double x = ((w[e + 1] - w[e]) * inv_h - anchor_d[e]) * anchor_inverse[e];
    const double x2 = x * x;
    // x − x²/2 + x³/3 − x⁴/4 + x⁵/5 − x⁶/6 in Estrin's form (as johnson_cook_law.cpp's log_rate).
    strain[e] = anchor_log[e] +
                (x * (1 - 0.5 * x) + x2 * x * ((1.0 / 3 - 0.25 * x) + x2 * (0.2 - x * (1.0 / 6))));
    outside |= !(std::abs(x) <= kLogAnchorRange);
  }
  *far = outside;
}

}  // namespace

void logarithmic_strains(BarState& s, double inv_h, int e0, int e1) {
  int far = 0;
  log_strains(s.w.data(), s.strain_next.data(), s.log_anchor_d.data(), s.log_anchor_value.data(),
              s.log_anchor_inverse.data(), inv_h, e0, e1, &far);
  if (!far) return;
  for (int e = e0; e <= e1; ++e) {
    const double d = (s.w[e + 1] - s.w[e]) * inv_h;
    if (!(std::abs((d - s.log_anchor_d[e]) * s.log_anchor_inverse[e]) <= kLogAnchorRange)) {
      s.log_anchor_d[e] = d;
      s.log_anchor_value[e] = std::log1p(d);
      s.log_anchor_inverse[e] = 1 / (1 + d);
      s.strain_next[e] = s.log_anchor_value[e];
    }
  }
}

// J = exp(x) for the elastic volume change x = (1 − 2ν)τ/E, below 1e-2 for any solid: by its
// series to x⁸ while |x| ≤ kExpSeriesRange (remainder x⁹/9! ≤ 3e-24, round-off), else std::exp.
// (A plastically flowing Al 6061 specimen has x ≈ 2e-3: the range covers it.)
constexpr double kExpSeriesRange = 1e-2;
inline double exp_series(double x) {
  const double x2 = x * x, x4 = x2 * x2;
  return ((1 + x) + x2 * (0.5 + x * (1.0 / 6))) +
         x4 * ((1.0 / 24 + x * (1.0 / 120)) + x2 * (1.0 / 720 + x * (1.0 / 5040)) +
               x4 * (1.0 / 40320));
}
double volume_ratio(double x) {
  if (!(std::abs(x) <= kExpSeriesRange)) return std::exp(x);
  return exp_series(x);
}

namespace {
// Finite strain without friction (bar.hpp): N_e = (τ − inertia J) A0/λ, σ = N_e λ/(A0 J) with J
// by volume_ratio's series, and the smallest stretch. False (nothing written) if some element's
// volume change is beyond the series' range (then the general loop does it with std::exp).
SHPB_TARGET_CLONES bool finite_strain_kernel(const double* __restrict w,
                                             const double* __restrict tau,
                                             double* __restrict axial_force,
                                             double* __restrict stress, double kappa,
                                             double inertia, double A0, double inv_h, int e0,
                                             int e1, double* smallest, double* largest) {
  int outside = 0;
  for (int e = e0; e <= e1; ++e) outside |= !(std::abs(kappa * tau[e]) <= kExpSeriesRange);
  if (outside) return false;
  for (int e = e0; e <= e1; ++e) {
    const double stretch = 1 + (w[e + 1] - w[e]) * inv_h;
    const double J = exp_series(kappa * tau[e]);
    const double axial = tau[e] - inertia * J;  // Kirchhoff: the true inertia stress × J
    axial_force[e] = axial * A0 / stretch;
    stress[e] = axial / J;
  }
  double m = *smallest, t = *largest;  // loops of their own: reductions keep the one above scalar
  for (int e = e0; e <= e1; ++e) m = std::min(m, 1 + (w[e + 1] - w[e]) * inv_h);
  for (int e = e0; e <= e1; ++e) t = std::max(t, std::abs(tau[e]));
  *smallest = m;
  *largest = t;
  return true;
}

bool finite_strain_forces(BarState& s, double kappa, double inertia, double A0, double inv_h,
                          int e0, int e1) {
  return finite_strain_kernel(s.w.data(), s.law_stress.data(), s.axial_force_N.data(),
                              s.stress_Pa.data(), kappa, inertia, A0, inv_h, e0, e1,
                              &s.smallest_stretch, &s.largest_stress_Pa);
}

}  // namespace

// Material-law kernel, elements [e0, e1]: strains → one law update → axial forces N_e. Finite
// strain, friction and radial inertia as in bar.hpp.
void law_element_forces(const BarModel& bar, BarState& s, int e0, int e1, double dt) {
  const double h0 = bar.element_length_m, inv_h = 1.0 / h0;
  if (bar.finite_strain) {
    logarithmic_strains(s, inv_h, e0, e1);
  } else {
    for (int e = e0; e <= e1; ++e) s.strain_next[e] = (s.w[e + 1] - s.w[e]) * inv_h;
  }
  // Friction work ½ X_n ΔL + ½ X_{n+1} ΔL of the face force X over the bar's change of length,
  // trapezoidal like the laws' own (material_law.hpp, energy contract): first half here.
  const bool friction = bar.friction_factor_per_aspect > 0;
  const int last = bar.nodes - 1;
  const double length_change = friction ? (s.w[last] - s.w[0]) - s.friction_length_m : 0.0;
  if (friction) {
    s.dissipated_J += 0.5 * s.friction_force_N * length_change;
    s.friction_length_m = s.w[last] - s.w[0];
  }
  const std::size_t n = static_cast<std::size_t>(e1 - e0 + 1);
  bar.law->update(std::span<const double>(s.strain_next.data() + e0, n), dt,
                  std::span<MaterialPointState>(s.points.data() + e0, n),
                  std::span<double>(s.law_stress.data() + e0, n));
  // Friction factor φ of the whole bar at its current aspect (volume-conserving diameter), and
  // whether its faces slide: the bar shortens (its ends approach at t_{n−1/2}), so its section
  // grows under the faces.
  double phi = 1;
  bool sliding = false;
  if (friction) {
    const double length0 = h0 * bar.elements();
    const double stretch = 1 + (s.w[last] - s.w[0]) / length0;
    const double d = bar.finite_strain ? bar.diameter_m / std::sqrt(stretch) : bar.diameter_m;
    phi = 1 + bar.friction_factor_per_aspect * d / (length0 * stretch);
    sliding = s.v[last] < s.v[0];
  }
  // Radial inertia of the whole bar (bar.hpp), compression positive.
  double inertia = 0;
  if (bar.radial_inertia_density_kg_m3 > 0) {
    const double length0 = h0 * bar.elements();
    const double stretch = 1 + (s.w[last] - s.w[0]) / length0;
    const double rate = -(s.v[last] - s.v[0]) / (length0 * stretch);
    const double raw = s.step > 0 ? (rate - s.inertia_rate_1_s) / dt : 0.0;
    s.inertia_acceleration_1_s2 +=
        (raw - s.inertia_acceleration_1_s2) * dt / (dt + bar.inertia_filter_s);
    s.inertia_rate_1_s = rate;
    // Only during the loading of the test: from when the bar is squeezed (both end elements
    // compressive) and shortening until it first stops shortening. The closed form is that of
    // volume-conserving flow, and once contact opens a free specimen's lumped end masses are far
    // lighter than the radial mass ρπa⁴/(8L) the explicit term would put between them.
    if (s.inertia_flowing && rate <= 0) s.inertia_finished = true;
    const bool flowing =
        !s.inertia_finished && rate > 0 && s.law_stress[0] < 0 && s.law_stress[last - 1] < 0;
    const double radius = 0.5 * bar.diameter_m / (bar.finite_strain ? std::sqrt(stretch) : 1.0);
    if (flowing)
      inertia = radial_inertia_stress(bar.radial_inertia_density_kg_m3, radius, rate,
                                      s.inertia_acceleration_1_s2);
    s.inertia_stress_Pa = inertia;
    s.inertia_flowing = flowing;
  }
  const double A0 = bar.area_m2;
  // Finite strain without friction (the usual specimen): the same operations over contiguous
  // arrays, in a loop the compiler vectorizes.
  const bool plain_finite =
      bar.finite_strain && !friction &&
      finite_strain_forces(s, bar.volume_change_per_stress, inertia, A0, inv_h, e0, e1);
  if (plain_finite) return;
  for (int e = e0; e <= e1; ++e) {
    const double tau = s.law_stress[e];
    if (bar.finite_strain) {
      const double stretch = 1 + (s.w[e + 1] - s.w[e]) * inv_h;
      const double J = volume_ratio(bar.volume_change_per_stress * tau);
      const double axial = tau - inertia * J;  // Kirchhoff: the true inertia stress × J
      s.axial_force_N[e] = axial * A0 / stretch;
      s.stress_Pa[e] = axial / J;
      s.smallest_stretch = std::min(s.smallest_stretch, stretch);
      s.largest_stress_Pa = std::max(s.largest_stress_Pa, std::abs(tau));
    } else {
      s.axial_force_N[e] = (tau - inertia) * A0;
      s.stress_Pa[e] = tau - inertia;
    }
  }
  if (!friction) return;
  // Friction raises the pressure needed for flow (Dharan & Hauser), a property of the flowing
  // specimen whatever its law (docs/methods.md §8.2). It acts at the faces, where they slide: a
  // pair of axial forces X = (φ − 1) N̄ on the two end nodes, N̄ the mean over the bar's elements of
  // the law's axial force of an element that has entered flow (its law has dissipated) under face
  // pressure (compressive stress), 0 for the others; X is on while the faces slide. Added to every
  // element's axial force it cancels at the inner nodes. Its work is X ΔL, ΔL ≤ 0 while it acts:
  // it only dissipates, where a stress (φ − 1) τ_e per element did work on every element that
  // lengthened while the bar shortened (a ringing element after unloading) and fed its ringing.
  // Element e's stretch λ and volume ratio J (1 and 1 at small strain): N = τ A0/λ, σ = N λ/(A0 J).
  const auto stretch = [&](int e) {
    return bar.finite_strain ? 1 + (s.w[e + 1] - s.w[e]) * inv_h : 1.0;
  };
  const auto volume = [&](int e) {
    return bar.finite_strain ? volume_ratio(bar.volume_change_per_stress * s.law_stress[e]) : 1.0;
  };
  double flowing_force = 0;
  for (int e = 0; e < last; ++e)
    if (s.law_stress[e] < 0 && s.points[e].dissipated_J_m3 > 0)
      flowing_force += s.law_stress[e] * A0 / stretch(e);
  s.friction_force_N = sliding ? (phi - 1) * flowing_force / last : 0.0;
  s.dissipated_J += 0.5 * s.friction_force_N * length_change;
  for (int e = e0; e <= e1; ++e) {
    s.axial_force_N[e] += s.friction_force_N;
    s.stress_Pa[e] = s.axial_force_N[e] * stretch(e) / (A0 * volume(e));
  }
}

namespace {
// Nodal forces f_i = N_i − N_{i−1} of a material-law bar over [lo, hi] within its owned nodes
// [first, last], whose ends are free (a joint's force is its owned element's alone).
void law_forces(const BarModel& bar, BarState& s, int lo, int hi, double dt) {
  const int first = bar.first_owned_node(), last = bar.last_owned_node();
  law_element_forces(bar, s, std::max(lo - 1, first), std::min(hi, last - 1), dt);
  const double* N = s.axial_force_N.data();
  double* f = s.force.data();
  int a = lo, b = hi;
  if (a == first) f[a++] = N[first] - 0.0;              // free left end
  if (b == last && b >= a) f[b--] = 0.0 - N[last - 1];  // free right end
  for (int i = a; i <= b; ++i) f[i] = N[i] - N[i - 1];
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
  // Nodes of end segments are another clock's (end_segment.hpp): the owned nodes end at the
  // joints, whose force here is their owned element's alone, as at a free end.
  const int first = bar.first_owned_node(), last = bar.last_owned_node();
  s.lo = std::max(s.lo - 1, first);
  s.hi = std::min(s.hi + 1, last);
  if (bar.law) {
    // The law advances from its stored state over the step that led to t_n.
    law_forces(bar, s, s.lo, s.hi, s.step > 0 ? s.dt_prev : s.dt);
  } else {
    elastic_forces(s.w.data() + first, s.force.data() + first, bar.stiffness_N_m, s.lo - first,
                   s.hi - first, last - first);
  }
}

void apply_dashpot(const BarModel& bar, BarState& s) {
  const int last = bar.nodes - 1;
  if (!bar.dashpot_right || s.quiet() || s.hi < last) return;
  const double half = 0.5 * s.dt_prev;  // v_n = v_{n−1/2} + ½Δt_{n−1} a_n (0 at n = 0)
  const double Z = bar.impedance_kg_s(), m = bar.mass_kg[last];
  // v_n = v_{n−1/2} + ½Δt (f − Z v_n)/m, solved for v_n.
  const double vn = (s.v[last] + half * s.force[last] / m) / (1 + half * Z / m);
  s.force[last] -= Z * vn;
  s.dissipated_J += Z * vn * vn * 0.5 * (s.dt_prev + s.dt);
}

long advance(const BarModel& bar, BarState& s) {
  const double dt = s.dt;
  const double kick = 0.5 * (s.dt_prev + dt);  // ½(Δt_{n−1} + Δt_n); ½Δt_0 at n = 0
  const long count = s.quiet() ? 0 : s.hi - s.lo + 1;
  if (count > 0)
    kick_drift(s.w.data(), s.v.data(), s.force.data(), bar.inverse_mass.data(), kick, dt, s.lo,
               s.hi);
  s.dt_prev = dt;
  ++s.step;
  return count;
}

double end_free_force_at(const BarModel& bar, const BarState& s, int end, double tau_n, double tau,
                         double end_w, bool law_on_path) {
  const int last = bar.nodes - 1;
  const int element = end == 0 ? 0 : last - 1;
  if (bar.law && !law_on_path)
    return end == 0 ? s.axial_force_N[element] : -s.axial_force_N[element];
  const int other = end == 0 ? 1 : last - 1;
  const double back = tau_n - tau;
  const double w_end = std::isnan(end_w) ? s.w[end] - back * s.v[end] : end_w;
  const double w_other = s.w[other] - back * s.v[other];
  if (!bar.law) return bar.stiffness_N_m * (w_other - w_end);
  // The axial force of the last assembly (at the instant before τ_n, current area) plus the
  // instantaneous response to the end element's stretch since: its strain then is in strain_next.
  const double h = bar.element_length_m, strain = s.strain_next[element];
  const double then = bar.finite_strain ? h * std::expm1(strain) : h * strain;
  const double now = end == 0 ? w_other - w_end : w_end - w_other;
  const double axial = s.axial_force_N[element] + bar.stiffness_N_m * (now - then);
  return end == 0 ? axial : -axial;
}

double node_velocity_now(const BarModel& bar, const BarState& s, int i) {
  const double half = 0.5 * s.dt_prev * s.force[i] * bar.inverse_mass[i];
  const bool active = !s.quiet() && i >= s.lo && i <= s.hi;
  return bar.initial_velocity_m_s + (active ? s.v[i] + half : 0.0);
}

namespace {
// Kinetic energy of nodes [lo, hi] at t_n and their mass. The central difference conserves
// ½ v_{n−1/2}·M v_{n+1/2} + U(u_n) (its discrete energy), not ½ v_n·M v_n + U: the two differ by
// (½Δt a_n)² per unit mass, one element's strain energy at a sharp front at C ≈ 1 and all of it
// for Nyquist ringing. Where the step changes (step_control.hpp), v_{n±1/2} = v_n ± ½Δt_{n−1/n}
// a_n. The sums run in four lanes (node lo + 4j + l into lane l, a vector of four doubles; the
// lanes added at the end): a different order of the same terms, so the sum moves by round-off.
constexpr int kEnergyLanes = 4;
// Internal, inlined functions on a 32-byte vector: GCC's note that their ABI differs with and
// without AVX does not concern them (off to the end of this file: GCC emits it there).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
#endif
typedef double Lanes __attribute__((vector_size(kEnergyLanes * sizeof(double))));
inline Lanes load_lanes(const double* p) {
  Lanes x;
  std::memcpy(&x, p, sizeof x);
  return x;
}
template <typename T>
inline T kinetic_term(T v, T f, T inv_m, T m, double V, double half, double dt, bool same_step) {
  const T vn = V + v + half * f * inv_m;
  const T a = f * inv_m;
  const T dv = 0.5 * dt * f * inv_m;
  return same_step ? 0.5 * m * (vn * vn - dv * dv) : 0.5 * m * (vn - half * a) * (vn + dv);
}
SHPB_TARGET_CLONES void kinetic_energy(const double* v, const double* f, const double* inv_m,
                                       const double* m, double V, double half, double dt,
                                       bool same_step, int lo, int hi, double* kinetic,
                                       double* mass) {
  Lanes k = {}, ms = {};
  int i = lo;
  for (; i + kEnergyLanes - 1 <= hi; i += kEnergyLanes) {
    const Lanes mi = load_lanes(m + i);
    k += kinetic_term(load_lanes(v + i), load_lanes(f + i), load_lanes(inv_m + i), mi, V, half, dt,
                      same_step);
    ms += mi;
  }
  for (int l = 0; i <= hi; ++i, ++l) {
    k[l] += kinetic_term(v[i], f[i], inv_m[i], m[i], V, half, dt, same_step);
    ms[l] += m[i];
  }
  *kinetic += (k[0] + k[1]) + (k[2] + k[3]);
  *mass += (ms[0] + ms[1]) + (ms[2] + ms[3]);
}
// Strain energy Σ ½ k (w_{e+1} − w_e)² of an elastic bar's elements [e0, e1], in lanes likewise.
SHPB_TARGET_CLONES double elastic_strain_energy(const double* w, double k, int e0, int e1) {
  Lanes sum = {};
  int e = e0;
  for (; e + kEnergyLanes - 1 <= e1; e += kEnergyLanes) {
    const Lanes d = load_lanes(w + e + 1) - load_lanes(w + e);
    sum += 0.5 * k * d * d;
  }
  for (int l = 0; e <= e1; ++e, ++l) {
    const double d = w[e + 1] - w[e];
    sum[l] += 0.5 * k * d * d;
  }
  return (sum[0] + sum[1]) + (sum[2] + sum[3]);
}
}  // namespace

double node_kinetic_energy(const BarModel& bar, const BarState& s, int i) {
  if (s.quiet() || i < s.lo || i > s.hi)
    return 0.5 * bar.mass_kg[i] * bar.initial_velocity_m_s * bar.initial_velocity_m_s;
  const bool same_step = s.step == 0 || s.dt_prev == s.dt;
  return kinetic_term(s.v[i], s.force[i], bar.inverse_mass[i], bar.mass_kg[i],
                      bar.initial_velocity_m_s, 0.5 * s.dt_prev, s.dt, same_step);
}

BarEnergy bar_energy(const BarModel& bar, const BarState& s) {
  BarEnergy e;
  const double V = bar.initial_velocity_m_s;
  double moving_mass = bar.total_mass_kg();
  if (bar.segment_elements[0] || bar.segment_elements[1]) {  // the owned nodes' (end_segment.hpp)
    moving_mass = 0;
    for (int i = bar.first_owned_node(); i <= bar.last_owned_node(); ++i)
      moving_mass += bar.mass_kg[i];
  }
  if (!s.quiet()) {
    const bool same_step = s.step == 0 || s.dt_prev == s.dt;
    double moving = 0;
    kinetic_energy(s.v.data(), s.force.data(), bar.inverse_mass.data(), bar.mass_kg.data(), V,
                   0.5 * s.dt_prev, s.dt, same_step, s.lo, s.hi, &e.kinetic_J, &moving);
    moving_mass -= moving;
    const int e0 = std::max(s.lo - 1, bar.first_owned_node());
    const int e1 = std::min(s.hi, bar.last_owned_node() - 1);
    if (bar.law) {
      const double volume = bar.area_m2 * bar.element_length_m;
      // A segment's stored energy is recorded with its tie, on its clock (end_segment.hpp).
      for (int k = 0; k < bar.elements(); ++k) {
        if (k >= bar.first_owned_node() && k < bar.last_owned_node())
          e.strain_J += volume * bar.law->stored_energy_J_m3(s.points[k]);
        e.dissipated_J += volume * s.points[k].dissipated_J_m3;
      }
      if (bar.radial_inertia_density_kg_m3 > 0) {
        // Radial kinetic energy of volume-conserving flow, ρ V a² ε̇²/16 (bar.hpp).
        const double length0 = bar.element_length_m * bar.elements();
        const double stretch = bar.finite_strain ? 1 + (s.w.back() - s.w.front()) / length0 : 1.0;
        const double a2 = 0.25 * bar.diameter_m * bar.diameter_m / stretch;
        const double rate = s.inertia_flowing ? s.inertia_rate_1_s : 0.0;
        e.kinetic_J +=
            bar.radial_inertia_density_kg_m3 * volume * bar.elements() * a2 * rate * rate / 16;
      }
    } else {
      e.strain_J += elastic_strain_energy(s.w.data(), bar.stiffness_N_m, e0, e1);
    }
  }
  e.kinetic_J += 0.5 * moving_mass * V * V;  // nodes outside the range move rigidly
  return e;
}

}  // namespace shpb
