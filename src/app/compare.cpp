// shpb compare SCENE.json -o DIR: simulate the scene and lay it over its measurement,
// pulse by pulse. Steps:
//  1. read the measured gauges; find the incident, reflected and transmitted pulses in them;
//  2. striker velocity: --striker-velocity, else measurement.striker_velocity, else inferred from
//     the measured incident plateau, v_bar = c0 ε_I and V = v_bar (Z_s + Z_b)/Z_s (docs/methods.md §4);
//  3. simulate; put the simulation (t = 0 at impact) on the measurement's clock by matching the
//     half-plateau crossings of the incident pulses;
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
#include "analysis/processing.hpp"
#include "analysis/pulse_window.hpp"
#include "app/commands.hpp"
#include "core/checked_write.hpp"
#include "core/csv_writer.hpp"
#include "core/error.hpp"
#include "core/json_value.hpp"
#include "core/output_folder.hpp"
#include "core/signal_gauges.hpp"
#include "dispersion/dispersion_table.hpp"
#include "dispersion/propagation.hpp"
#include "model/discretization.hpp"
#include "solver/simulation.hpp"
#include "version.hpp"

namespace shpb {
namespace {

// Each compared window reaches this fraction of the measured pulse's length beyond both ends,
// so that a shifted simulated pulse still lies inside it.
constexpr double kWindowMargin = 0.2;
// The striker velocity inferred from the measured plateau and the one used (given or the scene's)
// differing by more than this fraction: a wrong bridge factor, bar data or clipped signal.
constexpr double kVelocityMismatch = 0.1;
// A striker beyond this would yield any bar steel many times over (v_yield = 2 σ_y / (ρ c0) is
// ~100 m/s for maraging steel): not a split Hopkinson bar test.
constexpr double kMaxStrikerVelocity_m_s = 1000;
// An extended simulation runs this fraction longer than the measured pulses need (the clocks are
// matched on the incident pulse only after the run).
constexpr double kDurationMargin = 0.1;

// Linear interpolation of y on the uniform grid t0 + k·dt; 0 before the grid (the bars are at
// rest before impact), the last value after it.
double sample(const std::vector<double>& y, double t0, double dt, double t) {
  if (y.empty()) return 0;
  const double k = (t - t0) / dt;
  if (k <= 0) return k < -1 ? 0.0 : y.front() * (1 + k);
  const auto i = static_cast<std::size_t>(k);
  if (i + 1 >= y.size()) return y.back();
  const double f = k - static_cast<double>(i);
  return y[i] * (1 - f) + y[i + 1] * f;
}

struct Pulse {
  std::string gauge, name;
  std::size_t begin = 0, end = 0;  // compared window on the measured grid
  double distance_m = 0;           // travelled from the impact face to the gauge
  const BarWaveguide* waveguide = nullptr;
};

// Fractional sample where |x − level| first reaches half of the pulse's plateau.
double half_plateau_crossing(const std::vector<double>& x, double level, const PulseWindow& w) {
  const double half = 0.5 * std::abs(plateau_level(x, w.onset, w.end, w.sign) - level);
  for (std::size_t i = std::max<std::size_t>(w.onset, 1); i < w.end; ++i) {
    const double a = std::abs(x[i - 1] - level), b = std::abs(x[i] - level);
    if (b >= half) return static_cast<double>(i - 1) + (b != a ? (half - a) / (b - a) : 1.0);
  }
  return static_cast<double>(w.onset);
}

std::size_t widen(std::size_t i, double by, bool down, std::size_t n) {
  const auto d = static_cast<std::size_t>(by);
  if (down) return i > d ? i - d : 0;
  return std::min(n, i + d);
}

}  // namespace

int run_compare(const CompareArgs& args) {
  Scene scene = read_scene(args.scene);  // InputError → exit 2, nothing written
  apply_overrides(args.overrides, scene);
  const std::string file = scene.file.string();
  if (!scene.measurement)
    throw input_error(file, "measurement", "(missing)", "compare needs measured signals");
  if (scene.measurement->channels.empty())
    throw input_error(file, "measurement.channels", "(missing)", "compare needs measured signals");
  if (!scene.specimen || *scene.specimen < 2)
    throw input_error(file, "specimen", "(missing or no striker)",
                      "compare needs a striker, an incident bar and a specimen");
  const GaugeSignals measured = read_gauge_signals(*scene.measurement, {});
  const KolskySetup setup = resolve_setup(scene, measured.gauges);
  const std::size_t incident_bar = *scene.specimen - 1, striker = incident_bar - 1;

  // 1. The measured pulses.
  const std::vector<double>& m_inc = *measured.find(setup.incident_gauge);
  const std::vector<double>& m_tr = *measured.find(setup.transmitted_gauge);
  const std::size_t n = measured.time_s.size();
  const Baseline base_inc = estimate_baseline(m_inc), base_tr = estimate_baseline(m_tr);
  const auto w_inc = find_first_pulse(m_inc, base_inc);
  if (!w_inc)
    throw input_error(file, "measurement", setup.incident_gauge,
                      "no incident pulse above the noise in the measured signal");
  const auto w_ref = find_first_pulse(m_inc, base_inc, w_inc->end);
  const auto w_tr = find_first_pulse(m_tr, base_tr);

  // 2. Striker velocity.
  if (args.striker_velocity &&
      !(*args.striker_velocity > 0 && *args.striker_velocity <= kMaxStrikerVelocity_m_s))
    throw input_error("--striker-velocity", "",
                      JsonValue::format(*args.striker_velocity, Dimension::kVelocity),
                      "must be in (0, " + format_double(kMaxStrikerVelocity_m_s) + " m/s]");
  const double plateau =
      std::abs(plateau_level(m_inc, w_inc->onset, w_inc->end, w_inc->sign) - base_inc.level);
  const double z_s = scene.bars[striker].impedance_kg_s(),
               z_b = scene.bars[incident_bar].impedance_kg_s();
  const double inferred_velocity = setup.front.c0_m_s * plateau * (z_s + z_b) / z_s;
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
  const double scene_velocity = scene.bars[striker].velocity_m_s;
  scene.bars[striker].velocity_m_s = velocity;
  std::vector<std::string> warnings = measured.warnings;
  for (const auto& w : signal_warnings(measured)) warnings.push_back(w);
  for (const double other : {velocity, scene_velocity})
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
    std::size_t last = w_inc->end;
    for (const auto& w : {w_inc, w_ref, w_tr})
      if (w)
        last = std::max(last, widen(w->end, static_cast<double>(w->end - w->onset) * kWindowMargin,
                                    false, n - 1));
    const double arrival =
        (velocity > 0 ? scene.bars[striker].gap_m / velocity : 0.0) +
        (scene.bars[incident_bar].length_m - setup.incident_distance_m) / setup.front.c0_m_s;
    const double needed = (arrival + measured.time_s[last] - measured.time_s[w_inc->onset]) *
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
  const double dt_sim = 1.0 / scene.simulation.sample_rate_Hz;
  const std::vector<double>& s_inc = sim.gauges.column(setup.incident_gauge);
  const std::vector<double>& s_tr = sim.gauges.column(setup.transmitted_gauge);
  const double t_sim0 = sim.gauges.time_s.empty() ? 0.0 : sim.gauges.time_s.front();
  const Baseline base_sim = estimate_baseline(s_inc);
  const auto w_sim = find_first_pulse(s_inc, base_sim);
  if (!w_sim)
    throw NumericalError(file + ": simulation: no incident pulse at gauge " + setup.incident_gauge);
  const double t_meas0 = measured.time_s.front(), dt = measured.dt_s;
  // The two clocks meet where each incident pulse first reaches half its plateau: a time that
  // does not depend on how steep the front is (the trigger time of a measurement is unknown).
  const double half_meas = half_plateau_crossing(m_inc, base_inc.level, *w_inc);
  const double half_sim = half_plateau_crossing(s_inc, base_sim.level, *w_sim);
  const double offset = (t_meas0 + half_meas * dt) - (t_sim0 + half_sim * dt_sim);
  const double t_sim_end = t_sim0 + static_cast<double>(s_inc.size() - 1) * dt_sim;

  // 4. Pulses and the distance each travelled before reaching its gauge.
  const double l_inc = scene.bars[incident_bar].length_m;
  std::vector<Pulse> pulses;
  auto add = [&](const std::string& gauge, const std::string& name, const PulseWindow& w,
                 double distance, const BarWaveguide& guide) {
    const double len = static_cast<double>(w.end - w.onset) * kWindowMargin;
    Pulse p{gauge, name, widen(w.onset, len, true, n), widen(w.end, len, false, n), distance,
            &guide};
    // Only where the simulation exists; said when that cuts the pulse.
    const auto last = static_cast<std::size_t>(
        std::max(0.0, (t_sim_end + offset - t_meas0) / dt));
    if (p.end > last) {
      char msg[400];
      std::snprintf(msg, sizeof msg,
                    "the simulation ends (%.4g s on the measured clock) before the %s pulse has "
                    "passed gauge \"%s\" (its window ends at %.4g s): compared on %.0f %% of its "
                    "window only; set simulation.duration to at least %.3g s",
                    t_sim_end + offset, name.c_str(), gauge.c_str(), measured.time_s[p.end - 1],
                    100.0 * static_cast<double>(std::max(last, p.begin) - p.begin) /
                        static_cast<double>(p.end - p.begin),
                    measured.time_s[p.end - 1] - offset - t_sim0);
      warnings.push_back(msg);
      p.end = last;
    }
    if (p.begin + 2 < p.end) pulses.push_back(p);
  };
  add(setup.incident_gauge, "incident", *w_inc, l_inc - setup.incident_distance_m,
      setup.front_waveguide);
  if (w_ref)
    add(setup.incident_gauge, "reflected", *w_ref, l_inc + setup.incident_distance_m,
        setup.front_waveguide);
  if (w_tr)
    add(setup.transmitted_gauge, "transmitted", *w_tr, l_inc + setup.transmitted_distance_m,
        setup.back_waveguide);

  // Simulated signals on the measured clock: raw (1D) and, per pulse, dispersed.
  auto on_measured_clock = [&](const std::vector<double>& y, double advance_s) {
    std::vector<double> r(n);
    for (std::size_t k = 0; k < n; ++k)
      r[k] = sample(y, t_sim0, dt_sim, measured.time_s[k] - offset + advance_s);
    return r;
  };
  const std::vector<double> raw_inc = on_measured_clock(s_inc, 0), raw_tr = on_measured_clock(s_tr, 0);
  std::vector<double> sim_inc = raw_inc, sim_tr = raw_tr;
  std::optional<DispersionTable> front_table, back_table;
  if (args.dispersion) {
    // Tabulated up to the default cut-off the corrections below use.
    front_table.emplace(
        DispersionTable::up_to(setup.front_waveguide.poisson, kDefaultCutoffFaOverC0));
    back_table.emplace(
        DispersionTable::up_to(setup.back_waveguide.poisson, kDefaultCutoffFaOverC0));
    // The incident gauge carries two pulses: split its record half-way between them.
    const std::size_t split =
        w_ref ? (w_inc->end + w_ref->onset) / 2 : n;
    for (const Pulse& p : pulses) {
      const bool front = p.waveguide == &setup.front_waveguide;
      Propagator prop(front ? *front_table : *back_table, *p.waveguide, PropagationOptions{});
      // Zeros after the record leave room for the delay d/c(f) (the output keeps the input's
      // length); ×1.25 covers the slowest phase velocity below the cut-off.
      std::vector<double> src = p.name == "transmitted" ? s_tr : s_inc;
      src.resize(src.size() + static_cast<std::size_t>(
                                  1.25 * p.distance_m / p.waveguide->c0_m_s / dt_sim) + 1,
                 0.0);
      // Moving by Δz delays by Δz/c(f); the 1D model already delayed by Δz/c0: advance by that.
      const std::vector<double> moved =
          on_measured_clock(prop.propagate(src, dt_sim, p.distance_m), p.distance_m / p.waveguide->c0_m_s);
      std::vector<double>& dst = p.name == "transmitted" ? sim_tr : sim_inc;
      const std::size_t from = p.name == "reflected" ? split : 0;
      const std::size_t to = p.name == "incident" ? split : n;
      std::copy(moved.begin() + static_cast<long>(from), moved.begin() + static_cast<long>(to),
                dst.begin() + static_cast<long>(from));
    }
  }

  // 5. Compare.
  std::vector<PulseComparison> results;
  for (const Pulse& p : pulses) {
    const bool tr = p.gauge == setup.transmitted_gauge && p.name == "transmitted";
    PulseComparison c =
        compare_pulse(tr ? m_tr : m_inc, tr ? sim_tr : sim_inc, dt, p.begin, p.end);
    c.gauge = p.gauge, c.pulse = p.name;
    c.window_start_s += t_meas0, c.window_end_s += t_meas0;
    results.push_back(c);
  }

  {
    std::ostringstream csv;
    csv << "gauge,pulse,window_start_s,window_end_s,arrival_shift_s,peak_ratio,plateau_ratio,duration_ratio,"
           "rise_time_measured_s,rise_time_simulated_s,nrmse,correlation\n";
    for (const auto& c : results)
      csv << c.gauge << ',' << c.pulse << ',' << format_double(c.window_start_s) << ','
          << format_double(c.window_end_s) << ',' << format_double(c.arrival_shift_s) << ','
          << format_double(c.peak_ratio) << ',' << format_double(c.plateau_ratio) << ',' << format_double(c.duration_ratio) << ','
          << format_double(c.rise_time_measured_s) << ','
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
      w.row({measured.time_s[k], m_inc[k], sim_inc[k], raw_inc[k], m_tr[k], sim_tr[k],
             raw_tr[k]});
    w.close();
  }
  nlohmann::json s;
  s["scene"] = file;
  s["striker_velocity_m_s"] = velocity;
  s["striker_velocity_source"] = velocity_source;
  s["scene_striker_velocity_m_s"] = scene_velocity;
  s["measured_incident_plateau_strain"] = plateau;
  s["dispersion"] = args.dispersion;
  s["dispersion_note"] = args.dispersion
                             ? "each simulated pulse moved through the Pochhammer-Chree "
                               "dispersion of the distance it travelled from the impact face"
                             : "none (1D signals as simulated)";
  s["clock_offset_s"] = offset;
  s["clock"] = "measured; simulation placed so that both incident pulses reach half their "
               "plateau at the same time";
  s["pulses"] = nlohmann::json::array();
  for (std::size_t i = 0; i < results.size(); ++i) {
    const auto& c = results[i];
    s["pulses"].push_back({{"gauge", c.gauge},
                           {"pulse", c.pulse},
                           {"distance_travelled_m", pulses[i].distance_m},
                           {"arrival_shift_s", c.arrival_shift_s},
                           {"peak_ratio", c.peak_ratio},
                           {"plateau_ratio", c.plateau_ratio},
                           {"duration_ratio", c.duration_ratio},
                           {"nrmse", c.nrmse},
                           {"correlation", c.correlation}});
  }
  s["simulation"] = {{"stable", sim.stable},
                     {"wall_time_s", sim.wall_time_s},
                     {"energy_error", sim.energy_error}};
  s["simulation"]["duration_s"] = t_sim_end - t_sim0;
  s["simulation"]["duration_source"] =
      extended_duration ? "extended to cover the measured pulses"
                        : (scene.simulation.duration_s ? "scene" : "default");
  warnings.insert(warnings.end(), sim.warnings.begin(), sim.warnings.end());
  s["warnings"] = warnings;
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
  for (const auto& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  if (!args.overrides.quiet) {
    std::fprintf(stderr, "striker %.4g m/s (%s); dispersion %s\n", velocity,
                 velocity_source.c_str(), args.dispersion ? "applied" : "off");
    for (const auto& c : results)
      std::fprintf(stderr,
                   "%-12s %-12s shift %+7.2f us  peak ratio %.3f  plateau ratio %.3f  duration ratio %.3f  "
                   "NRMSE %.3f  r %.3f\n",
                   c.gauge.c_str(), c.pulse.c_str(), c.arrival_shift_s * 1e6, c.peak_ratio, c.plateau_ratio,
                   c.duration_ratio, c.nrmse, c.correlation);
    std::fprintf(stderr, "wrote %s\n", out.final_path().string().c_str());
  }
  return 0;
}

}  // namespace shpb
