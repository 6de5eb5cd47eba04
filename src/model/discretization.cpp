#include "model/discretization.hpp"

#include <algorithm>
#include <cmath>

namespace shpb {
// PROVISIONAL: a first automatic mesh, to be refined by the simulator work (issue 3).
ChainDiscretization discretize(const Scene& scene) {
  ChainDiscretization d;
  d.sample_rate_Hz = scene.simulation.sample_rate_Hz;
  d.stepping = scene.simulation.stepping;
  const double courant = scene.simulation.courant.value_or(0.99);
  double longest = 0, slowest = 1e30;
  for (const auto& bar : scene.bars) {
    BarDiscretization b;
    const double c = bar.material.wave_speed_m_s();
    b.elements = bar.elements > 0 ? bar.elements
                                  : std::max(20, static_cast<int>(std::ceil(bar.length_m / 1e-3)));
    b.element_length_m = bar.length_m / b.elements;
    b.critical_step_s = b.element_length_m / c;
    b.time_step_s = courant * b.critical_step_s;
    b.courant = courant;
    d.bars.push_back(b);
    longest = std::max(longest, bar.length_m);
    slowest = std::min(slowest, c);
  }
  if (d.stepping == Stepping::kGlobal) {
    double dt = 1e30;
    for (const auto& b : d.bars) dt = std::min(dt, b.time_step_s);
    for (auto& b : d.bars) {
      b.time_step_s = dt;
      b.courant = dt / b.critical_step_s;
    }
  }
  d.duration_s = scene.simulation.duration_s.value_or(2.0 * longest / slowest);
  return d;
}
}  // namespace shpb
