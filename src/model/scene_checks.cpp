#include "model/scene_checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/csv_writer.hpp"  // format_double
#include "core/number_format.hpp"
#include "model/test_setup.hpp"
#include "model/wave_travel.hpp"

namespace shpb {
namespace {

std::string micro(double seconds) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f us", seconds * 1e6);
  return buf;
}

// A pulse shaper wider than a bar face it is pressed by (docs/methods.md §8.4): the 1D chain
// spreads the shaper's force over its own cross-section, but only the contact, the smaller face,
// carries it, so the shaper's stress is understated by the area ratio (a metal shaper flows at
// that many times the force). Warned, not refused: the overhang confines the loaded core, which
// neither area models. A specimen is not a shaper: its reduction takes its own area as given.
void wide_shapers(const Scene& s, std::vector<std::string>& w) {
  for (std::size_t i : test_roles(s).shapers) {
    if (i == 0 || i + 1 >= s.bars.size()) continue;
    const BarSpec& shaper = s.bars[i];
    const BarSpec& face =
        s.bars[i - 1].area_m2 < s.bars[i + 1].area_m2 ? s.bars[i - 1] : s.bars[i + 1];
    if (!(shaper.area_m2 > face.area_m2)) continue;
    const std::string key = shaper.area_given ? "area" : "diameter";
    auto size = [&](const BarSpec& b) {
      return b.area_given ? format_number(b.area_m2 * 1e6) + " mm2"
                          : format_number(b.diameter_m * 1e3) + " mm";
    };
    w.push_back("bars[" + std::to_string(i) + "]." + key + ": " + size(shaper) +
                ": the pulse shaper \"" + shaper.name + "\" is wider than the face of bar \"" +
                face.name + "\" (" + size(face) +
                ") it is pressed by, which alone carries its load; the 1D chain spreads the load "
                "over the shaper's own area, understating its stress " +
                format_number(shaper.area_m2 / face.area_m2) +
                " times: give the shaper the contact's size (docs/methods.md §8.4)");
  }
}

}  // namespace

std::vector<std::string> scene_warnings(const Scene& s, double duration_s) {
  std::vector<std::string> w;
  wide_shapers(s, w);
  if (s.measurement) {
    std::error_code ec;
    if (!s.measurement->file.empty() && !std::filesystem::exists(s.measurement->file, ec))
      w.push_back("measurement file " + s.measurement->file.string() +
                  " not found (process and compare will need it)");
  }

  // The largest strain a step is planned for applies to finite strain only (discretization.hpp).
  if (s.simulation.max_strain && !s.simulation.finite_strain)
    w.push_back(
        "simulation.max_strain has no effect with \"kinematics\": \"small\" (the steps are "
        "planned for it with finite strain only)");

  // The striker: the first moving bar. Its pulse lasts 2 L/c (docs/methods.md §4).
  if (std::none_of(s.bars.begin(), s.bars.end(),
                   [](const BarSpec& b) { return b.velocity_m_s != 0; })) {
    w.push_back(
        "no bar has a velocity: a simulation would show nothing (fine for a scene that only "
        "processes measured signals)");
    return w;
  }
  const auto striker = striker_bar(s);
  if (const auto launched = test_roles(s).striker; launched && !striker) {
    w.push_back("bar " + s.bars[*launched].name +
                " moves away from the bar on its right (velocity " +
                format_double(s.bars[*launched].velocity_m_s) +
                " m/s, + to the right) and is not bonded to it: it loads nothing");
    return w;
  }
  if (!striker) return w;
  const double pulse_s = striker_pulse_s(s, *striker);
  const std::size_t first = *striker + 1;  // impact at its left end at t = 0
  const std::size_t last = s.bars.size() - 1;

  for (std::size_t b = first; b <= last; ++b) {
    for (const auto& g : s.bars[b].gauges) {
      const bool incident_side = s.specimen && b < *s.specimen;
      if (incident_side) {
        const double to_face = travel_time_s(s, b, g.position_m, *s.specimen, 0);
        if (2 * to_face < pulse_s)
          w.push_back("gauge " + g.name +
                      ": incident and reflected pulses overlap (round trip to "
                      "the specimen " +
                      micro(2 * to_face) + " < pulse " + micro(pulse_s) +
                      "); move it further from the specimen");
        const double to_left_end = travel_time_s(s, first, 0, b, g.position_m);
        if (2 * to_left_end < pulse_s)
          w.push_back("gauge " + g.name +
                      ": the reflection from the impact end overlaps the "
                      "reflected pulse (round trip " +
                      micro(2 * to_left_end) + " < pulse " + micro(pulse_s) + ")");
      } else {
        const double to_end = travel_time_s(s, b, g.position_m, last, s.bars[last].length_m);
        if (2 * to_end < pulse_s)
          w.push_back("gauge " + g.name +
                      ": the reflection from the far end of the chain "
                      "overlaps the pulse (round trip " +
                      micro(2 * to_end) + " < pulse " + micro(pulse_s) + ")");
      }
    }
  }
  const double needed_s = pulses_passed_s(s).value_or(0.0);
  if (duration_s < needed_s)
    w.push_back("duration " + micro(duration_s) +
                " ends before the pulses have passed every "
                "gauge (about " +
                micro(needed_s) + " by 1D travel times)");
  return w;
}

}  // namespace shpb
