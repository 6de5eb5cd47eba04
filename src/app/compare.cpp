// shpb compare SCENE.json -o DIR: simulate the scene and lay it over its measurement,
// pulse by pulse. Steps:
//  1. read the measured gauges; find the incident, reflected and transmitted pulses in them;
//  2. striker velocity: --striker-velocity, else measurement.striker_velocity, else inferred from
//     the measured incident plateau, v_bar = c0 ε_I and V = v_bar (Z_s + Z_b)/Z_s (docs/methods.md
//     §4);
//  3. simulate; put the simulation (t = 0 at impact) on the measurement's clock by matching the
//     incident pulses' front times (analysis/pulse_overlay.hpp);
//  4. a 1D bar does not disperse and a real one does: each simulated pulse is moved through the
//     Pochhammer–Chree dispersion of the distance it has travelled from the impact face (minus
//     the non-dispersive delay the 1D model already has), docs/methods.md §5;
//  5. compare in windows around the measured pulses (analysis/comparison.hpp).
// Writes comparison.csv, signals.csv (measured, simulated, simulated without dispersion, on the
// measured clock), summary.json, and the simulation's own files in simulation/.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/comparison.hpp"
#include "analysis/gauge_signals.hpp"
#include "analysis/processing.hpp"
#include "analysis/pulse_overlay.hpp"
#include "analysis/pulse_window.hpp"
#include "app/commands.hpp"
#include "core/checked_write.hpp"
#include "core/csv_writer.hpp"
#include "core/error.hpp"
#include "core/json_value.hpp"
#include "core/output_folder.hpp"
#include "model/calibration.hpp"
#include "model/discretization.hpp"
#include "model/test_setup.hpp"
#include "model/wave_travel.hpp"
#include "solver/simulation.hpp"
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
// A striker beyond this would yield any bar steel many times over (v_yield = 2 σ_y / (ρ c0) is
// ~100 m/s for maraging steel): not a split Hopkinson bar test.
constexpr double kMaxStrikerVelocity_m_s = 1000;
// An extended simulation runs this fraction longer than the measured pulses need (the clocks are
// matched on the incident pulse only after the run).
constexpr double kDurationMargin = 0.1;

}  // namespace

