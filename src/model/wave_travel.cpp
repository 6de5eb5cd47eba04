#include "model/wave_travel.hpp"

#include <algorithm>
#include <cmath>

namespace shpb {

double travel_time_s(const Scene& s, std::size_t a, double xa, std::size_t b, double xb) {
  if (a == b) return std::abs(xb - xa) / s.bars[a].material.wave_speed_m_s();
  double t = (s.bars[a].length_m - xa) / s.bars[a].material.wave_speed_m_s();
  for (std::size_t i = a + 1; i < b; ++i)
    t += s.bars[i].length_m / s.bars[i].material.wave_speed_m_s();
  return t + xb / s.bars[b].material.wave_speed_m_s();
}

double longest_transit_s(const Scene& s) {
  double longest = 0;
  for (const BarSpec& b : s.bars)
    longest = std::max(longest, b.length_m / b.material.wave_speed_m_s());
  return longest;
}

double striker_pulse_s(const Scene& s, std::size_t striker) {
  return 2 * s.bars[striker].length_m / s.bars[striker].material.wave_speed_m_s();
}

double pulses_passed_s(const Scene& s, std::size_t striker, std::size_t bar, double position) {
  const std::size_t first = striker + 1;  // impact at its left end at t = 0
  const double arrival = travel_time_s(s, first, 0, bar, position);
  const double pulse = striker_pulse_s(s, striker);
  if (s.specimen && bar < *s.specimen)  // the reflected pulse comes back after 2τ
    return arrival + 2 * travel_time_s(s, bar, position, *s.specimen, 0) + pulse;
  return arrival + pulse;
}

std::optional<double> pulses_passed_s(const Scene& s) {
  const auto striker = striker_bar(s);
  if (!striker) return std::nullopt;
  std::optional<double> latest;
  for (std::size_t b = *striker + 1; b < s.bars.size(); ++b)
    for (const auto& g : s.bars[b].gauges)
      latest = std::max(latest.value_or(0.0), pulses_passed_s(s, *striker, b, g.position_m));
  return latest;
}

}  // namespace shpb
