#include "study/stability_probe.hpp"

#include <algorithm>
#include <cmath>

#include "solver/simulation.hpp"

namespace shpb {

namespace {
// Energy samples over the probe's duration: enough to see a growth that doubles every few steps.
constexpr double kProbeSamples = 200;
// Relative closing speed of a tied probe: small against the rigid motion whose energy the growth
// is measured against, large against round-off.
constexpr double kTiedRelativeVelocity = 1e-3;
}  // namespace

Scene stability_probe_scene(const Scene& scene) {
  Scene probe;
  probe.file = scene.file;
  probe.bars.assign(scene.bars.begin(),
                    scene.bars.begin() + std::min<std::size_t>(2, scene.bars.size()));
  const double length = probe.bars.front().length_m;
  double slowest = probe.bars.front().material.wave_speed_m_s();
  for (BarSpec& b : probe.bars) {
    b.length_m = length;
    b.elements = kProbeElements;
    b.gap_m = 0;
    b.gauges.clear();
    slowest = std::min(slowest, b.material.wave_speed_m_s());
  }
  probe.bars.back().velocity_m_s = 0;
  if (probe.bars.front().velocity_m_s == 0) probe.bars.front().velocity_m_s = 1.0;
  probe.name = "stability probe: " + probe.bars.front().name + " on " + probe.bars.back().name +
               ", both " + std::to_string(length) + " m long with " +
               std::to_string(kProbeElements) + " elements";
  probe.contact.method = scene.contact.method;
  probe.simulation.duration_s = 3 * length / slowest;
  probe.simulation.sample_rate_Hz = kProbeSamples / *probe.simulation.duration_s;
  return probe;
}

StabilityVerdict judge_stability(const Scene& probe, const StabilityPoint& point) {
  Scene s = probe;
  s.contact.method = point.method;
  s.contact.interfaces.clear();
  s.contact.penalty = {};
  // Localized bipenalty with no stiffness: the rigid-link limit (docs/methods.md §3.3).
  const bool rigid_limit =
      point.method == ContactMethod::kLocalizedBipenalty && point.stiffness_factor == 0;
  if (!rigid_limit) s.contact.penalty.stiffness_factor = point.stiffness_factor;
  if (point.method != ContactMethod::kPenalty && !rigid_limit)
    s.contact.penalty.mass_ratio = point.mass_ratio;
  s.contact.penalty.tied = point.tied;
  // A tied link started at ġ = −V would hold ½ ε_m V² from nothing (the switching energy of
  // docs/methods.md §2), far above the bars' energy for a large mass penalty: the tied probe moves
  // both bars, the striker only kTiedRelativeVelocity faster, so the contact mode starts small.
  if (point.tied)
    s.bars.back().velocity_m_s = s.bars.front().velocity_m_s * (1 - kTiedRelativeVelocity);
  s.simulation.courant = point.courant;
  if (point.step_ratio != 1) {
    // The bar meshed finer by the step ratio (its element count rounded, its length adjusted so
    // that h_striker / h_bar is the ratio exactly), each bar on its own step.
    BarSpec& bar = s.bars.back();
    const double h = s.bars.front().length_m / s.bars.front().elements;
    bar.elements = static_cast<int>(std::lround(bar.elements * point.step_ratio));
    bar.length_m = bar.elements * h / point.step_ratio;
    s.simulation.stepping = Stepping::kAsynchronous;
  }
  SimulationOptions options;
  options.record_field = false;
  options.stabilize = false;  // the map shows where each method fails
  const SimulationResult r = simulate(s, options);
  StabilityVerdict v;
  const std::vector<double>& total = r.energy.column("total_J");
  if (!total.empty() && total.front() > 0)
    for (double e : total) v.energy_growth = std::max(v.energy_growth, e / total.front());
  v.stable = r.stable && v.energy_growth <= kUnstableEnergyGrowth;
  for (const InterfaceStatistics& i : r.interface_statistics) {
    v.closings_after_release += std::max(0L, i.activations - 1);
    v.meetings_after_unloading += i.meetings_after_unloading;
    const double share = i.force_after_unloading_share;  // NaN: never unloaded
    if (!std::isnan(share) && !(share <= v.force_after_unloading_share))
      v.force_after_unloading_share = share;
  }
  return v;
}

double penalty_critical_courant(double stiffness_factor) {
  const double s = stiffness_factor;
  return std::sqrt(2.0 / (1.0 + std::sqrt(1.0 + 4.0 * s * s)));
}

double bipenalty_critical_courant(double mass_ratio) {
  return mass_ratio <= 1 ? 1.0 : 1.0 / std::sqrt(mass_ratio);
}

double measured_critical_courant(const Scene& probe, StabilityPoint point, double lo, double hi,
                                 int iterations) {
  auto stable = [&](double c) {
    point.courant = c;
    return judge_stability(probe, point).stable;
  };
  if (!stable(lo)) return lo;
  if (stable(hi)) return hi;
  for (int i = 0; i < iterations; ++i) {
    const double mid = std::sqrt(lo * hi);
    (stable(mid) ? lo : hi) = mid;
  }
  return std::sqrt(lo * hi);
}

}  // namespace shpb
