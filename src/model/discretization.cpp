#include "model/discretization.hpp"

#include <algorithm>
#include <cmath>

namespace shpb {

namespace {
// Margin on the default duration so the tail of the last pulse is recorded whole.
constexpr double kDurationMargin = 1.1;

int automatic_elements(const Scene& scene, std::size_t i) {
  const BarSpec& bar = scene.bars[i];
  if (bar.elements > 0) return bar.elements;
  const bool specimen = scene.specimen && *scene.specimen == i;
  const double h = specimen ? kSpecimenElementLength_m : kBarElementLength_m;
  const int minimum = specimen ? kMinSpecimenElements : kMinBarElements;
  return std::max(minimum, static_cast<int>(std::ceil(bar.length_m / h - 1e-9)));
}
}  // namespace

double default_duration_s(const Scene& scene) {
  if (scene.bars.empty()) return 0;
  // The striker is the first bar; its pulse lasts 2 L/c.
  const double pulse = 2.0 * scene.bars.front().length_m / scene.bars.front().material.wave_speed_m_s();
  double travel = 0, last_gauge_arrival = -1;
  for (std::size_t i = 1; i < scene.bars.size(); ++i) {
    const BarSpec& bar = scene.bars[i];
    const double c = bar.material.wave_speed_m_s();
    for (const GaugeSpec& g : bar.gauges)
      last_gauge_arrival = std::max(last_gauge_arrival, travel + g.position_m / c);
    travel += bar.length_m / c;
  }
  if (last_gauge_arrival < 0) {
    double longest = 0;
    for (const BarSpec& bar : scene.bars)
      longest = std::max(longest, bar.length_m / bar.material.wave_speed_m_s());
    return 2.0 * longest * kDurationMargin;
  }
  return (last_gauge_arrival + pulse) * kDurationMargin;
}

ChainDiscretization discretize(const Scene& scene) {
  ChainDiscretization d;
  d.sample_rate_Hz = scene.simulation.sample_rate_Hz;
  d.stepping = scene.simulation.stepping;
  d.duration_s = scene.simulation.duration_s.value_or(default_duration_s(scene));
  const double courant = scene.simulation.courant.value_or(kDefaultCourant);
  for (std::size_t i = 0; i < scene.bars.size(); ++i) {
    BarDiscretization b;
    b.elements = automatic_elements(scene, i);
    b.element_length_m = scene.bars[i].length_m / b.elements;
    // The stable step is fixed at the elastic bound for every material law (material_law.hpp).
    b.wave_speed_m_s = scene.bars[i].material.wave_speed_m_s();
    b.critical_step_s = b.element_length_m / b.wave_speed_m_s;
    b.time_step_s = courant * b.critical_step_s;
    b.courant = courant;
    d.bars.push_back(b);
  }
  if (d.stepping == Stepping::kGlobal && !d.bars.empty()) {
    double dt = d.bars.front().time_step_s;
    for (const auto& b : d.bars) dt = std::min(dt, b.time_step_s);
    for (auto& b : d.bars) {
      b.time_step_s = dt;
      b.courant = dt / b.critical_step_s;
    }
  }
  for (auto& b : d.bars) b.steps = static_cast<long>(std::ceil(d.duration_s / b.time_step_s));
  return d;
}

}  // namespace shpb
