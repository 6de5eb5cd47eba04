// Plain penalty contact (stiffness only), the textbook baseline: while the gap is negative the
// ends are pushed apart by ε_s·(−g). Naive on/off switching. Stable only if ε_s is small
// against the bars' stiffness or the step is shrunk by ≈ sqrt(2k/ε_s) (docs/methods.md §2); at the
// bars' own steps with ε_s = 10⁴ EA/h it is unstable, and the run says so (exit 3).
#include "solver/contact.hpp"

namespace shpb {

ContactResult solve_penalty(const InterfaceModel& model, InterfaceState& state,
                            const EndState& left, const EndState& right) {
  ContactResult r;
  const double g = state.gap_m;
  state.active = g < 0 || model.tied;
  if (!state.active) {
    state.force_N = 0;
    state.energy_J = 0;
    return r;
  }
  const double eps = model.stiffness_N_m[0];
  const double push = -eps * g;  // > 0, compression
  state.force_N = push;
  state.energy_J = 0.5 * eps * g * g;
  if (left.stepping) r.force_left_N = -push;
  if (right.stepping) r.force_right_N = push;
  return r;
}

}  // namespace shpb
