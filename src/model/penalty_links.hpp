#pragma once
// The penalty links of one interface as every run builds them (docs/methods.md §2–3): the link
// stiffness ε_s and mass penalty ε_m from the scene's penalty parameters and the end elements of
// the two bars. The solver's interface model (solver/contact.hpp) and the check that a scene's
// derived quantities are computable (model/computable.hpp) take them from here.
#include "model/discretization.hpp"
#include "model/scene.hpp"

namespace shpb {

// Default penalty parameters (docs/methods.md §2): ε_s = kDefaultStiffnessFactor × the stiffer
// neighbour's EA/h; R_i = kDefaultMassRatio × (2 c_i/h_i)², the bar's own critical ratio, so
// that every link leaves its bar's stable step unchanged.
inline constexpr double kDefaultStiffnessFactor = 1e4;
inline constexpr double kDefaultMassRatio = 0.9;

struct NeighbourInfo {
  double stiffness_N_m;  // EA/h of the end element
  double wave_speed_m_s;
  double element_length_m;
  double impedance_kg_s() const {
    return stiffness_N_m * element_length_m / wave_speed_m_s;
  }                             // EA/c
  double end_mass_kg() const {  // ρAh/2 = (EA/h) h² / (2c²)
    return 0.5 * stiffness_N_m * element_length_m * element_length_m /
           (wave_speed_m_s * wave_speed_m_s);
  }
  // (2c/h)²: the critical bipenalty mass ratio of this bar's end element.
  double critical_ratio() const {
    const double r = 2.0 * wave_speed_m_s / element_length_m;
    return r * r;
  }
};

// The end element of bars[i] in discretization `d`.
NeighbourInfo neighbour_info(const Scene& scene, const ChainDiscretization& d, std::size_t i);

// Localized bipenalty: the seed paper's finite links when the scene gives any penalty parameter,
// else the rigid-link limit ε_s, ε_m → ∞ (solver/contact_localized_bipenalty.cpp).
inline bool finite_links(const PenaltyParams& p) {
  return p.stiffness_N_m || p.stiffness_factor || p.rise_time_s || p.mass_ratio;
}
// Whether an interface's links are the finite ones penalty_links() gives (the rigid link of
// localized bipenalty without parameters, and of `bonded`, takes neither).
inline bool links_are_finite(ContactMethod method, const PenaltyParams& p) {
  return method == ContactMethod::kPenalty || method == ContactMethod::kBipenalty ||
         (method == ContactMethod::kLocalizedBipenalty && finite_links(p));
}

// Each link's stiffness ε_s and mass penalty ε_m (0 for the plain penalty method). The localized
// method's two links have the same values.
struct PenaltyLinks {
  double stiffness_N_m = 0;
  double mass_penalty_kg = 0;
};
PenaltyLinks penalty_links(ContactMethod method, const PenaltyParams& params,
                           const NeighbourInfo& left, const NeighbourInfo& right);

}  // namespace shpb
