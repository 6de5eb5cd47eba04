#pragma once
// The specimen's own state (specimen.csv of `shpb simulate`) as a reduction sees it: averaged over
// a window, since the reduced curve is an average over a wave's transit; and the simulated gauges
// as process reads them.
#include <algorithm>
#include <cstddef>
#include <vector>

#include "analysis/gauge_signals.hpp"
#include "solver/simulation.hpp"

namespace shpb_test {

// Centred moving average over 2 half + 1 samples (fewer at the ends).
inline std::vector<double> moving_average(const std::vector<double>& y, std::size_t half) {
  std::vector<double> out(y.size());
  for (std::size_t i = 0; i < y.size(); ++i) {
    const std::size_t a = i >= half ? i - half : 0, b = std::min(y.size(), i + half + 1);
    double sum = 0;
    for (std::size_t k = a; k < b; ++k) sum += y[k];
    out[i] = sum / static_cast<double>(b - a);
  }
  return out;
}

// The simulated gauges of a scene, as process reads them.
inline shpb::GaugeSignals gauges_of(const shpb::SimulationResult& sim) {
  shpb::GaugeSignals g;
  g.time_s = sim.gauges.time_s;
  g.dt_s = g.time_s[1] - g.time_s[0];
  for (const char* name : {"incident", "transmitted"}) {
    g.gauges.push_back(name);
    g.strain.push_back(sim.gauges.column(name));
  }
  return g;
}

}  // namespace shpb_test
