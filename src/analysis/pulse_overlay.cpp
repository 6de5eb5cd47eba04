#include "analysis/pulse_overlay.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "core/interpolation.hpp"
#include "dispersion/propagation.hpp"

namespace shpb {
namespace {

// Each compared window reaches this fraction of the measured pulse's length beyond both ends,
// so that a shifted simulated pulse still lies inside it.
constexpr double kWindowMargin = 0.2;

// Linear interpolation of y on the uniform grid t0 + k·dt; 0 before the grid (the bars are at
// rest before impact), the last value after it.
double sample(const std::vector<double>& y, double t0, double dt, double t) {
  if (y.empty()) return 0;
  return sample_at(y, (t - t0) / dt, 0.0, y.back());
}

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

MeasuredPulses find_measured_pulses(const Scene& scene, const GaugeSignals& signals) {
  MeasuredPulses m;
  m.setup = resolve_setup(scene, signals.gauges);
  m.time_s = signals.time_s;
  m.dt_s = signals.dt_s;
  m.incident = *signals.find(m.setup.incident_gauge);
  m.transmitted = *signals.find(m.setup.transmitted_gauge);
  m.incident_baseline = estimate_baseline(m.incident);
  m.transmitted_baseline = estimate_baseline(m.transmitted);
  const auto w_inc = find_first_pulse(m.incident, m.incident_baseline);
  if (!w_inc)
    throw input_error(scene.file.string(), "measurement", m.setup.incident_gauge,
                      "no incident pulse above the noise in the measured signal");
  m.incident_window = *w_inc;
  m.reflected_window = find_first_pulse(m.incident, m.incident_baseline, w_inc->end);
  m.transmitted_window = find_first_pulse(m.transmitted, m.transmitted_baseline);
  m.incident_plateau = std::abs(plateau_level(m.incident, w_inc->onset, w_inc->end, w_inc->sign) -
                                m.incident_baseline.level);
  return m;
}

std::size_t last_compared_sample(const MeasuredPulses& m) {
  const std::size_t n = m.time_s.size();
  std::size_t last = m.incident_window.end;
  for (const auto& w :
       {std::optional<PulseWindow>(m.incident_window), m.reflected_window, m.transmitted_window})
    if (w)
      last = std::max(last, widen(w->end, static_cast<double>(w->end - w->onset) * kWindowMargin,
                                  false, n - 1));
  return last;
}

double striker_velocity_from_plateau(const Scene& scene, const MeasuredPulses& measured) {
  const std::size_t incident_bar = *scene.specimen - 1, striker = incident_bar - 1;
  const double z_s = scene.bars[striker].impedance_kg_s(),
               z_b = scene.bars[incident_bar].impedance_kg_s();
  return measured.setup.front.c0_m_s * measured.incident_plateau * (z_s + z_b) / z_s;
}

PulseOverlay::PulseOverlay(const Scene&, MeasuredPulses measured, bool dispersion)
    : measured_(std::move(measured)) {
  if (dispersion) {
    // Tabulated up to the default cut-off the propagations below use.
    front_table_.emplace(
        DispersionTable::up_to(measured_.setup.front_waveguide.poisson, kDefaultCutoffFaOverC0));
    back_table_.emplace(
        DispersionTable::up_to(measured_.setup.back_waveguide.poisson, kDefaultCutoffFaOverC0));
  }
}

Overlay PulseOverlay::overlay(const Scene& scene, const SimulationResult& sim,
                              double shift_s) const {
  const MeasuredPulses& m = measured_;
  const KolskySetup& setup = m.setup;
  const std::string file = scene.file.string();
  const std::size_t incident_bar = *scene.specimen - 1;
  const std::size_t n = m.time_s.size();
  const double dt_sim = 1.0 / scene.simulation.sample_rate_Hz;
  const std::vector<double>& s_inc = sim.gauges.column(setup.incident_gauge);
  const std::vector<double>& s_tr = sim.gauges.column(setup.transmitted_gauge);
  const double t_sim0 = sim.gauges.time_s.empty() ? 0.0 : sim.gauges.time_s.front();
  const Baseline base_sim = estimate_baseline(s_inc);
  const auto w_sim = find_first_pulse(s_inc, base_sim);
  if (!w_sim)
    throw NumericalError(file + ": simulation: no incident pulse at gauge " + setup.incident_gauge);
  const double t_meas0 = m.time_s.front(), dt = m.dt_s;
  Overlay o;
  // The two clocks meet where each incident pulse first reaches half its plateau: a time that
  // does not depend on how steep the front is (the trigger time of a measurement is unknown).
  const double half_meas =
      half_plateau_crossing(m.incident, m.incident_baseline.level, m.incident_window);
  const double half_sim = half_plateau_crossing(s_inc, base_sim.level, *w_sim);
  o.offset_s = (t_meas0 + half_meas * dt) - (t_sim0 + half_sim * dt_sim) + shift_s;
  o.t_sim_end = t_sim0 + static_cast<double>(s_inc.size() - 1) * dt_sim;

  // Pulses and the distance each travelled before reaching its gauge.
  const double l_inc = scene.bars[incident_bar].length_m;
  auto add = [&](const std::string& gauge, const std::string& name, const PulseWindow& w,
                 double distance, bool transmitted) {
    const double len = static_cast<double>(w.end - w.onset) * kWindowMargin;
    OverlaidPulse p{gauge,    name,       widen(w.onset, len, true, n), widen(w.end, len, false, n),
                    distance, transmitted};
    // Only where the simulation exists; said when that cuts the pulse.
    const auto last =
        static_cast<std::size_t>(std::max(0.0, (o.t_sim_end + o.offset_s - t_meas0) / dt));
    if (p.end > last) {
      char msg[400];
      std::snprintf(msg, sizeof msg,
                    "the simulation ends (%.4g s on the measured clock) before the %s pulse has "
                    "passed gauge \"%s\" (its window ends at %.4g s): compared on %.0f %% of its "
                    "window only; set simulation.duration to at least %.3g s",
                    o.t_sim_end + o.offset_s, name.c_str(), gauge.c_str(), m.time_s[p.end - 1],
                    100.0 * static_cast<double>(std::max(last, p.begin) - p.begin) /
                        static_cast<double>(p.end - p.begin),
                    m.time_s[p.end - 1] - o.offset_s - t_sim0);
      o.warnings.push_back(msg);
      p.end = last;
    }
    if (p.begin + 2 < p.end) o.pulses.push_back(p);
  };
  add(setup.incident_gauge, "incident", m.incident_window, l_inc - setup.incident_distance_m,
      false);
  if (m.reflected_window)
    add(setup.incident_gauge, "reflected", *m.reflected_window, l_inc + setup.incident_distance_m,
        false);
  if (m.transmitted_window)
    add(setup.transmitted_gauge, "transmitted", *m.transmitted_window,
        l_inc + setup.transmitted_distance_m, true);

  // Simulated signals on the measured clock: raw (1D) and, per pulse, dispersed.
  auto on_measured_clock = [&](const std::vector<double>& y, double advance_s) {
    std::vector<double> r(n);
    for (std::size_t k = 0; k < n; ++k)
      r[k] = sample(y, t_sim0, dt_sim, m.time_s[k] - o.offset_s + advance_s);
    return r;
  };
  o.raw_incident = on_measured_clock(s_inc, 0);
  o.raw_transmitted = on_measured_clock(s_tr, 0);
  o.incident = o.raw_incident;
  o.transmitted = o.raw_transmitted;
  if (!dispersion()) return o;
  // The incident gauge carries two pulses: split its record half-way between them.
  const std::size_t split =
      m.reflected_window ? (m.incident_window.end + m.reflected_window->onset) / 2 : n;
  for (const OverlaidPulse& p : o.pulses) {
    const BarWaveguide& guide = p.transmitted ? setup.back_waveguide : setup.front_waveguide;
    Propagator prop(p.transmitted ? *back_table_ : *front_table_, guide, PropagationOptions{});
    // Zeros after the record leave room for the delay d/c(f) (the output keeps the input's
    // length); ×1.25 covers the slowest phase velocity below the cut-off.
    std::vector<double> src = p.transmitted ? s_tr : s_inc;
    src.resize(
        src.size() + static_cast<std::size_t>(1.25 * p.distance_m / guide.c0_m_s / dt_sim) + 1,
        0.0);
    // Moving by Δz delays by Δz/c(f); the 1D model already delayed by Δz/c0: advance by that.
    const std::vector<double> moved =
        on_measured_clock(prop.propagate(src, dt_sim, p.distance_m), p.distance_m / guide.c0_m_s);
    std::vector<double>& dst = p.transmitted ? o.transmitted : o.incident;
    const std::size_t from = p.name == "reflected" ? split : 0;
    const std::size_t to = p.name == "incident" ? split : n;
    std::copy(moved.begin() + static_cast<long>(from), moved.begin() + static_cast<long>(to),
              dst.begin() + static_cast<long>(from));
  }
  return o;
}

}  // namespace shpb
