#include "solver/step_control.hpp"

#include <algorithm>
#include <cmath>

namespace shpb {

double geometric_stiffening(const BarModel& bar, double stress_Pa) {
  const double ratio = stress_Pa / (bar.density_kg_m3 * bar.wave_speed_m_s * bar.wave_speed_m_s);
  return ratio > kGeometricStiffeningRoom ? std::sqrt(1 + ratio) : 1.0;
}

double planned_step_s(const BarModel& bar, double stretch, double stress_Pa) {
  if (!bar.adaptive_step) return bar.own_step_s;
  return std::max(bar.time_step_s,
                  bar.reference_step_s * stretch / geometric_stiffening(bar, stress_Pa));
}

void start_phase(Chain& chain, std::size_t i, double dt) {
  BarState& s = chain.states[i];
  const double tau = chain.bar_tau(i);
  s.phase_step = s.step;
  s.phase_tau = tau;
  s.dt = dt;
  chain.final_step[i] = s.step + static_cast<long>(std::ceil((chain.end_tau_s - tau) / dt - 1e-9));
}

void plan_first_steps(Chain& chain) {
  const std::size_t nb = chain.bars.size();
  bool any = false;
  double common = 0;
  for (std::size_t i = 0; i < nb; ++i) {
    const double dt = planned_step_s(chain.bars[i], 1.0, 0.0);
    common = i == 0 ? dt : std::min(common, dt);
    any = any || chain.bars[i].adaptive_step;
  }
  if (!any) return;  // every bar keeps the step it was built with
  for (std::size_t i = 0; i < nb; ++i)
    if (chain.global_stepping)
      start_phase(chain, i, common);
    else if (chain.bars[i].adaptive_step)
      start_phase(chain, i, planned_step_s(chain.bars[i], 1.0, 0.0));
}

void replan_steps(Chain& chain, const std::vector<char>& stepping, std::size_t first,
                  std::size_t last) {
  bool changed = false;
  for (std::size_t i = first; i <= last; ++i) {
    const BarModel& b = chain.bars[i];
    BarState& s = chain.states[i];
    if (!stepping[i] || !b.adaptive_step) continue;
    const bool shorter = s.smallest_stretch < s.planned_stretch;
    const bool stiffer = s.largest_stress_Pa > s.planned_stress_Pa &&
                         geometric_stiffening(b, s.largest_stress_Pa) > 1;
    if (!shorter && !stiffer) continue;
    if (shorter) s.planned_stretch = std::max(b.min_stretch, s.smallest_stretch - kStepPlanMargin);
    if (stiffer) s.planned_stress_Pa = s.largest_stress_Pa * (1 + kStressPlanMargin);
    changed = true;
    if (!chain.global_stepping)
      start_phase(chain, i, planned_step_s(b, s.planned_stretch, s.planned_stress_Pa));
  }
  if (!changed || !chain.global_stepping) return;
  // Global stepping: every bar steps at every instant; all take the smallest step needed.
  double common = 0;
  for (std::size_t i = 0; i < chain.bars.size(); ++i) {
    const double dt = planned_step_s(chain.bars[i], chain.states[i].planned_stretch,
                                     chain.states[i].planned_stress_Pa);
    common = i == 0 ? dt : std::min(common, dt);
  }
  for (std::size_t i = 0; i < chain.bars.size(); ++i) start_phase(chain, i, common);
}

}  // namespace shpb
