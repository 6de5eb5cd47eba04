#include "solver/contact.hpp"

#include <algorithm>
#include <cmath>

#include "model/interface_name.hpp"

namespace shpb {

InterfaceModel make_interface_model(std::string name, ContactMethod method,
                                    const PenaltyParams& params, double gap0_m,
                                    const NeighbourInfo& left, const NeighbourInfo& right) {
  InterfaceModel m;
  m.name = std::move(name);
  m.method = method;
  m.gap0_m = gap0_m;
  m.tied = params.tied || method == ContactMethod::kBonded;
  const PenaltyLinks links = penalty_links(method, params, left, right);
  if (method == ContactMethod::kLocalizedBipenalty) {
    m.stiffness_N_m[0] = m.stiffness_N_m[1] = links.stiffness_N_m;
    m.mass_penalty_kg[0] = m.mass_penalty_kg[1] = links.mass_penalty_kg;
    m.end_follows_frame[0] = m.mass_penalty_kg[0] >= left.end_mass_kg();
    m.end_follows_frame[1] = m.mass_penalty_kg[1] >= right.end_mass_kg();
    m.finite_links = finite_links(params);
  } else {
    m.stiffness_N_m[0] = links.stiffness_N_m;
    m.mass_penalty_kg[0] = links.mass_penalty_kg;
  }
  return m;
}

InterfaceModel interface_model(const Scene& scene, const ChainDiscretization& d, std::size_t k) {
  InterfaceModel m =
      make_interface_model(interface_name(scene, k), interface_method(scene.contact, k),
                           interface_penalty(scene.contact, k), scene.bars[k].gap_m,
                           neighbour_info(scene, d, k), neighbour_info(scene, d, k + 1));
  // A body's end changes its motion only when a wave has crossed it: faces apart for less than
  // the shorter neighbour's transit are one meeting (a specimen's ringing, a train of closings
  // within it), longer a new one.
  const auto transit = [&](std::size_t i) {
    return scene.bars[i].length_m / scene.bars[i].material.wave_speed_m_s();
  };
  m.meeting_separation_s = std::min(transit(k), transit(k + 1));
  return m;
}

void book_unloading(const InterfaceModel& model, InterfaceState& state, double tau) {
  InterfaceState::Unloading& u = state.unloading;
  const bool closed = state.activations > state.booked_activations;
  const bool opened = state.releases > state.booked_releases;
  state.booked_activations = state.activations;
  state.booked_releases = state.releases;
  if (state.force_N > state.peak_force_N) u = {};  // a new loading peak: not unloaded yet
  if (std::isnan(u.release_s)) {
    if (opened) u.release_s = u.last_release_s = tau;
    return;
  }
  if (closed) {
    ++u.closings;
    if (tau - u.last_release_s > model.meeting_separation_s) ++u.meetings;
  }
  u.largest_force_N = std::max(u.largest_force_N, state.force_N);
  if (opened) u.last_release_s = tau;
}

ContactResult solve_contact(const InterfaceModel& model, InterfaceState& state, EndState left,
                            EndState right, double tau, double frame_next_tau) {
  state.gap_m = model.gap0_m + right.u - left.u;
  switch (model.method) {
    case ContactMethod::kPenalty:
    case ContactMethod::kBipenalty: {
      // The node-to-node methods switch by the gap and the link force alone: their closings and
      // openings are counted here (summary.json interfaces[].activations, releases).
      const bool was_active = state.active;
      const ContactResult r = model.method == ContactMethod::kPenalty
                                  ? solve_penalty(model, state, left, right)
                                  : solve_bipenalty(model, state, left, right);
      if (state.active && !was_active) ++state.activations;
      if (!state.active && was_active) ++state.releases;
      return r;
    }
    case ContactMethod::kBonded:  // the rigid link, bilateral
      return solve_localized_bipenalty(model, state, left, right, tau, frame_next_tau);
    case ContactMethod::kLocalizedBipenalty:
      if (model.finite_links)
        return solve_localized_finite(model, state, left, right, tau, frame_next_tau);
      return solve_localized_bipenalty(model, state, left, right, tau, frame_next_tau);
  }
  return {};
}

}  // namespace shpb
