#include "analysis/compare_run.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "analysis/kolsky_setup.hpp"
#include "analysis/pulse_window.hpp"
#include "analysis/signal_checks.hpp"
#include "core/checked_write.hpp"
#include "core/csv_writer.hpp"
#include "core/error.hpp"
#include "core/json_value.hpp"
#include "model/calibration.hpp"
#include "model/discretization.hpp"
#include "model/test_setup.hpp"
#include "model/wave_travel.hpp"
#include "output_schema.hpp"
#include "version.hpp"

namespace shpb {

// One compared pulse as summary.json lists it (docs/outputs.md); the window and rise times are in
// comparison.csv only.
void to_json(nlohmann::json& j, const PulseComparison& c) {
  j = {{"gauge", c.gauge},
       {"pulse", c.pulse},
       {"arrival_shift_s", c.arrival_shift_s},
       {"peak_ratio", c.peak_ratio},
       {"plateau_ratio", c.plateau_ratio},
       {"duration_ratio", c.duration_ratio},
       {"nrmse", c.nrmse},
       {"correlation", c.correlation}};
}

namespace {

// The striker velocity inferred from the measured plateau and the one used (given or the scene's)
// differing by more than this fraction: a wrong bridge factor, bar data or clipped signal.
constexpr double kVelocityMismatch = 0.1;
// A pulse compared beyond this NRMSE (the few percent a comparison is read to), which a clock off
// by half a sample alone would give, is said when the record does not resolve the incident front.
constexpr double kClockNrmse = 0.03;
// An extended simulation runs this fraction longer than the measured pulses need (the clocks are
// matched on the incident pulse only after the run).
constexpr double kDurationMargin = 0.1;

// Given, else the scene's, else inferred; launched the way the scene's striker moves (a tension
// striker pulls: − to the left).
void set_striker_velocity(ComparePlan& p, std::optional<double> given) {
  Scene& scene = p.scene;
  p.inferred_velocity_m_s =
      striker_velocity_from_plateau(p.found.setup, p.found.struck_end_plateau);
  if (given) {
    p.velocity_m_s = *given, p.velocity_source = "given (--striker-velocity)";
  } else if (scene.measurement->striker_velocity_m_s) {
    p.velocity_m_s = *scene.measurement->striker_velocity_m_s;
    p.velocity_source = "scene (measurement.striker_velocity)";
  } else {
    p.velocity_m_s = p.inferred_velocity_m_s;
    p.velocity_source = "inferred from the measured incident plateau";
  }
  p.scene_velocity_m_s = scene.bars[p.striker].velocity_m_s;
  scene.bars[p.striker].velocity_m_s = striker_direction(scene) * p.velocity_m_s;
  for (const double other : {p.velocity_m_s, std::abs(p.scene_velocity_m_s)})
    if (other > 0 && std::abs(p.inferred_velocity_m_s - other) > kVelocityMismatch * other) {
      p.warnings.push_back("the striker velocity inferred from the measured incident plateau, " +
                           format_double(p.inferred_velocity_m_s) + " m/s, differs from the " +
                           (other == p.velocity_m_s ? "one used" : "scene's") + ", " +
                           format_double(other) + " m/s, by more than " +
                           format_double(kVelocityMismatch * 100) +
                           " %: check the bridge factors, the bar data and the signals (clipping)");
      break;
    }
}

// The simulation must last until the measured pulses have passed their gauges: unless the scene
// sets a duration, the default is extended to the end of the last compared window, put on the
// simulation's clock by the incident pulse (its gauge is reached (l - d_I)/c0 after impact, after
// the striker has closed its gap).
void extend_duration(ComparePlan& p, std::size_t incident_bar) {
  Scene& scene = p.scene;
  if (scene.simulation.duration_s) return;
  const std::size_t last = last_compared_sample(p.found);
  const double arrival =
      (p.velocity_m_s > 0 ? scene.bars[p.striker].gap_m / p.velocity_m_s : 0.0) +
      travel_time_s(scene, incident_bar, 0, incident_bar,
                    scene.bars[incident_bar].length_m - p.found.setup.incident_distance_m);
  const double needed =
      (arrival + p.measured.time_s[last] - p.measured.time_s[p.found.incident_window.onset]) *
      (1 + kDurationMargin);
  if (needed > default_duration_s(scene))
    scene.simulation.duration_s = p.extended_duration_s = needed;
}

void write_comparison_csv(const std::vector<PulseComparison>& results,
                          const std::filesystem::path& file) {
  namespace k = schema::comparison;  // the column names (src/core/output_schema.json)
  CsvWriter csv(file, {k::gauge, k::pulse, k::window_start_s, k::window_end_s, k::arrival_shift_s,
                       k::peak_ratio, k::plateau_ratio, k::duration_ratio, k::rise_time_measured_s,
                       k::rise_time_simulated_s, k::nrmse, k::correlation});
  for (const auto& c : results) {
    // As computed: a ratio of a flat measured pulse may be non-finite, and is written as such.
    std::vector<std::string> cells = {c.gauge, c.pulse};
    for (double v : {c.window_start_s, c.window_end_s, c.arrival_shift_s, c.peak_ratio,
                     c.plateau_ratio, c.duration_ratio, c.rise_time_measured_s,
                     c.rise_time_simulated_s, c.nrmse, c.correlation})
      cells.push_back(format_double(v));
    csv.row(cells);
  }
  csv.close();
}

void write_signals_csv(const ComparePlan& p, const Overlay& o, const std::filesystem::path& file) {
  const std::vector<std::string> g = {p.found.setup.incident_gauge,
                                      p.found.setup.transmitted_gauge};
  CsvWriter w(
      file, {schema::compare_signals::time_s, g[0] + "_measured_strain", g[0] + "_simulated_strain",
             g[0] + "_simulated_raw_strain", g[1] + "_measured_strain", g[1] + "_simulated_strain",
             g[1] + "_simulated_raw_strain"});
  const auto& t = p.measured.time_s;
  for (std::size_t k = 0; k < t.size() && t[k] - o.offset_s <= o.t_sim_end; ++k)
    w.row({t[k], p.found.incident[k], o.incident[k], o.raw_incident[k], p.found.transmitted[k],
           o.transmitted[k], o.raw_transmitted[k]});
  w.close();
}

}  // namespace

ComparePlan plan_comparison(Scene scene, std::optional<double> striker_velocity_m_s) {
  const std::string file = scene.file.string();
  if (!scene.measurement)
    throw input_error(file, "measurement", "(missing)", "compare needs measured signals");
  if (scene.measurement->channels.empty())
    throw input_error(file, "measurement.channels", "(missing)", "compare needs measured signals");
  const TestRoles roles = test_roles(scene);
  if (!roles.striker || !roles.incident || *roles.striker >= *roles.incident)
    throw input_error(file, "specimen", "(missing or no striker)",
                      "compare needs a striker, an incident bar and a specimen");
  ComparePlan p;
  p.measured = read_gauge_signals(*scene.measurement, {});
  p.striker = *roles.striker;
  p.found = find_measured_pulses(scene, p.measured);
  if (striker_velocity_m_s &&
      !(*striker_velocity_m_s > 0 && *striker_velocity_m_s <= kMaxStrikerVelocity_m_s))
    throw input_error("--striker-velocity", "",
                      JsonValue::format(*striker_velocity_m_s, Dimension::kVelocity),
                      "must be in (0, " + format_double(kMaxStrikerVelocity_m_s) + " m/s]");
  p.scene = std::move(scene);
  p.warnings = p.measured.warnings;
  for (const auto& w : signal_warnings(p.measured)) p.warnings.push_back(w);
  p.warnings.insert(p.warnings.end(), p.found.warnings.begin(), p.found.warnings.end());
  set_striker_velocity(p, striker_velocity_m_s);
  extend_duration(p, *roles.incident);
  return p;
}

namespace {

// The clocks meet at the incident fronts' mean crossing time (docs/methods.md §9); a measured front
// with no sample between its 40 and 60 % levels does not say where in its sample interval it lies,
// so the clocks may be off by up to half of it. A pulse that changes within a few samples (a
// matched specimen's short reflected spike) may then compare worse by that alone: said where its
// NRMSE and the one half a sample's shift of the simulated pulse gives it both exceed kClockNrmse.
void warn_unresolved_clock(const ComparePlan& plan, const Overlay& o,
                           const std::vector<PulseComparison>& results,
                           std::vector<std::string>& warnings) {
  if (plan.found.incident_front_samples >= 1) return;
  for (std::size_t i = 0; i < results.size(); ++i) {
    const OverlaidPulse& p = o.pulses[i];
    const std::vector<double>& y = p.transmitted ? o.transmitted : o.incident;
    std::vector<double> half(y.size());  // y half a sample later, linearly
    for (std::size_t k = 0; k + 1 < y.size(); ++k) half[k] = 0.5 * (y[k] + y[k + 1]);
    if (!y.empty()) half.back() = y.back();
    const double shift = compare_pulse(y, half, plan.measured.dt_s, p.begin, p.end).nrmse;
    if (results[i].nrmse <= kClockNrmse || shift <= kClockNrmse) continue;
    warnings.push_back(
        "the measured incident pulse rises from 40 to 60 % of its plateau within "
        "one sample interval (" +
        format_double(plan.measured.dt_s * 1e6) +
        " us), so the clocks are placed to about half of it; a clock off by half a "
        "sample alone gives the " +
        p.name + " pulse an NRMSE of " + format_double(shift) + " (compared: " +
        format_double(results[i].nrmse) + "); record at a higher sample rate to compare it closer");
  }
}

}  // namespace

CompareOutcome compare_simulation(const ComparePlan& plan, const TimeSeries& simulated_gauges,
                                  bool dispersion, const SimulationFacts& simulation) {
  CompareOutcome c;
  const PulseOverlay overlay(plan.scene, plan.found, dispersion);
  c.overlay = overlay.overlay(plan.scene, simulated_gauges);
  const Overlay& o = c.overlay;
  c.warnings = plan.warnings;
  c.warnings.insert(c.warnings.end(), o.warnings.begin(), o.warnings.end());
  const double t_meas0 = plan.measured.time_s.front();
  for (const OverlaidPulse& p : o.pulses) {
    const bool tr = p.transmitted;
    PulseComparison r = compare_pulse(tr ? plan.found.transmitted : plan.found.incident,
                                      tr ? o.transmitted : o.incident, plan.measured.dt_s, p.begin,
                                      p.end, clipped_channel(plan.found, tr));
    r.gauge = p.gauge, r.pulse = p.name;
    r.window_start_s += t_meas0, r.window_end_s += t_meas0;
    c.results.push_back(r);
  }
  warn_unresolved_clock(plan, o, c.results, c.warnings);
  c.warnings.insert(c.warnings.end(), simulation.warnings.begin(), simulation.warnings.end());
  return c;
}

void write_comparison(const ComparePlan& plan, const CompareOutcome& outcome,
                      const TimeSeries& simulated_gauges, bool dispersion,
                      const SimulationFacts& simulation, const std::filesystem::path& dir) {
  const Overlay& o = outcome.overlay;
  write_comparison_csv(outcome.results, dir / schema::comparison::kFile);
  write_signals_csv(plan, o, dir / schema::compare_signals::kFile);
  nlohmann::json s;
  s["scene"] = plan.scene.file.string();
  s["striker_velocity_m_s"] = plan.scene.bars[plan.striker].velocity_m_s;  // + to the right
  s["striker_velocity_source"] = plan.velocity_source;
  s["scene_striker_velocity_m_s"] = plan.scene_velocity_m_s;
  s["measured_incident_plateau_strain"] = plan.found.incident_plateau;
  s["dispersion"] = dispersion;
  s["dispersion_note"] = dispersion ? "each simulated pulse moved through the Pochhammer-Chree "
                                      "dispersion of the distance it travelled from the impact face"
                                    : "none (1D signals as simulated)";
  s["clock_offset_s"] = o.offset_s;
  s["clock"] =
      "measured; simulation placed so that both incident pulses cross the levels between 40 and "
      "60 % of their plateaus at the same mean time";
  s["pulses"] = nlohmann::json::array();
  for (std::size_t i = 0; i < outcome.results.size(); ++i) {
    nlohmann::json p = outcome.results[i];
    p["distance_travelled_m"] = o.pulses[i].distance_m;
    s["pulses"].push_back(p);
  }
  const double t_sim0 = simulated_gauges.time_s.empty() ? 0.0 : simulated_gauges.time_s.front();
  s["simulation"] = {{"stable", simulation.stable},
                     {"wall_time_s", simulation.wall_time_s},
                     {"energy_error", simulation.energy_error}};
  s["simulation"]["duration_s"] = o.t_sim_end - t_sim0;
  s["simulation"]["duration_source"] =
      plan.extended_duration_s ? "extended to cover the measured pulses"
                               : (plan.scene.simulation.duration_s ? "scene" : "default");
  s["warnings"] = outcome.warnings;
  s["calibration"] = calibration_summary(plan.scene);
  s["version"] = kVersion;
  write_text_file(dir / "summary.json", s.dump(2) + "\n");
}

}  // namespace shpb
