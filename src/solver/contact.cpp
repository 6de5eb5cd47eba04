#include "solver/contact.hpp"

#include <algorithm>

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
  const double k = std::max(left.stiffness_N_m, right.stiffness_N_m);
  double eps_s = params.stiffness_factor.value_or(kDefaultStiffnessFactor) * k;
  if (params.stiffness_N_m) eps_s = *params.stiffness_N_m;
  if (params.rise_time_s) {
    // Two long bars joined by a spring of stiffness K: dF/dt = K (V − F/Z_l − F/Z_r), so the
    // force rises with 1/τ = K (1/Z_l + 1/Z_r) (PenaltyParams::rise_time_s). The localized method
    // puts its two links in series through the frame, each of stiffness 2K.
    const double zl = left.impedance_kg_s(), zr = right.impedance_kg_s();
    const double series = zl * zr / ((zl + zr) * *params.rise_time_s);
    eps_s = method == ContactMethod::kLocalizedBipenalty ? 2 * series : series;
  }
  const double ratio = params.mass_ratio.value_or(kDefaultMassRatio);
  auto r_crit = [](const NeighbourInfo& n) {
    const double r = 2.0 * n.wave_speed_m_s / n.element_length_m;
    return r * r;
  };
  if (method == ContactMethod::kLocalizedBipenalty) {
    // Each link keeps its own bar's step, R_i ≤ (2 c_i / h_i)² (docs/methods.md §3), and both take
    // the smaller of the two: with compliant links (ε_m,i ≪ m_bi) the frame moves on the links
    // alone at ω² = Σ ε_s,i / Σ ε_m,i, a mean of the R_i that the side with the longer step must
    // resolve (contact_localized_finite.cpp).
    const double r = ratio * std::min(r_crit(left), r_crit(right));
    m.stiffness_N_m[0] = m.stiffness_N_m[1] = eps_s;
    m.mass_penalty_kg[0] = m.mass_penalty_kg[1] = eps_s / r;
    m.end_follows_frame[0] = m.mass_penalty_kg[0] >= left.end_mass_kg();
    m.end_follows_frame[1] = m.mass_penalty_kg[1] >= right.end_mass_kg();
    m.finite_links =
        params.stiffness_N_m || params.stiffness_factor || params.rise_time_s || params.mass_ratio;
  } else {
    // One node-to-node link: R below the smaller critical ratio of the two bars.
    m.stiffness_N_m[0] = eps_s;
    m.mass_penalty_kg[0] = method == ContactMethod::kBipenalty || method == ContactMethod::kBonded
                               ? eps_s / (ratio * std::min(r_crit(left), r_crit(right)))
                               : 0.0;
  }
  return m;
}

InterfaceModel interface_model(const Scene& scene, const ChainDiscretization& d, std::size_t k) {
  auto neighbour = [&](std::size_t i) {
    const BarSpec& b = scene.bars[i];
    const double h = d.bars[i].element_length_m;
    return NeighbourInfo{b.material.youngs_modulus_Pa * b.area_m2 / h, b.material.wave_speed_m_s(),
                         h};
  };
  return make_interface_model(interface_name(scene, k), interface_method(scene.contact, k),
                              interface_penalty(scene.contact, k), scene.bars[k].gap_m,
                              neighbour(k), neighbour(k + 1));
}

ContactResult solve_contact(const InterfaceModel& model, InterfaceState& state, EndState left,
                            EndState right, double tau, double frame_next_tau) {
  state.gap_m = model.gap0_m + right.u - left.u;
  switch (model.method) {
    case ContactMethod::kPenalty:
      return solve_penalty(model, state, left, right);
    case ContactMethod::kBipenalty:
      return solve_bipenalty(model, state, left, right);
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
