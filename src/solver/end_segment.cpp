#include "solver/end_segment.hpp"

#include <algorithm>
#include <cmath>

#include "solver/bar_integrator.hpp"
#include "solver/scheduler.hpp"

namespace shpb {

namespace {
// The segment's nodes other than the joint, [first, last], its end node at the tie and its first
// element (the elements are [element, element + seg.elements)).
struct Span {
  int joint, first, last, end, element;
};
Span span(const Chain& chain, const EndSegment& seg) {
  const int n = chain.bars[seg.bar].nodes, k = seg.elements;
  if (seg.end == 1) return {n - 1 - k, n - k, n - 1, n - 1, n - 1 - k};
  return {k, 0, k - 1, 0, 0};
}
// The bar's side of the tie: its right end is the interface's left side.
int interface_side(const EndSegment& seg) { return seg.end == 1 ? 0 : 1; }
}  // namespace

void plan_end_segments(Chain& chain, const Scene& scene, bool law_specimen) {
  chain.interface_segment.assign(chain.interfaces.size(), -1);
  if (chain.global_stepping) return;
  for (std::size_t k = 0; k < chain.interfaces.size(); ++k) {
    const InterfaceModel& im = chain.interfaces[k];
    const bool rigid = im.method == ContactMethod::kBonded ||
                       (im.method == ContactMethod::kLocalizedBipenalty && !im.finite_links);
    const double dt_l = chain.bars[k].time_step_s, dt_r = chain.bars[k + 1].time_step_s;
    if (std::abs(dt_l - dt_r) <= kSameInstant * std::min(dt_l, dt_r)) continue;
    const std::size_t slow = dt_l > dt_r ? k : k + 1, fast = slow == k ? k + 1 : k;
    // Finite links (docs/methods.md §3.5; their half-frames stepping together on the fast clock
    // are its global-step scheme) take segments where the fast bar is squeezed between two others,
    // a pulse shaper or a specimen: measured, the shaper's ties chattered without them (46/42
    // closings; 422/385 and 9 % of the energy created at C 0.9995), while a steel striker of 2.19
    // times the bar's step rang more with them (plateau std 0.10 -> 0.84 %).
    const bool squeezed = squeezed_bar(fast, chain.bars.size());
    const bool finite = im.method == ContactMethod::kLocalizedBipenalty && im.finite_links;
    if (!rigid && !(finite && squeezed)) continue;
    const int end = slow == k ? 1 : 0;
    BarModel& s = chain.bars[slow];
    const BarModel& f = chain.bars[fast];
    // The fast bar may be an elastic specimen (docs/methods.md §3.7). A specimen with a material
    // law keeps the coupling of §3.4 through its loading unless asked (`law_specimen`): with
    // segments, on its adaptive step too, it keeps its energy, but the gauges' response to a law
    // parameter gets kinks (the fit's smooth response, §9: its adaptive instants slide with the
    // law past the bar's, and the joint's result changes slope at each crossing) and the loading
    // moves by up to 5 % of the peak, while that coupling holds the energy of every shipped
    // experiment. It takes them once the face is unloaded (start_release_segments).
    const bool specimen_face = scene.specimen && *scene.specimen == fast && f.law;
    // A slow bar with a law of its own (polymer bars) steps its segment's law on the fast clock;
    // not a specimen (its faces' coupling is §3.7's), nor a bar with friction or radial inertia
    // (laws of the whole bar's shape).
    const bool slow_law_ok =
        !s.law || (!(scene.specimen && *scene.specimen == slow) &&
                   s.friction_factor_per_aspect == 0 && s.radial_inertia_density_kg_m3 == 0);
    if (!slow_law_ok || s.adaptive_step || (end == 1 && s.dashpot_right)) continue;
    if (s.elements() < 2 * kSegmentElements + 2 + s.segment_elements[1 - end]) continue;
    // After a law specimen face's release, any two clocks there pin the faces (§3.7), light and
    // stiff or not (the PMMA mini-Kolsky's faces are at 1.14 k1/m1).
    if (specimen_face && !law_specimen) {
      chain.release_segments.push_back({slow, end, fast, k, kSegmentElements});
      continue;
    }
    // A light, stiff fast end: the tied pair's (k1 + k2)/(m1 + m2) well above the slow end's own
    // k1/m1 (docs/methods.md §3.6).
    const double k1 = s.stiffness_N_m, m1 = s.mass_kg[end == 1 ? s.nodes - 1 : 0];
    const double k2 = f.stiffness_N_m, m2 = f.mass_kg[end == 1 ? 0 : f.nodes - 1];
    if (!((k1 + k2) / (m1 + m2) > kLightStiffEnd * k1 / m1)) continue;
    s.segment_elements[end] = kSegmentElements;
    chain.interface_segment[k] = static_cast<int>(chain.segments.size());
    chain.segments.push_back({slow, end, fast, k, kSegmentElements});
  }
}

namespace {
// A face open after its loading: released, and the slow bar's end element (its pending state)
// carrying less than kUnloadedShare of the face's largest force. A face that opens briefly within
// the loading (a thin wafer's ringing at asynchronous steps) has the loading pulse in that
// element; after the unloading it is all but free.
bool unloaded(const Chain& chain, const EndSegment& seg) {
  const InterfaceState& is = chain.interface_states[seg.interface];
  if (is.active || is.releases == 0) return false;
  const BarModel& b = chain.bars[seg.bar];
  const BarState& s = chain.states[seg.bar];
  const int e = seg.end == 1 ? b.nodes - 2 : 0;
  const double force = b.law ? s.axial_force_N[e] : b.stiffness_N_m * (s.w[e + 1] - s.w[e]);
  return std::abs(force) < kUnloadedShare * is.peak_force_N;
}
}  // namespace

void start_release_segments(Chain& chain, const std::vector<char>& stepping, double tau) {
  auto& pending = chain.release_segments;
  for (auto it = pending.begin(); it != pending.end();) {
    EndSegment seg = *it;
    const Span sp = span(chain, seg);
    if (!stepping[seg.clock_bar] || !unloaded(chain, seg)) {
      ++it;
      continue;
    }
    BarModel& b = chain.bars[seg.bar];
    BarState& s = chain.states[seg.bar];
    // The segment's nodes go from the bar's pending instant back to τ on their straight paths
    // (the central difference's own between two instants; nothing if the bar steps at τ too).
    // Their last kick, at the bar's last instant, took its forces over half the bar's step after
    // it; the clock's kick at τ takes τ's over half the clock's step before: the overlap (< 0: a
    // gap) is taken back at those forces, and the segment element's share of the joint's force
    // with it (its pending position moved as by rule 6). Without it each node kept up to half a
    // bar step's impulse twice or not at all (measured on 25 m/s copper specimens whose faces
    // opened with 1-10 % of their peak force left in the bar's end: 0.16-0.30 % of the energy
    // created, 0.07-0.08 % with it).
    const double ahead = chain.bar_tau(seg.bar) - tau, dt = s.dt_prev;
    const double overlap = ahead - 0.5 * dt + 0.5 * chain.states[seg.clock_bar].dt_prev;
    const auto kicked = [&](int i) { return !s.quiet() && i >= s.lo && i <= s.hi; };
    const int ej = seg.end == 1 ? sp.joint : sp.joint - 1;  // the segment element at the joint
    const double tension =
        b.law ? s.axial_force_N[ej]
              : b.stiffness_N_m * ((s.w[ej + 1] - dt * s.v[ej + 1]) - (s.w[ej] - dt * s.v[ej]));
    if (kicked(sp.joint)) {
      const double dv = -overlap * (seg.end == 1 ? tension : -tension) * b.inverse_mass[sp.joint];
      s.v[sp.joint] += dv;
      s.w[sp.joint] += ahead * dv;
    }
    for (int i = sp.first; i <= sp.last; ++i) {
      s.w[i] -= ahead * s.v[i];
      if (kicked(i)) s.v[i] -= overlap * s.force[i] * b.inverse_mass[i];
    }
    b.segment_elements[seg.end] = seg.elements;
    if (!s.quiet()) {  // the bar's own range of moving nodes ends at its joints
      s.lo = std::max(s.lo, b.first_owned_node());
      s.hi = std::min(s.hi, b.last_owned_node());
    }
    seg.nodes_tau = seg.from_tau = tau;
    seg.bar_steps_before = s.step;
    seg.clock_steps_before = chain.states[seg.clock_bar].step;
    chain.interface_segment[seg.interface] = static_cast<int>(chain.segments.size());
    chain.segments.push_back(seg);
    it = pending.erase(it);
  }
}

void prepare_segment(Chain& chain, EndSegment& seg, double tau, bool bar_stepping) {
  const BarModel& b = chain.bars[seg.bar];
  BarState& s = chain.states[seg.bar];
  const Span sp = span(chain, seg);
  // Rule 4: a tied end is where the frame is (both sides of the tie step now).
  const double target =
      tied_end_position(chain.interfaces[seg.interface], chain.interface_states[seg.interface],
                        interface_side(seg), tau);
  if (!std::isnan(target)) s.w[sp.end] = target - b.initial_velocity_m_s * tau;
  // The joint on its straight path at τ (its state is at the bar's pending instant).
  seg.joint_w =
      bar_stepping ? s.w[sp.joint] : s.w[sp.joint] - (chain.bar_tau(seg.bar) - tau) * s.v[sp.joint];
  const auto w = [&](int i) { return i == sp.joint ? seg.joint_w : s.w[i]; };
  for (int i = sp.first; i <= sp.last; ++i) s.force[i] = 0;
  seg.joint_force_N = 0;
  // Element forces, and the segment's strain energy at τ recorded with the tie (finish_segment).
  InterfaceState& is = chain.interface_states[seg.interface];
  is.segment_strain_J = 0;
  const int e_end = sp.element + seg.elements;
  if (b.law) {
    // The law advances its elements over the clock's step that led to τ, the joint on its path.
    const BarState& clock = chain.states[seg.clock_bar];
    const double pending = s.w[sp.joint];
    s.w[sp.joint] = seg.joint_w;
    law_element_forces(b, s, sp.element, e_end - 1, clock.step > 0 ? clock.dt_prev : clock.dt);
    s.w[sp.joint] = pending;
  }
  const double volume = b.area_m2 * b.element_length_m;
  for (int e = sp.element; e < e_end; ++e) {
    const double stretch = w(e + 1) - w(e);
    const double tension = b.law ? s.axial_force_N[e] : b.stiffness_N_m * stretch;
    (e == sp.joint ? seg.joint_force_N : s.force[e]) += tension;
    (e + 1 == sp.joint ? seg.joint_force_N : s.force[e + 1]) -= tension;
    is.segment_strain_J += b.law ? volume * b.law->stored_energy_J_m3(s.points[e])
                                 : 0.5 * b.stiffness_N_m * stretch * stretch;
  }
}

EndState segment_end_state(const Chain& chain, const EndSegment& seg, double tau) {
  const BarModel& b = chain.bars[seg.bar];
  const BarState& s = chain.states[seg.bar];
  const BarState& clock = chain.states[seg.clock_bar];
  const int end = span(chain, seg).end;
  EndState e;
  e.mass = b.mass_kg[end];
  e.stepping = true;
  e.u = s.w[end] + b.initial_velocity_m_s * tau;
  e.v = node_velocity(b, s, end);
  e.free_force = s.force[end];
  e.kick_s = 0.5 * (clock.dt_prev + clock.dt);
  e.step_s = clock.dt;
  e.next_tau = tau + clock.dt;
  return e;
}

void apply_segment_end(Chain& chain, const EndSegment& seg, double dv, double force) {
  BarState& s = chain.states[seg.bar];
  const int end = span(chain, seg).end;
  s.v[end] += dv;
  s.force[end] += force;
}

long finish_segment(Chain& chain, EndSegment& seg, double tau, bool bar_stepping) {
  const BarModel& b = chain.bars[seg.bar];
  BarState& s = chain.states[seg.bar];
  const BarState& clock = chain.states[seg.clock_bar];
  const Span sp = span(chain, seg);
  const double kick = 0.5 * (clock.dt_prev + clock.dt), dt = clock.dt;
  const double V = b.initial_velocity_m_s;
  // Kinetic energy at τ (the central difference's own, ½ m v_{n−1/2} v_{n+1/2};
  // bar_integrator.hpp); the strain energy was taken with the forces (prepare_segment).
  InterfaceState& is = chain.interface_states[seg.interface];
  is.segment_kinetic_J = 0;
  for (int i = sp.first; i <= sp.last; ++i) {
    const double before = s.v[i] + V, after = before + kick * s.force[i] * b.inverse_mass[i];
    is.segment_kinetic_J += 0.5 * b.mass_kg[i] * before * after;
  }
  for (int i = sp.first; i <= sp.last; ++i) {  // kick and drift on the clock bar's step
    s.v[i] += kick * s.force[i] * b.inverse_mass[i];
    s.w[i] += dt * s.v[i];
  }
  seg.nodes_tau = tau + dt;
  // The joint's impulse κ N: a force over the bar's own kick if it steps now, else a velocity
  // jump moving its pending position along its new path (scheduler rule 6).
  if (seg.joint_force_N != 0) {
    activate_node(b, s, sp.joint);
    if (bar_stepping) {
      s.force[sp.joint] += seg.joint_force_N * kick / (0.5 * (s.dt_prev + s.dt));
    } else {
      const double dv = kick * seg.joint_force_N * b.inverse_mass[sp.joint];
      s.v[sp.joint] += dv;
      s.w[sp.joint] += (chain.bar_tau(seg.bar) - tau) * dv;
    }
  }
  return sp.last - sp.first + 1;
}

namespace {
// Node `node`'s displacement at τ: its own, or a segment node's at τ on its straight path.
double node_w_at(const Chain& chain, std::size_t bar, int node, double tau) {
  const BarModel& b = chain.bars[bar];
  const BarState& s = chain.states[bar];
  if (node >= b.first_owned_node() && node <= b.last_owned_node()) return s.w[node];
  const int end = node < b.first_owned_node() ? 0 : 1;
  for (const EndSegment& seg : chain.segments)
    if (seg.bar == bar && seg.end == end) return s.w[node] - (seg.nodes_tau - tau) * s.v[node];
  return s.w[node];
}
}  // namespace

double segmented_element_strain(const Chain& chain, std::size_t bar, int element, double tau) {
  const BarModel& b = chain.bars[bar];
  const double inv_h = 1.0 / b.element_length_m;  // as the recorder's unsegmented bars
  const auto strain = [&](int e) {
    return (node_w_at(chain, bar, e + 1, tau) - node_w_at(chain, bar, e, tau)) * inv_h;
  };
  const bool joint = (b.segment_elements[0] > 0 && element == b.first_owned_node() - 1) ||
                     (b.segment_elements[1] > 0 && element == b.last_owned_node());
  return joint ? 0.5 * (strain(element - 1) + strain(element + 1)) : strain(element);
}

}  // namespace shpb