int run_compare(const CompareArgs& args) {
  Scene scene = read_scene(args.scene);  // InputError → exit 2, nothing written
  apply_overrides(args.overrides, scene);
  const std::string file = scene.file.string();
  if (!scene.measurement)
    throw input_error(file, "measurement", "(missing)", "compare needs measured signals");
  if (scene.measurement->channels.empty())
    throw input_error(file, "measurement.channels", "(missing)", "compare needs measured signals");
  const TestRoles roles = test_roles(scene);
  if (!roles.striker || !roles.incident || *roles.striker >= *roles.incident)
    throw input_error(file, "specimen", "(missing or no striker)",
                      "compare needs a striker, an incident bar and a specimen");
  const GaugeSignals measured = read_gauge_signals(*scene.measurement, {});
  const std::size_t incident_bar = *roles.incident, striker = *roles.striker;

  // 1. The measured pulses.
  const MeasuredPulses found = find_measured_pulses(scene, measured);
  const KolskySetup& setup = found.setup;
  const std::vector<double>& m_inc = found.incident;
  const std::vector<double>& m_tr = found.transmitted;
  const std::size_t n = measured.time_s.size();

  // 2. Striker velocity.
  if (args.striker_velocity &&
      !(*args.striker_velocity > 0 && *args.striker_velocity <= kMaxStrikerVelocity_m_s))
    throw input_error("--striker-velocity", "",
                      JsonValue::format(*args.striker_velocity, Dimension::kVelocity),
                      "must be in (0, " + format_double(kMaxStrikerVelocity_m_s) + " m/s]");
  const double plateau = found.incident_plateau;
  const double inferred_velocity = striker_velocity_from_plateau(found);
  std::string velocity_source;
  double velocity = 0;
  if (args.striker_velocity) {
    velocity = *args.striker_velocity, velocity_source = "given (--striker-velocity)";
  } else if (scene.measurement->striker_velocity_m_s) {
    velocity = *scene.measurement->striker_velocity_m_s;
    velocity_source = "scene (measurement.striker_velocity)";
  } else {
    velocity = inferred_velocity;
    velocity_source = "inferred from the measured incident plateau";
  }
  // Launched the way the scene's striker moves (a tension striker pulls: − to the left).
  const double scene_velocity = scene.bars[striker].velocity_m_s;
  scene.bars[striker].velocity_m_s = striker_direction(scene) * velocity;
  std::vector<std::string> warnings = measured.warnings;
  for (const auto& w : signal_warnings(measured)) warnings.push_back(w);
  for (const double other : {velocity, std::abs(scene_velocity)})
    if (other > 0 && std::abs(inferred_velocity - other) > kVelocityMismatch * other) {
      warnings.push_back("the striker velocity inferred from the measured incident plateau, " +
                         format_double(inferred_velocity) + " m/s, differs from the " +
                         (other == velocity ? "one used" : "scene's") + ", " +
                         format_double(other) + " m/s, by more than " +
                         format_double(kVelocityMismatch * 100) +
                         " %: check the bridge factors, the bar data and the signals (clipping)");
      break;
    }

  // The simulation must last until the measured pulses have passed their gauges: unless the scene
  // sets a duration, the default is extended to the end of the last compared window, put on the
  // simulation's clock by the incident pulse (its gauge is reached (l - d_I)/c0 after impact,
  // after the striker has closed its gap).
  std::optional<double> extended_duration;
  if (!scene.simulation.duration_s) {
    const std::size_t last = last_compared_sample(found);
    const double arrival =
        (velocity > 0 ? scene.bars[striker].gap_m / velocity : 0.0) +
        travel_time_s(scene, incident_bar, 0, incident_bar,
                      scene.bars[incident_bar].length_m - setup.incident_distance_m);
    const double needed =
        (arrival + measured.time_s[last] - measured.time_s[found.incident_window.onset]) *
        (1 + kDurationMargin);
    if (needed > default_duration_s(scene))
      scene.simulation.duration_s = extended_duration = needed;
  }

  OutputFolder out(args.output, "compare",
                   scene_inputs(scene));  // every input checked: from here on results are written

  // 3. Simulate.
  SimulationOptions options;
  options.cancel = [] { return interrupted(); };
  const SimulationResult sim = simulate(scene, options);
  std::filesystem::create_directories(out.path() / "simulation");
  write_simulation_outputs(sim, scene, out.path() / "simulation");
  // 4. On the measured clock, each pulse dispersed over the distance it travelled.
  const PulseOverlay overlay(scene, found, args.dispersion);
  const Overlay o = overlay.overlay(scene, sim.gauges);
  const double offset = o.offset_s, t_sim_end = o.t_sim_end, dt = measured.dt_s,
               t_meas0 = measured.time_s.front();
  const double t_sim0 = sim.gauges.time_s.empty() ? 0.0 : sim.gauges.time_s.front();
  const std::vector<OverlaidPulse>& pulses = o.pulses;
  const std::vector<double>& raw_inc = o.raw_incident;
  const std::vector<double>& raw_tr = o.raw_transmitted;
  const std::vector<double>& sim_inc = o.incident;
  const std::vector<double>& sim_tr = o.transmitted;
  warnings.insert(warnings.end(), o.warnings.begin(), o.warnings.end());

  // 5. Compare.
  std::vector<PulseComparison> results;
  for (const OverlaidPulse& p : pulses) {
    const bool tr = p.transmitted;
    PulseComparison c = compare_pulse(tr ? m_tr : m_inc, tr ? sim_tr : sim_inc, dt, p.begin, p.end);
    c.gauge = p.gauge, c.pulse = p.name;
    c.window_start_s += t_meas0, c.window_end_s += t_meas0;
    results.push_back(c);
  }

  {
    std::ostringstream csv;
    csv << "gauge,pulse,window_start_s,window_end_s,arrival_shift_s,peak_ratio,plateau_ratio,"
           "duration_ratio,"
           "rise_time_measured_s,rise_time_simulated_s,nrmse,correlation\n";
    for (const auto& c : results)
      csv << c.gauge << ',' << c.pulse << ',' << format_double(c.window_start_s) << ','
          << format_double(c.window_end_s) << ',' << format_double(c.arrival_shift_s) << ','
          << format_double(c.peak_ratio) << ',' << format_double(c.plateau_ratio) << ','
          << format_double(c.duration_ratio) << ',' << format_double(c.rise_time_measured_s) << ','
          << format_double(c.rise_time_simulated_s) << ',' << format_double(c.nrmse) << ','
          << format_double(c.correlation) << '\n';
    write_text_file(out.file("comparison.csv"), csv.str());
  }
  {
    const std::vector<std::string> g = {setup.incident_gauge, setup.transmitted_gauge};
    CsvWriter w(out.file("signals.csv"),
                {"time_s", g[0] + "_measured_strain", g[0] + "_simulated_strain",
                 g[0] + "_simulated_raw_strain", g[1] + "_measured_strain",
                 g[1] + "_simulated_strain", g[1] + "_simulated_raw_strain"});
    for (std::size_t k = 0; k < n && measured.time_s[k] - offset <= t_sim_end; ++k)
      w.row({measured.time_s[k], m_inc[k], sim_inc[k], raw_inc[k], m_tr[k], sim_tr[k], raw_tr[k]});
    w.close();
  }
  nlohmann::json s;
  s["scene"] = file;
  s["striker_velocity_m_s"] = scene.bars[striker].velocity_m_s;  // as launched, + to the right
  s["striker_velocity_source"] = velocity_source;
  s["scene_striker_velocity_m_s"] = scene_velocity;
  s["measured_incident_plateau_strain"] = plateau;
  s["dispersion"] = args.dispersion;
  s["dispersion_note"] = args.dispersion
                             ? "each simulated pulse moved through the Pochhammer-Chree "
                               "dispersion of the distance it travelled from the impact face"
                             : "none (1D signals as simulated)";
  s["clock_offset_s"] = offset;
  s["clock"] =
      "measured; simulation placed so that both incident pulses cross the levels between 40 and "
      "60 % of their plateaus at the same mean time";
  s["pulses"] = nlohmann::json::array();
  for (std::size_t i = 0; i < results.size(); ++i) {
    nlohmann::json p = results[i];
    p["distance_travelled_m"] = pulses[i].distance_m;
    s["pulses"].push_back(p);
  }
  s["simulation"] = {
      {"stable", sim.stable}, {"wall_time_s", sim.wall_time_s}, {"energy_error", sim.energy_error}};
  s["simulation"]["duration_s"] = t_sim_end - t_sim0;
  s["simulation"]["duration_source"] = extended_duration
                                           ? "extended to cover the measured pulses"
                                           : (scene.simulation.duration_s ? "scene" : "default");
  warnings.insert(warnings.end(), sim.warnings.begin(), sim.warnings.end());
  s["warnings"] = warnings;
  s["calibration"] = calibration_summary(scene);
  s["version"] = kVersion;
  write_text_file(out.file("summary.json"), s.dump(2) + "\n");
  out.commit();
  // What is implausible is said even with --quiet (which silences progress only).
  for (const auto& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());

  if (!sim.stable) {
    std::fprintf(stderr, "error: %s: %s (outputs up to then written to %s)\n", file.c_str(),
                 sim.failure.c_str(), out.final_path().string().c_str());
    return 3;
  }
  if (!args.overrides.quiet) {
    std::fprintf(stderr, "striker %.4g m/s (%s); dispersion %s\n", velocity,
                 velocity_source.c_str(), args.dispersion ? "applied" : "off");
    for (const auto& c : results)
      std::fprintf(
          stderr,
          "%-12s %-12s shift %+7.2f us  peak ratio %.3f  plateau ratio %.3f  duration ratio %.3f  "
          "NRMSE %.3f  r %.3f\n",
          c.gauge.c_str(), c.pulse.c_str(), c.arrival_shift_s * 1e6, c.peak_ratio, c.plateau_ratio,
          c.duration_ratio, c.nrmse, c.correlation);
    std::fprintf(stderr, "wrote %s\n", out.final_path().string().c_str());
  }
  return 0;
}

}  // namespace shpb
