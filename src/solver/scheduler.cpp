#include "solver/scheduler.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include "core/error.hpp"
#include "solver/bar_integrator.hpp"
#include "solver/end_segment.hpp"
#include "solver/step_control.hpp"

namespace shpb {

namespace {

// The Courant number an unstable asynchronous run is advised to try (the default of
// docs/methods.md §1), unless it ran at or below it.
constexpr double kAdvisedCourant = 0.995;

// The end of bar i that touches interface k: its last node (left side) or node 0 (right side).
// `neighbour_dt`: the other side's step; an ahead material-law bar with the longer step carries
// its end force along its path (rule 4). Not given (a stepping end): never the slow side.
EndState end_state(const Chain& chain, std::size_t bar, int node, double tau, bool stepping,
                   double tied_u, double neighbour_dt = std::numeric_limits<double>::infinity()) {
  const BarModel& b = chain.bars[bar];
  const BarState& s = chain.states[bar];
  const double tau_n = chain.bar_tau(bar);
  EndState e;
  e.mass = b.mass_kg[node];
  e.stepping = stepping;
  if (stepping) {
    e.u = s.w[node] + b.initial_velocity_m_s * tau;
    e.free_force = s.quiet() || node < s.lo || node > s.hi ? 0.0 : s.force[node];
  } else {
    e.u = node_displacement_at(b, s, node, tau_n, tau);
    // A tied end is at the frame (rule 4); otherwise on its own linear path.
    const double w_end = std::isnan(tied_u) ? std::numeric_limits<double>::quiet_NaN()
                                            : tied_u - b.initial_velocity_m_s * tau;
    const bool slow = s.dt > (1 + kSameInstant) * neighbour_dt;
    e.free_force = end_free_force_at(b, s, node, tau_n, tau, w_end, slow);
  }
  e.v = node_velocity(b, s, node);
  e.kick_s = 0.5 * (s.dt_prev + s.dt);  // ½(Δt_{n−1} + Δt_n), ½Δt_0 at n = 0
  e.step_s = s.dt;
  return e;
}

void apply_end(Chain& chain, std::size_t bar, int node, double tau, bool stepping, double dv,
               double force) {
  if (dv == 0 && force == 0) return;
  const BarModel& b = chain.bars[bar];
  BarState& s = chain.states[bar];
  activate_node(b, s, node);
  if (dv != 0) {
    s.v[node] += dv;
    if (!stepping) s.w[node] += (chain.bar_tau(bar) - tau) * dv;  // rule 6
  }
  if (stepping) s.force[node] += force;
}

std::string describe_failure(const Chain& chain, double t, const char* energy, double ratio) {
  std::ostringstream out;
  out << "unstable: the " << energy << " reached " << ratio
      << " times the initial energy at t = " << t << " s";
  std::size_t worst = chain.interfaces.size();
  double largest = 0;
  for (std::size_t k = 0; k < chain.interfaces.size(); ++k) {
    const double f = std::abs(chain.interface_states[k].force_N);
    if (!(f <= largest)) {
      largest = f;
      worst = k;
    }
  }
  if (worst < chain.interfaces.size())
    out << "; largest contact force " << largest << " N at interface "
        << chain.interfaces[worst].name << " (" << to_string(chain.interfaces[worst].method) << ")";
  // Ties between bars on different steps near C = 1 are where the localized coupling can feed a
  // mode (docs/methods.md §3.6–3.7); a plain penalty link's stiffness is its own limit (§2).
  // The advice names a Courant number below the run's own (one at 0.995 already was told 0.995).
  double courant = 0;
  for (std::size_t i = 0; i < chain.bars.size(); ++i)
    courant = std::max(courant, chain.bars[i].courant_at(chain.states[i].dt));
  // At C = 1 a free bar's highest mode (ω = 2c/h) meets the central difference's double root:
  // its amplitude grows linearly with no change of the discrete energy (§1.1), whatever the
  // coupling.
  if (courant >= 1 - kSameInstant)
    out << "; a bar steps at C = 1, where its highest mode grows linearly (docs/methods.md §1.1)";
  if (!chain.global_stepping) {
    out << "; compare with --stepping global";
    if (courant > kAdvisedCourant)
      out << " or --courant " << kAdvisedCourant;
    else
      out << " or a --courant below " << std::setprecision(3) << courant;
  } else if (courant > kAdvisedCourant) {
    out << "; compare with --courant " << kAdvisedCourant;
  }
  return out.str();
}

// What every solve of interface k at τ leaves in the chain: its closing losses, what follows its
// unloading, its largest force and the largest interpenetration, also in elements of the smaller
// neighbouring one.
void book_solve(Chain& chain, std::size_t k, const ContactResult& res, double tau) {
  InterfaceState& is = chain.interface_states[k];
  const double gap = is.gap_m;
  book_unloading(chain.interfaces[k], is, tau);
  is.peak_force_N = std::max(is.peak_force_N, is.force_N);
  chain.contact_dissipated_J[k] += res.dissipated_J;
  chain.max_penetration_m = std::max(chain.max_penetration_m, -gap);
  chain.max_penetration_elements =
      std::max(chain.max_penetration_elements,
               -gap / std::min(chain.bars[k].element_length_m, chain.bars[k + 1].element_length_m));
}

// One instant τ* for the stepping bars, all in [first, last] (rules 3–6); the interfaces
// touching them are solved in chain order.
void take_instant(Chain& chain, ChainRecorders& recorders, const std::vector<char>& stepping,
                  std::size_t first, std::size_t last, double tau) {
  const std::size_t ni = chain.interfaces.size();
  const std::size_t k0 = first > 0 ? first - 1 : 0, k1 = std::min(last + 1, ni);

  // Rule 11: a law specimen's face takes its end segment once unloaded.
  if (!chain.release_segments.empty()) start_release_segments(chain, stepping, tau);

  // Rule 4: a stepping end tied to a frame is put where the frame is.
  for (std::size_t k = k0; k < k1; ++k)
    for (int side = 0; side < 2; ++side) {
      const std::size_t bar = k + side;
      if (!stepping[bar]) continue;
      const EndSegment* seg = chain.segment_at(k);
      if (seg && seg->bar == bar) continue;  // on its clock bar's instants (end_segment.hpp)
      const double target =
          tied_end_position(chain.interfaces[k], chain.interface_states[k], side, tau);
      if (std::isnan(target)) continue;
      const int node = side == 0 ? chain.bars[bar].nodes - 1 : 0;
      BarState& s = chain.states[bar];
      const double w = target - chain.bars[bar].initial_velocity_m_s * tau;
      if (w != s.w[node]) {
        s.w[node] = w;
        activate_node(chain.bars[bar], s, node);
      }
    }

  // Rule 3: internal forces of the stepping bars.
  for (std::size_t i = first; i <= last; ++i)
    if (stepping[i]) assemble_internal_forces(chain.bars[i], chain.states[i]);
  // Rule 1: an adaptive bar may start a new phase here (step_control.hpp).
  replan_steps(chain, stepping, first, last);

  // Rules 4–6: interfaces touching a stepping bar, solved once at τ*.
  for (std::size_t k = k0; k < k1; ++k) {
    const std::size_t l = k, r = k + 1;
    if (!stepping[l] && !stepping[r]) continue;
    const int l_node = chain.bars[l].nodes - 1;
    const InterfaceModel& im = chain.interfaces[k];
    InterfaceState& is = chain.interface_states[k];
    if (chain.segment_at(k)) {
      // Rule 11: a tie with an end segment is solved at its clock bar's instants only, both ends
      // stepping there together (end_segment.hpp).
      EndSegment& seg = chain.segments[chain.interface_segment[k]];
      const std::size_t f = seg.clock_bar;
      if (!stepping[f]) continue;
      const bool bar_stepping = stepping[seg.bar];
      prepare_segment(chain, seg, tau, bar_stepping);
      const double nan = std::numeric_limits<double>::quiet_NaN();
      const int f_node = f == l ? l_node : 0;
      const EndState seg_end = segment_end_state(chain, seg, tau);
      const EndState f_end = end_state(chain, f, f_node, tau, true, nan);
      const double next = tau + chain.states[f].dt;
      const bool seg_left = seg.bar == l;
      EndState left = seg_left ? seg_end : f_end, right = seg_left ? f_end : seg_end;
      left.next_tau = right.next_tau = next;
      const ContactResult res = solve_contact(im, is, left, right, tau, next);
      apply_segment_end(chain, seg, seg_left ? res.dv_left : res.dv_right,
                        seg_left ? res.force_left_N : res.force_right_N);
      apply_end(chain, f, f_node, tau, true, seg_left ? res.dv_right : res.dv_left,
                seg_left ? res.force_right_N : res.force_left_N);
      book_solve(chain, k, res, tau);
      chain.states[seg.bar].node_updates += finish_segment(chain, seg, tau, bar_stepping);
      recorders.on_interface_solve(chain, k, tau, next);
      continue;
    }
    // A stepping end is already at the frame (rule 4); an ahead one is put there for its load.
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EndState left =
        end_state(chain, l, l_node, tau, stepping[l],
                  stepping[l] ? nan : tied_end_position(im, is, 0, tau), chain.states[r].dt);
    EndState right =
        end_state(chain, r, 0, tau, stepping[r],
                  stepping[r] ? nan : tied_end_position(im, is, 1, tau), chain.states[l].dt);
    const double next_l = stepping[l] ? tau + chain.states[l].dt : chain.bar_tau(l);
    const double next_r = stepping[r] ? tau + chain.states[r].dt : chain.bar_tau(r);
    const double next = std::min(next_l, next_r);
    left.next_tau = next_l;
    right.next_tau = next_r;
    const ContactResult res = solve_contact(im, is, left, right, tau, next);
    apply_end(chain, l, l_node, tau, stepping[l], res.dv_left, res.force_left_N);
    apply_end(chain, r, 0, tau, stepping[r], res.dv_right, res.force_right_N);
    book_solve(chain, k, res, tau);
    recorders.on_interface_solve(chain, k, tau, next);
  }

  // Rule 3: record and advance.
  for (std::size_t i = first; i <= last; ++i) {
    if (!stepping[i]) continue;
    apply_dashpot(chain.bars[i], chain.states[i]);
    recorders.on_bar_instant(chain, i, tau, tau + chain.states[i].dt);
    chain.states[i].node_updates += advance(chain.bars[i], chain.states[i]);
  }
}

// Rule 10: an interface that a solve at rest leaves as it is: a rigid link (the default
// localized bipenalty, or bonded) either open with a gap (nothing closes it) or tied with its
// frame at rest where both ends are.
bool interface_at_rest(const InterfaceModel& m, const InterfaceState& s) {
  const bool rigid = m.method == ContactMethod::kBonded ||
                     (m.method == ContactMethod::kLocalizedBipenalty && !m.finite_links);
  if (!rigid) return false;
  if (!s.active) return s.gap_m > 0;
  return s.frame_v == 0 && tied_end_position(m, s, 0, s.frame_tau) == 0 &&
         tied_end_position(m, s, 1, s.frame_tau) == 0;
}

// Rule 10: bar j is quiet and nothing around it moves, so its instants until a neighbour steps
// change nothing. The neighbours do not step meanwhile (they are ahead), so this holds for all of
// them or none.
bool at_rest(const Chain& chain, std::size_t j) {
  const std::size_t nb = chain.bars.size();
  if (!chain.states[j].quiet() || !chain.segments.empty()) return false;  // segments: rule 11
  for (std::size_t i = j > 0 ? j - 1 : 0; i < std::min(j + 2, nb); ++i)
    if (chain.bars[i].initial_velocity_m_s != 0) return false;
  if (j > 0) {  // the left neighbour's last two nodes (its end and end element) at rest
    const BarState& l = chain.states[j - 1];
    if (!l.quiet() && l.hi >= chain.bars[j - 1].nodes - 2) return false;
    if (!interface_at_rest(chain.interfaces[j - 1], chain.interface_states[j - 1])) return false;
  }
  if (j + 1 < nb) {  // the right neighbour's first two nodes
    const BarState& r = chain.states[j + 1];
    if (!r.quiet() && r.lo <= 1) return false;
    if (!interface_at_rest(chain.interfaces[j], chain.interface_states[j])) return false;
  }
  return true;
}

}  // namespace

ScheduleOutcome run_schedule(Chain& chain, ChainRecorders& recorders,
                             const std::function<void(double)>& progress,
                             const std::function<bool()>& cancel, bool subcycle,
                             bool subcycle_at_rest) {
  ScheduleOutcome outcome;
  const std::size_t nb = chain.bars.size();
  std::vector<char> stepping(nb, 0);
  double energy0 = std::numeric_limits<double>::quiet_NaN();
  long energy_checked = 0;
  long instants = 0;
  int progress_done = -1;
  double next_progress_tau = 0;
  double dt_min = std::numeric_limits<double>::infinity();
  for (const BarModel& b : chain.bars) dt_min = std::min(dt_min, b.time_step_s);
  const double same = kSameInstant * dt_min;
  auto unfinished = [&](std::size_t i) { return chain.states[i].step <= chain.final_step[i]; };

  // Rules 7 and 9 after each instant; false: the run is unstable and `outcome` says so.
  auto after_instant = [&](double tau) {
    // Rule 7: energy check on completed grid points (none can complete before τ* passes the
    // next one).
    const long complete = tau >= recorders.energy_grid_tau(energy_checked)
                              ? recorders.energy_complete()
                              : energy_checked;
    for (; energy_checked < complete; ++energy_checked) {
      const double e = recorders.energy_total(energy_checked);
      if (energy_checked == 0) energy0 = e;
      const double t = recorders.energy_grid_tau(energy_checked);
      const bool finite = std::isfinite(e);
      if (finite && energy0 > 0)
        outcome.energy_error = std::max(outcome.energy_error, std::abs(e - energy0) / energy0);
      // The strain energy alone too: a Nyquist mode's negative kinetic energy cancels it in the
      // total (scheduler.hpp, kStrainGrowthLimit).
      const double strain = recorders.energy_strain(energy_checked);
      const bool total_grew = !finite || (energy0 > 0 && e > kEnergyGrowthLimit * energy0);
      if (total_grew || (energy0 > 0 && strain > kStrainGrowthLimit * energy0)) {
        outcome.stable = false;
        outcome.failure = total_grew
                              ? describe_failure(chain, t, "total energy", finite ? e / energy0 : e)
                              : describe_failure(chain, t, "strain energy", strain / energy0);
        outcome.checked_until_s =
            energy_checked == 0 ? 0.0 : recorders.energy_grid_tau(energy_checked - 1);
        return false;
      }
    }
    ++instants;
    if (cancel && instants % kCancelPollInstants == 0 && cancel()) throw Interrupted();
    if (progress && tau >= next_progress_tau) {
      const int pct = static_cast<int>(100.0 * std::min(1.0, tau / chain.end_tau_s));
      if (pct != progress_done) {
        progress_done = pct;
        progress(pct / 100.0);
      }
      next_progress_tau = (pct + 1) * 0.01 * chain.end_tau_s;
    }
    return true;
  };

  while (true) {
    // Rule 2: the earliest pending instant among unfinished bars.
    double tau = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < nb; ++i)
      if (unfinished(i)) tau = std::min(tau, chain.bar_tau(i));
    if (!std::isfinite(tau)) break;
    std::size_t first = nb, last = 0;
    for (std::size_t i = 0; i < nb; ++i) {
      stepping[i] = unfinished(i) && chain.bar_tau(i) <= tau + same;
      if (stepping[i]) {
        first = std::min(first, i);
        last = i;
      }
    }
    take_instant(chain, recorders, stepping, first, last, tau);
    if (!after_instant(tau)) return outcome;
    if (!subcycle || first != last) continue;

    // Rule 2 for a lone fast bar j: while its next instant comes before every other bar's
    // pending one (by more than kSameInstant), it is τ* again and steps alone, so its instants
    // run in a tight loop without the search.
    const std::size_t j = first;
    double others = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < nb; ++i)
      if (i != j && unfinished(i)) others = std::min(others, chain.bar_tau(i));
    const bool rest = subcycle_at_rest && at_rest(chain, j);
    while (unfinished(j)) {
      double tau_j = chain.bar_tau(j);
      if (!(tau_j + same < others)) break;
      if (rest) {
        // Rule 10: straight to the last instant of the loop; it records the rest values that
        // the skipped ones would have (linear interpolation between equal values).
        BarState& s = chain.states[j];
        const long first_step = s.step;
        while (s.step < chain.final_step[j]) {
          ++s.step;
          if (!(chain.bar_tau(j) + same < others)) {
            --s.step;
            break;
          }
        }
        if (s.step != first_step) s.dt_prev = s.dt;
        tau_j = chain.bar_tau(j);
      }
      take_instant(chain, recorders, stepping, j, j, tau_j);
      if (!after_instant(tau_j)) return outcome;
    }
  }
  outcome.checked_until_s = chain.end_tau_s;
  return outcome;
}

}  // namespace shpb
