#include "model/scene_checks.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>

namespace shpb {
namespace {

std::string micro(double seconds) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f us", seconds * 1e6);
  return buf;
}

// Travel time of a bar wave along the chain from (bar a, position xa) to (bar b, position xb),
// a <= b, through every bar in between at its own c0.
double travel_time(const Scene& s, std::size_t a, double xa, std::size_t b, double xb) {
  if (a == b) return std::abs(xb - xa) / s.bars[a].material.wave_speed_m_s();
  double t = (s.bars[a].length_m - xa) / s.bars[a].material.wave_speed_m_s();
  for (std::size_t i = a + 1; i < b; ++i)
    t += s.bars[i].length_m / s.bars[i].material.wave_speed_m_s();
  return t + xb / s.bars[b].material.wave_speed_m_s();
}

}  // namespace

std::vector<std::string> scene_warnings(const Scene& s, double duration_s) {
  std::vector<std::string> w;
  if (s.measurement) {
    std::error_code ec;
    if (!s.measurement->file.empty() && !std::filesystem::exists(s.measurement->file, ec))
      w.push_back("measurement file " + s.measurement->file.string() +
                  " not found (process and compare will need it)");
  }

  // The striker: the first moving bar. Its pulse lasts 2 L/c (docs/methods.md §4).
  std::size_t striker = s.bars.size();
  for (std::size_t i = 0; i < s.bars.size() && striker == s.bars.size(); ++i)
    if (s.bars[i].velocity_m_s != 0) striker = i;
  if (striker == s.bars.size()) {
    w.push_back(
        "no bar has a velocity: a simulation would show nothing (fine for a scene that only "
        "processes measured signals)");
    return w;
  }
  if (striker + 1 >= s.bars.size() || s.bars[striker].velocity_m_s < 0) return w;
  const auto& sb = s.bars[striker];
  const double pulse_s = 2 * sb.length_m / sb.material.wave_speed_m_s();
  const std::size_t first = striker + 1;  // impact at its left end at t = 0 (docs/outputs.md (conventions))
  const std::size_t last = s.bars.size() - 1;

  double needed_s = 0;  // when the last pulse of interest has passed the last gauge
  for (std::size_t b = first; b <= last; ++b) {
    for (const auto& g : s.bars[b].gauges) {
      const double arrival = travel_time(s, first, 0, b, g.position_m);
      double passed = arrival + pulse_s;
      const bool incident_side = s.specimen && b < *s.specimen;
      if (incident_side) {
        // The reflected pulse comes back from the specimen's front face after 2τ.
        const double to_face = travel_time(s, b, g.position_m, *s.specimen, 0);
        passed = arrival + 2 * to_face + pulse_s;
        if (2 * to_face < pulse_s)
          w.push_back("gauge " + g.name +
                      ": incident and reflected pulses overlap (round trip to "
                      "the specimen " +
                      micro(2 * to_face) + " < pulse " + micro(pulse_s) +
                      "); move it further from the specimen");
        const double to_left_end = travel_time(s, first, 0, b, g.position_m);
        if (2 * to_left_end < pulse_s)
          w.push_back("gauge " + g.name +
                      ": the reflection from the impact end overlaps the "
                      "reflected pulse (round trip " +
                      micro(2 * to_left_end) + " < pulse " + micro(pulse_s) + ")");
      } else {
        const double to_end = travel_time(s, b, g.position_m, last, s.bars[last].length_m);
        if (2 * to_end < pulse_s)
          w.push_back("gauge " + g.name +
                      ": the reflection from the far end of the chain "
                      "overlaps the pulse (round trip " +
                      micro(2 * to_end) + " < pulse " + micro(pulse_s) + ")");
      }
      needed_s = std::max(needed_s, passed);
    }
  }
  if (duration_s < needed_s)
    w.push_back("duration " + micro(duration_s) +
                " ends before the pulses have passed every "
                "gauge (about " +
                micro(needed_s) + " by 1D travel times)");
  return w;
}

}  // namespace shpb
