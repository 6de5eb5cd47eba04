#include "analysis/process_setup.hpp"

#include <algorithm>

#include "analysis/bar_check.hpp"
#include "analysis/gauge_signals.hpp"
#include "analysis/kolsky_setup.hpp"
#include "analysis/signal_checks.hpp"
#include "analysis/uncertainty.hpp"
#include "model/test_setup.hpp"

namespace shpb {
namespace {

using nlohmann::json;

json window_json(const std::optional<TimeWindow>& w) {
  return w ? json::array({w->start_s, w->end_s}) : json("detected");
}

json column_json(const ColumnRef& c) { return c.index ? json(*c.index) : json(c.name); }

}  // namespace

json process_setup(const Scene& scene) {
  const MeasurementSpec& m = *scene.measurement;
  const GaugeSignals signals = read_gauge_signals(m, {});
  json p;
  p["file"] = m.file.empty() ? json(nullptr) : json(m.file.string());
  p["format"] = std::string(enum_name(kSignalFormatNames, m.format));
  if (!m.sheet.empty()) p["sheet"] = m.sheet;
  p["time_column"] = m.time_clock ? json("none (measurement.time.interval)")
                     : m.time_column.name.empty() && !m.time_column.index
                         ? json("the format's own")
                         : column_json(m.time_column);
  p["time_unit"] = m.time_unit;
  p["samples"] = signals.time_s.size();
  p["sample_interval_s"] = signals.dt_s;
  p["record_s"] = {signals.time_s.front(), signals.time_s.back()};
  for (const ChannelSpec& ch : m.channels) {
    json c = {{"gauge", ch.gauge},
              {"file", (ch.file.empty() ? m.file : ch.file).string()},
              {"column", column_json(ch.column)},
              {"unit", std::string(enum_name(kSignalUnitNames, ch.unit))},
              {"invert", ch.invert}};
    const double per_unit = strain_per_unit(ch);
    if (ch.bridge)
      c["bridge"] = {{"arms", ch.bridge->arms},
                     {"gauge_factor", ch.bridge->gauge_factor},
                     {"excitation_V", ch.bridge->excitation_V},
                     {"gain", ch.bridge->gain}};
    c["strain_per_unit"] = per_unit;
    p["channels"].push_back(c);
  }
  for (std::size_t g = 0; g < signals.gauges.size(); ++g) {
    const auto [lo, hi] = std::minmax_element(signals.strain[g].begin(), signals.strain[g].end());
    p["gauges"].push_back({{"name", signals.gauges[g]}, {"strain_min", *lo}, {"strain_max", *hi}});
  }
  std::vector<std::string> warnings = signals.warnings;
  const std::vector<std::string> record = signal_warnings(signals);
  warnings.insert(warnings.end(), record.begin(), record.end());
  if (scene.specimen) {
    const KolskySetup k = resolve_setup(scene, signals.gauges);
    // A time base process would refuse is refused here too (docs/scene-format.md `measurement`).
    const RestSignal inc =
        rest_signal(signals, k.incident_gauge, m.tension ? 1.0 : -1.0, scene.file.string());
    if (inc.first)
      require_pulse_fits_round_trip(
          k, signals.dt_s * static_cast<double>(inc.first->end - 1 - inc.first->onset),
          scene.file.string());
    check_uncertainty(scene, signals);  // what process refuses before its draws
    p["reduction"] = "specimen";
    p["test"] = m.tension ? "tension" : "compression";
    p["incident_gauge"] = {{"name", k.incident_gauge},
                           {"distance_to_specimen_m", k.incident_distance_m}};
    p["transmitted_gauge"] = {{"name", k.transmitted_gauge},
                              {"distance_to_specimen_m", k.transmitted_distance_m}};
    // Timing of the 1D bar model (docs/methods.md §6): the reflected pulse reaches the incident
    // gauge 2d/c0 after the incident pulse (the lab's calibrated time when given), the
    // transmitted one reaches its gauge (d_i/c0 + d_t/c0) after it (the specimen's transit aside).
    const double reflected =
        m.reflected_time_s.value_or(2 * k.incident_distance_m / k.front.c0_m_s);
    const double transmitted =
        k.incident_distance_m / k.front.c0_m_s + k.transmitted_distance_m / k.back.c0_m_s;
    p["timing"] = {
        {"reflected_after_incident_s", reflected},
        {"transmitted_after_incident_s", transmitted},
        {"reflected_time", m.reflected_time_s ? "measurement.reflected_time" : "2 d / c0"}};
  } else {
    const BarCheckSetup b = resolve_bar_check(scene, signals.gauges);
    p["reduction"] = "bars together (no specimen)";
    p["near_gauge"] = b.near_gauge;
    p["far_gauge"] = b.far_gauge;
    p["distance_m"] = b.distance_m;
  }
  p["windows"] = {{"incident", window_json(m.windows.incident)},
                  {"reflected", window_json(m.windows.reflected)},
                  {"transmitted", window_json(m.windows.transmitted)}};
  p["dispersion"] = std::string(enum_name(kCorrectionNames, m.dispersion.correction));
  p["warnings"] = warnings;
  return p;
}

}  // namespace shpb
