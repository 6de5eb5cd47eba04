// Node-to-node bipenalty contact (docs/methods.md §2), the baseline with naive switching: while the
// gap is negative the potential ½ ε_s g² and the kinetic term ½ ε_m ġ² are added, so the two end
// nodes solve the 2×2 system
//   [m1 + ε_m, −ε_m; −ε_m, m2 + ε_m] [ü1; ü2] = [f̃1 + ε_s g; f̃2 − ε_s g].
// Switching is the textbook one, with no velocity or position correction: the contact switches
// on when g < 0 whatever ġ is, and off when the link force turns tensile. This is the
// formulation whose force chatters between ~0 and 2Zv from step to step (docs/methods.md §2).
#include "solver/contact.hpp"

namespace shpb {

ContactResult solve_bipenalty(const InterfaceModel& model, InterfaceState& state,
                              const EndState& left, const EndState& right) {
  ContactResult r;
  const double g = state.gap_m;
  if (!state.active && g >= 0 && !model.tied) {
    state.force_N = 0;
    state.energy_J = 0;
    return r;
  }
  const double es = model.stiffness_N_m[0], em = model.mass_penalty_kg[0];
  const double m1 = left.mass, m2 = right.mass;
  const double F1 = left.free_force + es * g, F2 = right.free_force - es * g;
  const double a11 = m1 + em, a22 = m2 + em, a12 = -em;
  const double det = a11 * a22 - a12 * a12;
  const double acc1 = (a22 * F1 - a12 * F2) / det;
  const double acc2 = (a11 * F2 - a12 * F1) / det;
  const double on_left = m1 * acc1 - left.free_force;
  const double on_right = m2 * acc2 - right.free_force;
  double compression;
  if (left.stepping && right.stepping)
    compression = 0.5 * (on_right - on_left);
  else
    compression = left.stepping ? -on_left : on_right;
  state.active = compression >= 0 || model.tied;
  if (!state.active) {
    state.force_N = 0;
    state.energy_J = 0;
    return r;
  }
  if (left.stepping) r.force_left_N = on_left;
  if (right.stepping) r.force_right_N = on_right;
  state.force_N = compression;
  // Only the potential counts: with naive switching the mass-penalty term ½ ε_m ġ² appears
  // from nothing at every activation and is not energy the bars ever held.
  state.energy_J = 0.5 * es * g * g;
  return r;
}

}  // namespace shpb
