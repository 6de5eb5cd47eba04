#include "model/penalty_links.hpp"

#include <algorithm>

namespace shpb {

NeighbourInfo neighbour_info(const Scene& scene, const ChainDiscretization& d, std::size_t i) {
  const BarSpec& b = scene.bars[i];
  const double h = d.bars[i].element_length_m;
  return NeighbourInfo{b.material.youngs_modulus_Pa * b.area_m2 / h, b.material.wave_speed_m_s(),
                       h};
}

PenaltyLinks penalty_links(ContactMethod method, const PenaltyParams& params,
                           const NeighbourInfo& left, const NeighbourInfo& right) {
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
  // Localized bipenalty: each link keeps its own bar's step, R_i ≤ (2 c_i / h_i)²
  // (docs/methods.md §3), and both take the smaller of the two: with compliant links
  // (ε_m,i ≪ m_bi) the frame moves on the links alone at ω² = Σ ε_s,i / Σ ε_m,i, a mean of the R_i
  // that the side with the longer step must resolve (contact_localized_finite.cpp). One
  // node-to-node link: R below the smaller critical ratio of the two bars.
  const double r = params.mass_ratio.value_or(kDefaultMassRatio) *
                   std::min(left.critical_ratio(), right.critical_ratio());
  return {eps_s, method == ContactMethod::kPenalty ? 0.0 : eps_s / r};
}

}  // namespace shpb
