#include "analysis/pulse_overlay.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>

#include "analysis/message_text.hpp"
#include "core/error.hpp"
#include "core/interpolation.hpp"
#include "core/median.hpp"
#include "core/number_format.hpp"
#include "dispersion/propagation.hpp"

namespace shpb {
namespace {

// Each compared window reaches this fraction of the measured pulse's length beyond both ends,
// so that a shifted simulated pulse still lies inside it.
constexpr double kWindowMargin = 0.2;
// A reflected pulse detected over less than this fraction of the incident pulse's length has lost
// its tail in the rest band (report_missing_pulses).
constexpr double kShortReflected = 0.5;

// Linear interpolation of y on the uniform grid t0 + k·dt; 0 before the grid (the bars are at
// rest before impact), the last value after it.
double sample(const std::vector<double>& y, double t0, double dt, double t) {
  if (y.empty()) return 0;
  return sample_at(y, (t - t0) / dt, 0.0, y.back());
}

// The incident front's time, in fractional samples: the mean, over the levels from kFrontLow to
// kFrontHigh of the pulse's plateau, of the time the pulse reaches that level. With u the signal as
// a fraction of the plateau clipped to [a, b] and linear between samples, over a span [t0, t1] that
// starts below a and ends on the plateau,
//   T = t1 − ∫ (u − a) dt / (b − a),
// which is the mean crossing time for a monotone front and, unlike one crossing, averages the
// record noise over every sample between the two levels (a step at τ gives τ; a front symmetric
// about its half-plateau crossing that crossing, whatever its steepness). The band is narrow
// because measured and simulated fronts differ in shape: on the LANL copper record a 20–80 % band
// moves the clock by 0.2 µs against the half-plateau crossing, 40–60 % by 0.03 µs, while the
// synthetic fit's estimates scatter as their standard errors say from 40–60 % on (docs/methods.md
// §9, docs/validation.md "shpb fit").
constexpr double kFrontLow = 0.4, kFrontHigh = 0.6;

// ∫₀¹ clip(u0 + (u1 − u0) s, a, b) ds, exact: piecewise linear between the crossings of a and b.
double clipped_segment(double u0, double u1, double a, double b) {
  // The crossings of a and b inside (0, 1), in order.
  double sa = u1 != u0 ? (a - u0) / (u1 - u0) : -1, sb = u1 != u0 ? (b - u0) / (u1 - u0) : -1;
  if (sa > sb) std::swap(sa, sb);
  const double cuts[4] = {0, std::clamp(sa, 0.0, 1.0), std::clamp(sb, 0.0, 1.0), 1};
  double sum = 0;
  for (int k = 0; k < 3; ++k) {
    const double mid = 0.5 * (cuts[k] + cuts[k + 1]);
    sum += (cuts[k + 1] - cuts[k]) * std::clamp(u0 + (u1 - u0) * mid, a, b);
  }
  return sum;
}

struct FrontTime {
  double sample = 0;   // fractional sample
  double samples = 0;  // samples between the two levels
  double plateau = 0;  // |plateau − baseline|
};

FrontTime front_time(const std::vector<double>& x, double level, const PulseWindow& w) {
  const double plateau = plateau_level(x, w.onset, w.end, w.sign) - w.sign * level;
  const std::size_t end = std::min(w.end, x.size());
  // No plateau to take fractions of (a window of noise): its onset, as a crossing would give.
  if (!(plateau > 0) || w.onset + 1 >= end) return {static_cast<double>(w.onset), 0, 0};
  auto u = [&](std::size_t i) { return w.sign * (x[i] - level) / plateau; };
  // First reaches of a and of b, and a span one rise wider on both sides (clipped to a and b
  // there, so its exact ends do not matter).
  std::size_t ia = w.onset;
  while (ia + 1 < end && u(ia) < kFrontLow) ++ia;
  std::size_t ib = ia;
  while (ib + 1 < end && u(ib) < kFrontHigh) ++ib;
  const std::size_t rise = ib - ia + 2;
  const std::size_t t0 = ia > rise ? ia - rise : 0, t1 = std::min(end - 1, ib + rise);
  double area = 0, inside = 0;
  for (std::size_t i = t0; i < t1; ++i) {
    area += clipped_segment(u(i), u(i + 1), kFrontLow, kFrontHigh) - kFrontLow;
    inside += u(i) > kFrontLow && u(i) < kFrontHigh;
  }
  return {static_cast<double>(t1) - area / (kFrontHigh - kFrontLow), inside, std::abs(plateau)};
}

std::size_t widen(std::size_t i, double by, bool down, std::size_t n) {
  const auto d = static_cast<std::size_t>(by);
  if (down) return i > d ? i - d : 0;
  return std::min(n, i + d);
}

// A rise to half height whose median holds this share of the peak is a shoulder (a pulse shaper's
// step tops at 0.40–0.49 of the peak); a front rising steadily from rest holds 0.25 at most (a
// straight one), one with a foot less.
constexpr double kShoulderFraction = 0.35;

// The rest level again, from the whole record before the first pulse rather than its first 5 %
// (an amplifier settling after the trigger; and its error is an offset common to the hundreds of
// samples a fit lays over each pulse, docs/validation.md "shpb fit"), and the pulse found anew.
// Returns that level's standard deviation (rest_level_sd; 0 when the level is not settled so).
// First up to the pulse's half-height sample (or its onset, below), as its onset found against
// the first 5 % of a record that settles after its trigger is not the pulse's; then before the
// onset of the pulse found against the level so read (rest_samples_before), again while the
// samples read reach past the onset found against their level: never the rise's samples. After a
// short rest before a sharp front the median up to the half-height sample held as many samples of
// the rise as of the rest, a level 6-10 % of the peak up the front (compare's striker
// velocity 13.8-14.2 m/s for 15 from the classic record at 100 MS/s with 10 samples of rest), and
// the rest before the onset found against it, less one rise, was fewer than kMinRestSamples, so
// that level stayed. Where the onset leaves fewer than kMinRestSamples, the level of the record's
// first samples (its baseline, whose pulse starts after them: require_rest_before_pulse) stays, and
// it is said.
double settle_rest_level(RestSignal& s, const std::string& gauge,
                         std::vector<std::string>& warnings) {
  if (!s.first) return 0;
  const std::vector<double> baseline_x = s.x;
  const PulseWindow baseline_first = *s.first;
  auto settle = [&s](std::size_t rest) -> std::optional<double> {
    const auto level = rest_level_before(s.x, rest);
    if (!level) return std::nullopt;
    for (double& v : s.x) v -= *level;
    if (auto again = find_first_pulse(s.x, {0.0, s.noise})) s.first = again;
    return rest_level_sd(s.noise, rest);
  };
  // Up to the half-height sample, unless the rise to it outlasts the record before the onset and
  // sits on a shoulder (its median at least kShoulderFraction of the peak): a pulse shaper's step
  // stops just below half height, and by the noise draw the half-height sample is on it or on the
  // ramp µs later, after a shoulder at 0.4–0.5 of the peak that a median up to there took for the
  // rest (compare's striker velocity from the incident plateau 3.7 against 7.1 m/s): up to the
  // onset then. A record settling after its trigger has its early onset at rest, not on a shoulder.
  const PulseWindow& w = *s.first;
  std::vector<double> rise;
  for (std::size_t i = w.onset; i < w.half && i < s.x.size(); ++i) rise.push_back(w.sign * s.x[i]);
  const bool shoulder = rise.size() > w.onset && median(rise) >= kShoulderFraction * w.peak;
  std::size_t end = shoulder ? w.onset : w.half;
  const auto first = settle(end);
  if (!first) return 0;
  double sd = *first;
  // Again while the samples read reach past the onset of the pulse found against their level
  // (each time fewer: rest_samples_before is at most that onset).
  for (bool again = true; s.first->onset >= kMinRestSamples; again = end > s.first->onset) {
    if (!again) return sd;
    sd = settle(end = rest_samples_before(*s.first)).value_or(sd);
  }
  warnings.push_back("gauge \"" + gauge + "\": " +
                     fmt("its first pulse starts %.0f samples into the record against the rest "
                         "level read before it, fewer than the %.0f a level is read from: the "
                         "level of its first samples is kept",
                         static_cast<double>(s.first->onset),
                         static_cast<double>(kMinRestSamples)));
  s.x = baseline_x, s.first = baseline_first;
  return 0;
}

// A pulse the record does not hold (it ended first, or a dead channel) is not compared, and one
// still on at the record's end is compared over its recorded part only: both said.
void report_missing_pulses(MeasuredPulses& m) {
  const KolskySetup& k = m.setup;
  const double t_end = m.time_s.back(), t_inc = m.time_s[m.incident_window.onset];
  char msg[400];
  // A pulse that follows the incident onset by `after` in a record that ends before it.
  const auto record_ends_first = [&](const std::string& gauge, const char* pulse,
                                     const char* after_is, double after) {
    if (t_end - t_inc >= after) return false;
    std::snprintf(msg, sizeof msg,
                  "gauge \"%s\": no %s pulse in the record, which ends at %s s (%.3g s after "
                  "the incident onset; the %s pulse follows it by %s%.3g s): the %s pulse is not "
                  "compared",
                  gauge.c_str(), pulse, format_resolved(t_end, m.dt_s, 4).c_str(), t_end - t_inc,
                  pulse, after_is, after, pulse);
    m.warnings.push_back(msg);
    return true;
  };
  const double round_trip = 2 * k.incident_distance_m / k.front.c0_m_s;
  if (!m.reflected_window &&
      !record_ends_first(k.incident_gauge, "reflected", "2d/c0 = ", round_trip)) {
    std::snprintf(
        msg, sizeof msg,
        "gauge \"%s\": no reflected pulse beyond the incident pulse's tail (twice the "
        "band it ends within, %.3g strain; a specimen matched to the bar reflects next to "
        "nothing): the reflected pulse is not compared",
        k.incident_gauge.c_str(),
        following_pulse_min_peak(m.incident_baseline.noise, m.incident_window.peak));
    m.warnings.push_back(msg);
  }
  if (!m.transmitted_window &&
      !record_ends_first(k.transmitted_gauge, "transmitted", "", transmitted_arrival_s(k, 0.0)))
    m.warnings.push_back("gauge \"" + k.transmitted_gauge +
                         "\": no pulse above the noise: the transmitted pulse is not compared");
  const std::size_t n = m.time_s.size();
  for (const auto& [w, name, gauge] :
       {std::tuple{std::optional<PulseWindow>(m.incident_window), "incident", k.incident_gauge},
        std::tuple{m.reflected_window, "reflected", k.incident_gauge},
        std::tuple{m.transmitted_window, "transmitted", k.transmitted_gauge}})
    if (w && w->end >= n) {
      std::snprintf(msg, sizeof msg,
                    "gauge \"%s\": the %s pulse lasts until the record ends (%s s): compared "
                    "over its recorded part only",
                    gauge.c_str(), name, format_resolved(t_end, m.dt_s, 4).c_str());
      m.warnings.push_back(msg);
    }
  // A reflected pulse lasts as long as the incident one (the specimen is loaded that long; a broken
  // one reflects the rest whole, docs/methods.md §6): a window ending sooner than kShortReflected
  // of it ended where the pulse's tail sank into the rest band (a hardening specimen's reflected
  // pulse decays), and only its first part is compared.
  const PulseWindow& in = m.incident_window;
  if (const auto& r = m.reflected_window;
      r && r->end < n &&
      static_cast<double>(r->end - r->onset) <
          kShortReflected * static_cast<double>(in.end - in.onset)) {
    std::snprintf(msg, sizeof msg,
                  "gauge \"%s\": the reflected pulse's window (%.3g s) is shorter than half the "
                  "incident pulse (%.3g s): its tail lies within the record's rest band (%.3g "
                  "strain) and is not compared; its ratios and NRMSE are of its first part only",
                  k.incident_gauge.c_str(), m.time_s[r->end - 1] - m.time_s[r->onset],
                  m.time_s[in.end - 1] - m.time_s[in.onset],
                  rest_band(m.incident_baseline.noise, r->peak));
    m.warnings.push_back(msg);
  }
}

}  // namespace

MeasuredPulses find_measured_pulses(const Scene& scene, const GaugeSignals& signals) {
  MeasuredPulses m;
  m.setup = resolve_setup(scene, signals.gauges);
  m.time_s = signals.time_s;
  m.dt_s = signals.dt_s;
  const bool tension = scene.measurement && scene.measurement->tension;
  const double first_sign = tension ? 1.0 : -1.0;
  RestSignal inc = rest_signal(signals, m.setup.incident_gauge, first_sign, scene.file.string());
  RestSignal tra = rest_signal(signals, m.setup.transmitted_gauge, first_sign, scene.file.string());
  if (!inc.first)
    throw no_pulse_error(signals, m.setup.incident_gauge, scene.file.string(),
                         "no incident pulse to compare");
  for (const auto* s : {&inc, &tra})
    if (s->inverted)
      m.warnings.push_back(inverted_gauge_warning(
          s == &inc ? m.setup.incident_gauge : m.setup.transmitted_gauge, tension));
  m.incident_rest_sd = settle_rest_level(inc, m.setup.incident_gauge, m.warnings);
  m.transmitted_rest_sd = settle_rest_level(tra, m.setup.transmitted_gauge, m.warnings);
  m.incident = std::move(inc.x), m.transmitted = std::move(tra.x);
  m.incident_clipped = clipped_samples(*signals.find(m.setup.incident_gauge), m.incident,
                                       signals.range_of(m.setup.incident_gauge));
  m.transmitted_clipped = clipped_samples(*signals.find(m.setup.transmitted_gauge), m.transmitted,
                                          signals.range_of(m.setup.transmitted_gauge));
  if (m.incident_clipped) m.incident_clipped->noise = inc.noise;
  if (m.transmitted_clipped) m.transmitted_clipped->noise = tra.noise;
  m.incident_baseline = {0.0, inc.noise}, m.transmitted_baseline = {0.0, tra.noise};
  m.incident_window = *inc.first;
  require_pulse_fits_round_trip(m.setup,
                                m.dt_s * static_cast<double>(inc.first->end - 1 - inc.first->onset),
                                scene.file.string());
  // Only a pulse beyond the incident pulse's ringing tail is its reflection, as `process` takes it:
  // a record ending before the reflection arrives otherwise had that tail compared as it.
  m.reflected_window = find_first_pulse(m.incident, m.incident_baseline, inc.first->end);
  if (m.reflected_window &&
      !(m.reflected_window->peak > following_pulse_min_peak(inc.noise, inc.first->peak)))
    m.reflected_window.reset();
  m.transmitted_window = tra.first;
  report_missing_pulses(m);
  m.incident_plateau =
      std::abs(plateau_level(m.incident, inc.first->onset, inc.first->end, inc.first->sign));
  m.struck_end_plateau = std::abs(struck_end_plateau(m.setup, m.incident, m.dt_s, *inc.first));
  // T moves by −dt/(P (b − a)) per unit of each sample between the levels: with white noise σ,
  // sd(T) = dt σ √n / (P (b − a)).
  const FrontTime front = front_time(m.incident, 0.0, m.incident_window);
  m.incident_front_samples = front.samples;
  if (front.plateau > 0)
    m.incident_front_sd_s = m.dt_s * m.incident_baseline.noise * std::sqrt(front.samples) /
                            (front.plateau * (kFrontHigh - kFrontLow));
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

std::vector<double> PulseOverlay::dispersed(const std::vector<double>& y, double dt,
                                            double distance_m, bool back,
                                            const BarWaveguide& guide) const {
  Propagator prop(back ? *back_table_ : *front_table_, guide, PropagationOptions{});
  // Zeros after the record leave room for the delay d/c(f) (the output keeps the input's length);
  // ×1.25 covers the slowest phase velocity below the cut-off.
  std::vector<double> src = y;
  src.resize(src.size() + static_cast<std::size_t>(1.25 * distance_m / guide.c0_m_s / dt) + 1, 0.0);
  const std::vector<double> moved = prop.propagate(src, dt, distance_m);
  // Moving by Δz delays by Δz/c(f); the 1D model already delayed by Δz/c0: advance by that.
  std::vector<double> out(src.size());
  for (std::size_t k = 0; k < out.size(); ++k)
    out[k] = sample(moved, 0, dt, static_cast<double>(k) * dt + distance_m / guide.c0_m_s);
  return out;
}

Overlay PulseOverlay::overlay(const Scene& scene, const TimeSeries& simulated_gauges,
                              double shift_s, double transmitted_delay_s) const {
  const MeasuredPulses& m = measured_;
  const KolskySetup& setup = m.setup;
  const std::string file = scene.file.string();
  const std::size_t incident_bar = *scene.specimen - 1;
  const std::size_t n = m.time_s.size();
  const double dt_sim = 1.0 / scene.simulation.sample_rate_Hz;
  const std::vector<double>& s_inc = simulated_gauges.column(setup.incident_gauge);
  const std::vector<double>& s_tr = simulated_gauges.column(setup.transmitted_gauge);
  const double t_sim0 = simulated_gauges.time_s.empty() ? 0.0 : simulated_gauges.time_s.front();
  const Baseline base_sim = estimate_baseline(s_inc);
  const auto w_sim = find_first_pulse(s_inc, base_sim);
  if (!w_sim)
    throw NumericalError(file + ": simulation: no incident pulse at gauge " + setup.incident_gauge);
  const double t_meas0 = m.time_s.front(), dt = m.dt_s;
  // The bars' waveguides with the simulated scene's wave speeds (the same Poisson ratio: the
  // tables are the measurement's).
  BarWaveguide front = setup.front_waveguide, back = setup.back_waveguide;
  front.c0_m_s = scene.bars[incident_bar].material.wave_speed_m_s();
  back.c0_m_s = scene.bars[incident_bar + 2].material.wave_speed_m_s();
  // A viscoelastic bar's law already acts in the simulation: only the geometry's dispersion is
  // added.
  for (BarWaveguide* w : {&front, &back}) w->arms.clear(), w->long_term_fraction = 1;
  Overlay o;
  // The two clocks meet at the incident pulses' front times (the trigger time of a measurement is
  // unknown): a time averaged over the whole front, so the record noise moves it little, and that
  // does not depend on how steep the front is.
  const double front_meas =
      front_time(m.incident, m.incident_baseline.level, m.incident_window).sample;
  // The measured incident pulse has dispersed over the bar from the impact face to the gauge: the
  // simulated one is compared as it would arrive, dispersed over the same distance (the 1D pulse's
  // front would otherwise be aligned with a front that dispersion has already delayed). The same
  // dispersed pulse is laid over the record below.
  const double l_inc = scene.bars[incident_bar].length_m;
  std::vector<double> dispersed_incident;
  double front_sim = front_time(s_inc, base_sim.level, *w_sim).sample;
  if (dispersion()) {
    dispersed_incident = dispersed(s_inc, dt_sim, l_inc - setup.incident_distance_m, false, front);
    const auto w = find_first_pulse(dispersed_incident, base_sim);
    if (w) front_sim = front_time(dispersed_incident, base_sim.level, *w).sample;
  }
  o.offset_s = (t_meas0 + front_meas * dt) - (t_sim0 + front_sim * dt_sim) + shift_s;
  o.t_sim_end = t_sim0 + static_cast<double>(s_inc.size() - 1) * dt_sim;

  // Pulses and the distance each travelled before reaching its gauge.
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
                    "the simulation ends (%s s on the measured clock) before the %s pulse has "
                    "passed gauge \"%s\" (its window ends at %s s): compared on %.0f %% of its "
                    "window only; set simulation.duration to at least %.3g s",
                    format_resolved(o.t_sim_end + o.offset_s, dt, 4).c_str(), name.c_str(),
                    gauge.c_str(), format_resolved(m.time_s[p.end - 1], dt, 4).c_str(),
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
  if (!dispersion() && setup.excess_delay_s_per_m == 0 && transmitted_delay_s == 0) return o;
  // The incident gauge carries two pulses: split its record half-way between them.
  const std::size_t split =
      m.reflected_window ? (m.incident_window.end + m.reflected_window->onset) / 2 : n;
  for (const OverlaidPulse& p : o.pulses) {
    // What the real bars add to the travel from the incident gauge on (the lab's calibrated
    // reflected time): 2d for the reflected pulse, d + d' for the transmitted one.
    const double d = setup.incident_distance_m;
    const double beyond_incident_m = p.transmitted           ? d + setup.transmitted_distance_m
                                     : p.name == "reflected" ? 2 * d
                                                             : 0;
    const double delay_s = setup.excess_delay_s_per_m * beyond_incident_m +
                           (p.transmitted ? transmitted_delay_s : 0.0);
    const std::vector<double>* arriving = p.transmitted ? &s_tr : &s_inc;
    std::vector<double> moved_here;
    if (dispersion()) {
      if (p.name != "incident")
        moved_here =
            dispersed(*arriving, dt_sim, p.distance_m, p.transmitted, p.transmitted ? back : front);
      arriving = p.name == "incident" ? &dispersed_incident : &moved_here;
    }
    const std::vector<double> moved = on_measured_clock(*arriving, -delay_s);
    std::vector<double>& dst = p.transmitted ? o.transmitted : o.incident;
    const std::size_t from = p.name == "reflected" ? split : 0;
    const std::size_t to = p.name == "incident" ? split : n;
    std::copy(moved.begin() + static_cast<long>(from), moved.begin() + static_cast<long>(to),
              dst.begin() + static_cast<long>(from));
  }
  return o;
}

}  // namespace shpb
