#include "analysis/processing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <span>
#include <tuple>

#include "analysis/dispersion_cutoff.hpp"
#include "analysis/message_text.hpp"
#include "analysis/pulse_window.hpp"
#include "analysis/reduction_checks.hpp"
#include "analysis/sample_index.hpp"
#include "analysis/signal_checks.hpp"
#include "core/csv_writer.hpp"  // format_double
#include "core/error.hpp"
#include "core/number_format.hpp"

namespace shpb {
namespace {

// The face window runs this fraction of the incident duration past its end, so the
// transmitted pulse (delayed by the specimen transit) is not cut.
constexpr double kWindowTail = 0.15;
// A record ends with a pulse on it when the mean of its last this many samples lies outside the
// rest band: a few, so that one noisy sample decides nothing.
constexpr std::size_t kEndSamples = 5;

// The pulses are moved by the gauge distances: refuse a delay of more samples than any record
// holds before the propagation pads the signal by it.
void require_delays_fit(const KolskySetup& k, double dt, const std::string& scene_file) {
  for (const auto& [distance, c, gauge] :
       {std::tuple{k.incident_distance_m, k.front.c0_m_s, k.incident_gauge},
        std::tuple{k.transmitted_distance_m, k.back.c0_m_s, k.transmitted_gauge}})
    if (distance / (c * dt) > kMaxDelaySamples) {
      char value[160];
      std::snprintf(value, sizeof value,
                    "gauge \"%s\": delay %.3g s to the specimen = %.3g samples of %.3g s",
                    gauge.c_str(), distance / c, distance / (c * dt), dt);
      throw input_error(scene_file, "measurement.time.unit", value,
                        "expected at most 2^24 samples: is the time unit right?");
    }
}

// A gauge's signal from its rest level, and its noise; polarity checked (the first large
// excursion of each gauge is compressive, in the reduction's sign convention).
struct PreparedSignal {
  std::vector<double> x;
  double noise = 0;
};
PreparedSignal prepared_signal(const GaugeSignals& signals, const std::string& gauge,
                               const ProcessingOptions& options, ProcessingResult& r) {
  RestSignal s = rest_signal(signals, gauge, -1.0, options.scene_file);
  if (!s.first) throw no_pulse_error(signals, gauge, options.scene_file, "no pulse to process");
  if (s.inverted) {
    r.inverted_gauges.push_back(gauge);
    r.warnings.push_back(inverted_gauge_warning(gauge, options.tension));
  }
  return {std::move(s.x), s.noise};
}

// The incident pulse's samples [on, end) on the gauge clock: the scene's window, or detected.
std::pair<std::size_t, std::size_t> incident_samples(const std::vector<double>& t,
                                                     const PreparedSignal& inc,
                                                     const ProcessingOptions& options,
                                                     ProcessingResult& r) {
  if (!options.windows.incident) {
    const auto p = find_first_pulse(inc.x, {0.0, inc.noise});
    r.incident_window.detected = true;
    return {p->onset, p->end};
  }
  const TimeWindow& w = *options.windows.incident;
  if (w.start_s < t.front() || w.end_s > t.back())
    throw input_error(options.scene_file, "measurement.windows.incident", "",
                      "the window lies outside the record");
  const std::size_t on = nearest_sample(t, w.start_s), end = nearest_sample(t, w.end_s) + 1;
  if (!(end > on + 2) || end > t.size())
    throw input_error(options.scene_file, "measurement.windows.incident", "",
                      "the window lies outside the record or is shorter than 3 samples");
  return {on, end};
}

// The sign of the reflected pulse's front on the incident gauge, whose incident pulse is negative
// here: at the front face σ_R/σ_I = (Z_s − Z_b)/(Z_s + Z_b) until the specimen rings up
// (docs/methods.md §6), so a specimen of lower impedance ρ c0 A than the incident bar first
// reflects a tensile pulse (+), a stiffer one a compressive pulse (−). Without the specimen's
// modulus the usual softer specimen is assumed.
double reflected_sign(const KolskySetup& k) {
  return k.specimen_impedance_kg_s && *k.specimen_impedance_kg_s > k.incident_impedance_kg_s ? -1.0
                                                                                             : 1.0;
}

// Where the pulses are expected at the gauges and at the faces, where they were detected, and the
// extra time shifts of the reflected and transmitted pulses after the move by the gauge distances.
struct PulseTiming {
  double duration = 0;    // the incident pulse's
  double face_start = 0;  // the incident pulse's start at the front face
  double extra_r = 0, extra_t = 0;
  std::optional<double> reflected_onset_s, transmitted_onset_s;  // gauge clocks
};
// How much later than Σd/c0 a polymer bar's law puts the foot of the incident pulse moved along
// `legs` (bar, distance): its front travels at c0 but attenuated by e^{−α∞ d} below the band an
// onset is picked above, so the foot arrives later (methods.md §5.1); 0 through elastic bars.
double law_foot_delay_s(const PreparedSignal& inc, std::size_t on, std::size_t end, double dt,
                        std::initializer_list<std::pair<const BarWaveguide*, double>> legs) {
  double travel = 0;
  bool law = false;
  for (const auto& [w, d] : legs) travel += d / w->c0_m_s, law = law || w->viscoelastic();
  if (!law || end <= on) return 0;
  const auto lead = static_cast<std::size_t>(std::ceil(travel / dt));
  std::vector<double> x(end + lead + (end - on), 0.0);
  std::copy(inc.x.begin(), inc.x.begin() + static_cast<std::ptrdiff_t>(end), x.begin());
  PropagationOptions o;
  o.dispersion = false;
  for (const auto& [w, d] : legs) x = Propagator(*w, o).propagate(x, dt, d);
  const auto peak = std::max_element(inc.x.begin() + static_cast<std::ptrdiff_t>(on),
                                     inc.x.begin() + static_cast<std::ptrdiff_t>(end),
                                     [](double a, double b) { return std::abs(a) < std::abs(b); });
  const auto foot = find_onset(x, {0.0, inc.noise}, *peak < 0 ? -1.0 : 1.0, lead, x.size(), 0.0);
  return foot ? (static_cast<double>(foot->onset) - static_cast<double>(on + lead)) * dt : 0.0;
}

// The length of an incident pulse whose reflection reaches its gauge before it has passed. Where
// the two nearly cancel (a specimen that reflects almost all of it, of the other sign), their sum
// lies in the rest band and the pulse seems to end when its reflection arrives; the reflected
// pulse then shows alone once the incident one has passed, and ends one pulse length after its
// arrival (docs/methods.md §6). Sought within the detected length beyond it (a pulse up to twice
// that long); never shorter than the detected window.
double incident_length_at_overlap(const std::vector<double>& t, std::size_t on, std::size_t end,
                                  double travel_r, const PreparedSignal& inc) {
  const double detected = t[end - 1] - t[on];
  const std::size_t limit = std::min(inc.x.size(), index_at(t, t[on] + travel_r + 2 * detected));
  if (end >= limit) return detected;
  const auto q =
      find_first_pulse(std::span<const double>(inc.x).first(limit), {0.0, inc.noise}, end);
  // The incident pulse is negative here: a cancelling reflection is positive.
  if (!q || q->sign < 0) return detected;
  return std::max(detected, t[q->end - 1] - t[on] - travel_r);
}

PulseTiming time_the_pulses(const std::vector<double>& t, double dt, std::size_t on,
                            std::size_t end, const PreparedSignal& inc, const PreparedSignal& tra,
                            const KolskySetup& k, const ProcessingOptions& options,
                            ProcessingResult& r) {
  PulseTiming p;
  const double c_front = k.front.c0_m_s, c_back = k.back.c0_m_s;
  const double d_i = k.incident_distance_m, d_t = k.transmitted_distance_m;
  p.duration = t[end - 1] - t[on];
  p.face_start = t[on] + d_i / c_front;
  const BarWaveguide *front = &k.front_waveguide, *back = &k.back_waveguide;
  const double expected_r =
      t[on] + 2 * d_i / c_front + law_foot_delay_s(inc, on, end, dt, {{front, 2 * d_i}});
  const double expected_t = transmitted_arrival_s(k, t[on]) +
                            law_foot_delay_s(inc, on, end, dt, {{front, d_i}, {back, d_t}});
  // Alignment check: where the reflected and transmitted pulses really start against where
  // geometry puts them.
  std::size_t inc_half = on;  // first half-peak sample of the incident pulse: its front's rise
  const double incident_peak = -*std::min_element(inc.x.begin() + static_cast<std::ptrdiff_t>(on),
                                                  inc.x.begin() + static_cast<std::ptrdiff_t>(end));
  while (inc_half + 1 < end && -inc.x[inc_half] < 0.5 * incident_peak) ++inc_half;
  r.incident_rise_s = t[inc_half] - t[on];
  // A reflected front due before the incident pulse has ended on its gauge (a gauge closer to the
  // specimen than half the pulse's length) cannot be told from that pulse: no onset is sought.
  // It is sought from the incident pulse's first sample at rest, beyond the incident's tail
  // (following_pulse_min_peak).
  const double travel_r = 2 * d_i / c_front;
  const bool apart = t[end - 1] < t[on] + travel_r - alignment_tolerance_s(dt, travel_r);
  const auto i1 = index_at(t, expected_r + p.duration);
  const double min_peak = following_pulse_min_peak(inc.noise, incident_peak);
  if (const auto o = apart
                         ? find_onset(inc.x, {0.0, inc.noise}, reflected_sign(k), end, i1, min_peak)
                         : std::nullopt) {
    p.reflected_onset_s = t[o->onset];
    r.reflected_onset_offset_s = t[o->onset] - expected_r;
    r.reflected_rise_s = t[o->half] - t[o->onset];
  }
  if (!apart) r.incident_length_s = incident_length_at_overlap(t, on, end, travel_r, inc);
  if (const auto q = find_first_pulse(tra.x, {0.0, tra.noise})) {
    p.transmitted_onset_s = t[q->onset];
    r.transmitted_onset_offset_s = t[q->onset] - expected_t;
    std::size_t half = q->onset;  // first half-peak sample: the front's rise
    while (half + 1 < q->end && q->sign * tra.x[half] < 0.5 * q->peak) ++half;
    r.transmitted_rise_s = t[half] - t[q->onset];
  }
  if (!options.windows.reflected && !options.windows.transmitted)
    check_alignment(r, k, dt, r.warnings);
  // Extra time shifts after the move by the gauge distances (docs/methods.md §6): a hand-set
  // window puts its start at the incident pulse's face start (a window is a time shift); with
  // "align": "onsets" each detected onset is put where geometry expects it.
  if (options.windows.reflected) {
    p.extra_r = t[nearest_sample(t, options.windows.reflected->start_s)] - expected_r;
  } else if (options.align == Alignment::kOnsets && r.reflected_onset_offset_s) {
    p.extra_r = *r.reflected_onset_offset_s;
    r.reflected_at_onset = true;
  }
  if (options.windows.transmitted) {
    p.extra_t =
        t[nearest_sample(t, options.windows.transmitted->start_s)] - d_t / c_back - p.face_start;
  } else if (options.align == Alignment::kOnsets && r.transmitted_onset_offset_s) {
    p.extra_t = *r.transmitted_onset_offset_s;
    r.transmitted_at_onset = true;
  }
  p.extra_r += options.reflected_shift_s;
  p.extra_t += options.transmitted_shift_s;
  r.shift_incident_s = d_i / c_front;
  r.shift_reflected_s = -d_i / c_front - p.extra_r;
  r.shift_transmitted_s = -d_t / c_back - p.extra_t;
  // The stretch of record moved to the faces: its front's time at c0, plus the extra shift.
  const double reflected_start = t[on] + travel_r + p.extra_r;
  r.reflected_window = {k.incident_gauge, reflected_start, reflected_start + p.duration,
                        !options.windows.reflected};
  return p;
}

// The three pulses at the faces, as strains (e*) and — with Tyas–Pope amplitude factors — as
// stresses over the modulus (f*; the strains again without them).
// The kinematic pulses at the faces and the force pulses, these empty where they are the same
// (an elastic bar without amplitude factors): no copy of three whole records.
struct FacePulses {
  std::vector<double> ei, er, et, fi, fr, ft;
  // How much short of a pure delay the moved reflected and transmitted pulses already depend on
  // their record's end (Propagator::end_reach_s).
  double reach_r = 0, reach_t = 0;
};
FacePulses pulses_at_faces(const PreparedSignal& inc, const PreparedSignal& tra, double dt,
                           const PulseTiming& timing, const KolskySetup& k,
                           const ProcessingOptions& options, ProcessingResult& r) {
  // Propagation (Pochhammer–Chree or pure delay).
  const DispersionSpec& ds = options.dispersion;
  PropagationOptions po;
  po.dispersion = ds.correction;
  // One band for every pulse of a viscoelastic bar: the law's inverse grows what lies above it by
  // more than kMaxLawGain (methods.md §5.1).
  po.law_cutoff_Hz = std::min(law_band_limit_Hz(k.front_waveguide, k.incident_distance_m),
                              law_band_limit_Hz(k.back_waveguide, k.transmitted_distance_m));
  if (std::isfinite(po.law_cutoff_Hz))
    r.warnings.push_back(
        fmt("the polymer bars' law attenuates a pulse between its gauge and the specimen by more "
            "than %g x above %.3g kHz, and moving it back would grow it (and the noise) as much: "
            "the pulses at the faces are low-passed there, their fronts smeared over about "
            "%.3g us; gauges nearer the specimen keep more of the band",
            kMaxLawGain, po.law_cutoff_Hz / 1e3, 1e6 / po.law_cutoff_Hz));
  auto table_reach = [&](const BarWaveguide& w) {
    PropagationOptions o = po;
    o.cutoff_fa_over_c0 = cutoff_fa_over_c0(ds, w);
    return mode_reach(w, o);
  };
  // A cut-off read through a viscoelastic bar's law: f·a over its phase velocity, not over c0.
  auto cutoff_text = [&](const BarWaveguide& w) {
    std::string text = "f·a/c0 = " + format_double(cutoff_fa_over_c0(ds, w));
    if (w.viscoelastic())
      text += " (f·a over the law's phase velocity up to " + format_double(table_reach(w)) + ")";
    return text;
  };

  // The mode is tabulated only for a correction, and only up to the highest cut-off asked of its
  // Poisson ratio; the corrections share their FFT plans (one per padded length).
  std::optional<DispersionTable> front_table, back_own;
  const DispersionTable* front = nullptr;
  const DispersionTable* back = nullptr;
  if (ds.correction) {
    const bool shared = k.back_waveguide.poisson == k.front_waveguide.poisson;
    const double fa_front = table_reach(k.front_waveguide), fa_back = table_reach(k.back_waveguide);
    const double fa_shared = shared ? std::max(fa_front, fa_back) : fa_front;
    if (options.tables) {
      front = &options.tables->up_to(k.front_waveguide.poisson, fa_shared);
      back = shared ? front : &options.tables->up_to(k.back_waveguide.poisson, fa_back);
    } else {
      front = &front_table.emplace(DispersionTable::up_to(k.front_waveguide.poisson, fa_shared));
      back = shared ? front
                    : &back_own.emplace(DispersionTable::up_to(k.back_waveguide.poisson, fa_back));
    }
  }
  FftPlans own_plans;
  FftPlans& plans = options.plans ? *options.plans : own_plans;
  // A manual window's extra shift is a pure delay after the move.
  auto delayed = [&](std::vector<double> y, double extra) {
    if (extra == 0) return y;
    std::vector<double> z(y.size());
    delay_by_interpolation(y, -extra / dt, z);
    return z;
  };
  auto moved = [&](const std::vector<double>& x, const BarWaveguide& w,
                   const DispersionTable* table, double distance, double extra, AmplitudeFactor a,
                   WaveQuantity q, double* reach = nullptr) {
    PropagationOptions o = po;
    o.amplitude = a;
    o.quantity = q;
    o.cutoff_fa_over_c0 = cutoff_fa_over_c0(ds, w);
    if (!ds.correction) {
      Propagator p(w, o);
      if (reach) *reach = p.end_reach_s(x.size(), dt, distance);
      return delayed(p.propagate(x, dt, distance), extra);
    }
    const DispersionTable& tab = *table;
    const std::string key = dispersion_cutoff_key(ds);
    if (table_reach(w) > tab.max_normalized_frequency())
      throw input_error(options.scene_file, key, cutoff_text(w),
                        "cut-off beyond the tabulated mode");
    if (a != AmplitudeFactor::kNone && table_reach(w) >= tab.m1_pole_normalized_frequency())
      throw input_error(options.scene_file, key, cutoff_text(w),
                        "with amplitude factors the cut-off must lie below the m1 pole (f·a/c0 = " +
                            std::to_string(tab.m1_pole_normalized_frequency()) + ")");
    Propagator p(tab, w, o, &plans);
    if (reach) *reach = p.end_reach_s(x.size(), dt, distance);
    return delayed(p.propagate(x, dt, distance), extra);
  };
  const double d_i = k.incident_distance_m, d_t = k.transmitted_distance_m;
  const auto kin = ds.amplitude_factors ? AmplitudeFactor::kStrain : AmplitudeFactor::kNone;
  // The kinematic pulses give the faces' velocities, the force pulses their forces: one pulse in
  // an elastic bar without amplitude factors, two in a viscoelastic one (methods.md §5.1).
  constexpr auto kVelocity = WaveQuantity::kVelocity, kForce = WaveQuantity::kForce;
  FacePulses f;
  f.ei = moved(inc.x, k.front_waveguide, front, d_i, 0, kin, kVelocity);
  f.er = moved(inc.x, k.front_waveguide, front, -d_i, timing.extra_r, kin, kVelocity, &f.reach_r);
  f.et = moved(tra.x, k.back_waveguide, back, -d_t, timing.extra_t, kin, kVelocity, &f.reach_t);
  constexpr auto kStress = AmplitudeFactor::kStress;
  if (ds.amplitude_factors || k.front_waveguide.viscoelastic() || k.back_waveguide.viscoelastic()) {
    const auto force = ds.amplitude_factors ? kStress : AmplitudeFactor::kNone;
    f.fi = moved(inc.x, k.front_waveguide, front, d_i, 0, force, kForce);
    f.fr = moved(inc.x, k.front_waveguide, front, -d_i, timing.extra_r, force, kForce);
    f.ft = moved(tra.x, k.back_waveguide, back, -d_t, timing.extra_t, force, kForce);
  }
  if (ds.correction) r.cutoff_Hz = dispersion_cutoff_Hz(ds, k.front_waveguide);
  return f;
}

// Whether a gauge's record ends with a pulse still on it: the mean of its last kEndSamples
// samples beyond what a following pulse must rise to (twice the rest band, max(5σ, 3 % of its
// peak)): a pulse's ringing tail at the end (±7 % of the peak on a 20 mm steel bar at 1 MS/s) is
// not one.
bool ends_in_pulse(const PreparedSignal& s) {
  double peak = 0;
  for (const double x : s.x) peak = std::max(peak, std::abs(x));
  const std::size_t m = std::min(kEndSamples, s.x.size());
  double sum = 0;
  for (std::size_t i = s.x.size() - m; i < s.x.size(); ++i) sum += s.x[i];
  return std::abs(sum / static_cast<double>(m)) > following_pulse_min_peak(s.noise, peak);
}

// The last time at the faces at which every pulse is read from the record: the reflected and
// transmitted pulses are moved back from their gauges (negative shifts), so the record holds them
// at the faces only until its end less their travel, and a record that ends while a pulse is still
// on it less the reach of the dispersion correction (the tapered end, the slowest component's
// extra travel) too. Beyond it a pulse at the faces was read off the record (as zero) or from the
// taper: a record cut while its reflected pulse still passed its gauge (a DEWESoft export of a
// 1 MS/s test cut 4 us early) read its 1-wave peak 10 % and its 3-wave peak 5 % high, cut 24 us
// early its 3-wave peak 32 % high, blamed on a specimen that broke.
struct RecordedAtFaces {
  double time_s = 0;
  bool by_reflected = true;  // the reflected pulse's gauge ends it (else the transmitted one's)
};
RecordedAtFaces recorded_at_faces(const std::vector<double>& t, const FacePulses& f,
                                  const PreparedSignal& inc, const PreparedSignal& tra,
                                  const ProcessingResult& r) {
  const double reflected = r.shift_reflected_s - (ends_in_pulse(inc) ? f.reach_r : 0.0);
  const double transmitted = r.shift_transmitted_s - (ends_in_pulse(tra) ? f.reach_t : 0.0);
  return {t.back() + std::min({0.0, reflected, transmitted}), reflected <= transmitted};
}

// A record that ends before the loading has passed the faces (the incident pulse's duration from
// the window's start) ends the curve short of the loading's end: said, with the gauge whose pulse
// the record ends in.
void warn_record_ends_in_loading(const std::vector<double>& t, double dt, const RecordedAtFaces& at,
                                 const PulseTiming& timing, const KolskySetup& k,
                                 ProcessingResult& r) {
  const double recorded = at.time_s, loaded = timing.face_start + timing.duration;
  const bool reflected = at.by_reflected;
  if (!(recorded < loaded)) return;
  r.warnings.push_back(
      "gauge \"" + (reflected ? k.incident_gauge : k.transmitted_gauge) +
      "\": the record ends at " + format_resolved(t.back(), dt, 6) + " s" +
      fmt(", %.3g us before the ", (loaded - recorded) * 1e6) +
      (reflected ? "reflected" : "transmitted") + " pulse has passed it (the loading lasts until " +
      format_resolved(loaded, dt, 6) + " s at the faces, the record holds every pulse until " +
      format_resolved(recorded, dt, 6) +
      " s): the curve ends with the record, short of the loading's end; a longer record keeps it");
}

// Where the window at the faces would end if the record held every pulse: the incident duration
// plus a tail, short of the incident pulse's next reflection (2 d_I / c0 later).
double window_end_held(double dt, const PulseTiming& timing, const KolskySetup& k) {
  return std::min(timing.face_start + (1 + kWindowTail) * timing.duration,
                  timing.face_start + 2 * k.incident_distance_m / k.front.c0_m_s - dt);
}

// The pulses cut to a common window at the faces — the incident duration plus a tail, never
// reaching the next reflection of the incident pulse (2 d_I / c0 later) nor the time the record
// holds every pulse to (recorded_at_faces) — and reduced to the curve.
void reduce_at_faces(const std::vector<double>& t, double dt, const FacePulses& f, double recorded,
                     const PulseTiming& timing, const KolskySetup& k,
                     const ProcessingOptions& options, ProcessingResult& r) {
  const double face_end = std::min(window_end_held(dt, timing, k), recorded);
  // The window opens where the specimen is still at rest, and the strain is integrated from zero
  // there: at the last sample at or before the incident pulse's last sample at rest on its gauge
  // (the one before its onset, the first beyond the rest band) moved to the faces. The pulse
  // started somewhere after that sample: a coarse record (500 kS/s) whose front rises between two
  // samples puts its onset up to a sample interval after the start, and a window opened from the
  // onset lost what the specimen strained before (0.003 of an Al 6061 specimen's 0.060 in tension,
  // its max strain 5 % low); one opened after the start at the faces lost 0.004 of a PMMA wafer's
  // 0.053 at 1 MS/s.
  const double at_rest = timing.face_start - dt;
  std::size_t a = index_at(t, at_rest);
  if (a > 0 && (a == t.size() || t[a] > at_rest)) --a;
  const std::size_t b = std::min(index_at(t, face_end) + 1, t.size());
  if (!(b > a + 4))
    throw input_error(
        options.scene_file, "measurement", "gauge \"" + k.incident_gauge + "\"",
        "the pulse window at the specimen faces lies outside the record" +
            (recorded < face_end + dt
                 ? " (it holds every pulse at the faces until " + format_resolved(recorded, dt, 6) +
                       " s, and the loading starts there at " +
                       format_resolved(timing.face_start, dt, 6) +
                       " s: it ends before the reflected or transmitted pulse has reached its "
                       "gauge; a longer record)"
                 : std::string()));
  r.face_start_s = t[a];
  r.face_end_s = t[b - 1];
  r.transmitted_window = {k.transmitted_gauge, t[a] - r.shift_transmitted_s,
                          t[b - 1] - r.shift_transmitted_s, !options.windows.transmitted};
  auto cut = [&](const std::vector<double>& v) {
    return std::vector<double>(v.begin() + static_cast<std::ptrdiff_t>(a),
                               v.begin() + static_cast<std::ptrdiff_t>(b));
  };
  r.time_s = cut(t);
  r.incident = cut(f.ei);
  r.reflected = cut(f.er);
  r.transmitted = cut(f.et);
  const bool forces = !f.fi.empty();
  r.curve = reduce_pulses(r.incident, r.reflected, r.transmitted, forces ? cut(f.fi) : r.incident,
                          forces ? cut(f.fr) : r.reflected, forces ? cut(f.ft) : r.transmitted, dt,
                          k.front, k.back, k.specimen);
}

// The curve ends with loading (docs/methods.md §6): at the primary strain's maximum or, earlier,
// at the first sample from which the 1-wave stress stays below (1 − f) × the peak it had
// reached. The transmitted face carries neither the front face's start-up ringing nor the
// incident–reflected alignment, and a drop that recovers (an early overshoot) is not the end.
// A maximum before `ring_up` (the specimen still ringing up) is an overshoot, not the end of
// loading — an elastic specimen's strain then stays on a plateau below it —, so the load drop is
// then sought to the record's end. Returns whether a load drop ended it.
bool find_loading_end(const std::vector<double>& strain, std::size_t ring_up,
                      const ProcessingOptions& options, ProcessingResult& r) {
  const std::vector<double>& s1 = r.curve.stress_1wave_Pa;
  const auto strain_max =
      static_cast<std::size_t>(std::max_element(strain.begin(), strain.end()) - strain.begin());
  r.record_max_strain = strain[strain_max];
  r.loading_end = strain_max + 1;
  r.loading_end_how = "strain maximum";
  if (options.load_drop <= 0) return false;
  // A maximum reached while the incident pulse still loads the front face at its plateau (within
  // the plateau band of its peak) for a ring-up's span after it is an overshoot as well: under a
  // load that has not begun to fall only an elastic specimen's strain goes down, settling just
  // below its first peak for the whole pulse.
  double incident_peak = 0;
  for (const double e : r.incident) incident_peak = std::max(incident_peak, std::abs(e));
  const bool held =
      ring_up > 0 && strain_max + ring_up < r.incident.size() &&
      std::all_of(r.incident.begin() + strain_max, r.incident.begin() + strain_max + ring_up + 1,
                  [&](double e) { return std::abs(e) >= (1 - kPlateauBand) * incident_peak; });
  const std::size_t last = strain_max < ring_up || held ? strain.size() - 1 : strain_max;
  std::vector<double> later(last + 1);  // largest 1-wave stress from i to `last`
  later[last] = s1[last];
  for (std::size_t i = last; i-- > 0;) later[i] = std::max(s1[i], later[i + 1]);
  double reached = 0;
  for (std::size_t i = 0; i <= last; ++i) {
    reached = std::max(reached, s1[i]);
    if (reached > 0 && later[i] < (1 - options.load_drop) * reached) {
      r.loading_end = i;
      r.loading_end_how =
          fmt("load drop: the 1-wave stress fell below %.3g %% of the peak it had reached and "
              "stayed there",
              100 * (1 - options.load_drop));
      return true;
    }
  }
  return false;
}

// The transmitter's far end, when it closes the chain, reflects the transmitted pulse back to the
// gauge 2(L − x)/c0 after it arrived; a transmitter that short records the pulse and its
// reflection (of the other sign) together from then on, which the 1-wave stress and the strain
// take for the specimen's (a momentum trap or an absorber at that end aside).
void warn_transmitted_echo(const KolskySetup& k, const PulseTiming& timing, double dt,
                           ProcessingResult& r) {
  if (!k.transmitted_far_end_m) return;
  const double arrival = timing.transmitted_onset_s.value_or(r.transmitted_window.start_s);
  const double echo = arrival + 2 * *k.transmitted_far_end_m / k.back.c0_m_s;
  if (!(echo < r.transmitted_window.end_s - kOverlapSamples * dt)) return;
  r.transmitted_echo_s = echo + r.shift_transmitted_s;
  r.warnings.push_back(
      "gauge \"" + k.transmitted_gauge + "\": " +
      fmt("the transmitter's far end, %.3g m beyond it, reflects the transmitted pulse back to it "
          "%.3g us after its onset, %.3g us before the window the curve uses ends: ",
          *k.transmitted_far_end_m, (echo - arrival) * 1e6,
          (r.transmitted_window.end_s - echo) * 1e6) +
      fmt("from there it records the pulse and its reflection together (a momentum trap or an "
          "absorber at that end aside); a transmitter at least %.3g m longer keeps them apart",
          0.5 * k.back.c0_m_s * (r.transmitted_window.end_s - echo)));
}

// What a load drop that ends the curve short says about the specimen (docs/methods.md §6). A
// broken specimen carries no force: its transmitted pulse falls back to its gauge's rest band
// (rest_band: max(5σ, 3 % of the peak)) while the incident pulse still loads the front face. One
// that softens (adiabatic heating, a rate effect) or necks keeps carrying a part of its peak.
// Judged on the median 1-wave stress over the samples after the drop while the incident pulse holds
// its plateau band (a median: the broken specimen's transmitted pulse rings about zero);
// `transmitted_noise` is the transmitted gauge's σ.
std::string load_drop_cause(const ProcessingResult& r, const KolskySetup& k,
                            double transmitted_noise) {
  const std::vector<double>& s1 = r.curve.stress_1wave_Pa;
  const double level = std::abs(r.incident_plateau_strain);
  std::vector<double> after;
  for (std::size_t i = r.loading_end; i < s1.size(); ++i)
    if (std::abs(r.incident[i]) >= (1 - kPlateauBand) * level) after.push_back(s1[i]);
  const double peak = r.peak_stress_1wave_Pa;
  if (after.empty() || !(peak > 0))
    return "the incident pulse no longer loads the front face at its plateau after it, so the drop "
           "is the pulse's unloading, not a fracture; set ";
  std::nth_element(after.begin(), after.begin() + static_cast<std::ptrdiff_t>(after.size() / 2),
                   after.end());
  const double carried = after[after.size() / 2] / peak;
  const double at_rest =
      rest_band(transmitted_noise * k.back.youngs_modulus_Pa * k.back.area_m2 / k.specimen.area_m2,
                peak) /
      peak;
  const std::string median =
      fmt("a median %.3g %% of its peak 1-wave stress over the %.3g us after the drop while the "
          "incident pulse still loads it",
          100 * carried + 0.0,  // + 0: a stress of exactly −0 (a zero strain times −E A) as 0
          static_cast<double>(after.size()) * (r.time_s[1] - r.time_s[0]) * 1e6);
  if (carried <= at_rest)
    return "the specimen broke there: it carries " + median +
           ", the transmitted gauge back at rest; set ";
  return "the specimen still carries " + median +
         fmt(" (a broken one leaves the transmitted gauge at rest, within %.3g %%): it did not "
             "break but softened (adiabatic heating, a rate effect) or necked, and carries force "
             "past the drop; set ",
             100 * at_rest);
}

// The transmitted face's peak stress (docs/methods.md §6): the largest over the loading's first
// `n` samples of a straight line fitted by least squares to the samples of `stress` within
// ±`h` of each (clipped to the loading: one-sided at its ends, where a hardening specimen peaks on
// a ramp the line keeps). The largest single sample of a noisy stress lies about two of the
// noise's s.d. above the stress; the fit's noise is about 1/√(2h + 1) of it. h = 0: the largest
// sample.
double largest_line_fit(const std::vector<double>& stress, std::size_t n, std::size_t h) {
  std::vector<double> sum(n + 1, 0.0), moment(n + 1, 0.0);  // running Σ s_j and Σ j s_j
  for (std::size_t j = 0; j < n; ++j) {
    sum[j + 1] = sum[j] + stress[j];
    moment[j + 1] = moment[j] + static_cast<double>(j) * stress[j];
  }
  double best = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t a = i > h ? i - h : 0, b = std::min(n, i + h + 1);
    const auto m = static_cast<double>(b - a);
    const double centre = 0.5 * static_cast<double>(a + b - 1), sy = sum[b] - sum[a];
    const double sxx = m * (m * m - 1) / 12;  // Σ (j − centre)² over the window
    const double slope = sxx > 0 ? (moment[b] - moment[a] - centre * sy) / sxx : 0;
    best = std::max(best, sy / m + slope * (static_cast<double>(i) - centre));
  }
  return best;
}

// The half-width in samples of the windows the transmitted face's peak is read over: a quarter
// period of the transmitter's dispersion cut-off f_c = 0.2619 c0/a (docs/methods.md §5), above
// which the bar does not carry its 1D stress: the window spans half a period, the shortest feature
// of the stress the bar resolves. 0 (the largest sample) for a bar of unknown radius.
std::size_t resolved_half_window(const BarWaveguide& bar, double dt) {
  if (!(bar.radius_m > 0 && bar.c0_m_s > 0 && dt > 0)) return 0;
  const double cutoff_Hz = kDefaultCutoffFaOverC0 * bar.c0_m_s / bar.radius_m;
  return static_cast<std::size_t>(std::lround(0.25 / (cutoff_Hz * dt)));
}

// Where the transmitted face's stress `s1` starts to unload, as its own record shows it
// (docs/methods.md §6): the end of the samples its peak is read over. The loading ends at the
// strain's maximum `n`, which a transmitted record running ahead of the reflected one (a trigger
// delay) or a fast test's edge (Johnson-Cook copper at 30 m/s) puts a few samples into the
// transmitted pulse's unloading edge, where a window that spans them reads low. The edge's first
// samples fall by less than a noisy record's noise, so it is timed where it is steep: its last
// crossing of 90 % of the peak `level` before it first falls below 50 %. It started to unload as
// long before that 90 % crossing as it takes from there to 50 % (the simulated classic test's
// rounded edge, 0.5 us from 90 to 50 %: at its top sample). That is a step the bar does not
// resolve when it falls from 90 to 50 % within half the half window `h` the peak is read over; an
// edge the bar's band limit spreads (a step low-passed at the cut-off falls from 90 to 50 % in
// about h) has a crest, read by the windows centred on it, where one ending at the crest would
// extrapolate its rising flank (the classic test low-passed at its cut-off, its transmitted record
// 1 us late: +1.7 %). The loading is only shortened, by at most h (a stress below 90 % of its peak
// earlier in the loading softened, its peak lies before): past the strain's maximum the back
// face's stress is no longer the loading's (a bilinear copper at 30 m/s: still rising, 1.9 % above
// the specimen's peak). n when the stress does not fall below half its peak.
std::size_t transmitted_loading_end(const std::vector<double>& s1, std::size_t n, std::size_t h,
                                    double level) {
  if (h == 0 || n == 0 || !(level > 0)) return n;
  const auto top = static_cast<std::size_t>(
      std::max_element(s1.begin(), s1.begin() + static_cast<std::ptrdiff_t>(n)) - s1.begin());
  std::size_t half = top;
  while (half < s1.size() && s1[half] >= 0.5 * level) ++half;
  if (half == s1.size()) return n;
  std::size_t steep = half;  // the last sample at or above 90 % before `half`
  while (steep > top && s1[steep] < 0.9 * level) --steep;
  if (s1[steep] < 0.9 * level) return n;
  auto crossing = [&](std::size_t j, double at) {  // between samples j and j + 1
    return static_cast<double>(j) + (s1[j] - at) / (s1[j] - s1[j + 1]);
  };
  const double t90 = crossing(steep, 0.9 * level), t50 = crossing(half - 1, 0.5 * level);
  if (t50 - t90 > 0.5 * static_cast<double>(h)) return n;
  const double start = std::floor(2 * t90 - t50) + 1;
  const double low = static_cast<double>(n > h ? n - h : 1);
  return static_cast<std::size_t>(std::clamp(start, low, static_cast<double>(n)));
}

// Peaks and strains over the loading, and a warning when a load drop ended the curve well short
// of the record's strain maximum. The peak stresses are read from the line fitted over the
// windows each stress's bars resolve (largest_line_fit): the 3-wave stress's, from both bars'
// pulses, over the coarser one's.
void summarize_loading(bool one_wave, bool dropped, const KolskySetup& k, double transmitted_noise,
                       ProcessingResult& r) {
  const Curve& c = r.curve;
  const std::size_t loaded = r.loading_end;
  auto largest = [loaded](const std::vector<double>& v) {
    return *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(loaded));
  };
  const double dt = r.time_s[1] - r.time_s[0];
  const std::size_t back = resolved_half_window(k.back_waveguide, dt);
  r.peak_stress_3wave_over_loading_Pa = largest(c.stress_3wave_Pa);
  r.peak_stress_3wave_Pa = largest_line_fit(
      c.stress_3wave_Pa, loaded, std::max(resolved_half_window(k.front_waveguide, dt), back));
  r.max_strain_3wave = largest(c.strain);
  const std::vector<double>& s1 = c.stress_1wave_Pa;
  r.peak_stress_1wave_Pa = largest_line_fit(
      s1, transmitted_loading_end(s1, loaded, back, largest_line_fit(s1, loaded, back)), back);
  r.max_strain_1wave = largest(c.strain_1wave);
  r.peak_stress_Pa = headline_peak_stress(r).stress_Pa;
  r.max_strain = one_wave ? r.max_strain_1wave : r.max_strain_3wave;
  if (dropped && r.max_strain < (1 - kLoadDropStrainShortfall) * r.record_max_strain) {
    r.loading_cut_short = true;
    // A drop where the transmitter's far-end reflection reaches its gauge has that cause.
    const bool echo = r.transmitted_echo_s && r.time_s[loaded - 1] >= *r.transmitted_echo_s;
    r.warnings.push_back(
        fmt("the curve ends at a load drop at strain %.3g, short of the record's strain maximum "
            "%.3g (%.3g us after the window start): ",
            r.max_strain, r.record_max_strain, (r.time_s[loaded - 1] - r.time_s[0]) * 1e6) +
        (echo ? "it comes after the transmitter's far-end reflection reached its gauge (above), "
                "which the 1-wave stress takes for a drop: use a longer transmitter, or set "
              : load_drop_cause(r, k, transmitted_noise)) +
        "measurement.load_drop to false to keep the whole loading");
  }
}

// "a to b us" on a record's clock, each end resolving its sample interval dt.
std::string us_range(double from_s, double to_s, double dt) {
  return format_resolved(from_s * 1e6, dt * 1e6, 6) + " to " +
         format_resolved(to_s * 1e6, dt * 1e6, 6) + " us";
}

// The mean strain rate over measurement.rate_window (by strain or by time on the faces' clock).
void mean_rate_in_window(const std::vector<double>& strain, const std::vector<double>& rate,
                         double dt, const ProcessingOptions& options, ProcessingResult& r) {
  if (!options.rate_window) return;
  const RateWindow& w = *options.rate_window;
  const std::size_t loaded = r.loading_end;
  double sum = 0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < loaded; ++i) {
    const double x = w.by_strain ? strain[i] : r.time_s[i];
    if (x >= w.from && x <= w.to) sum += rate[i], ++count;
  }
  if (count == 0)
    throw input_error(
        options.scene_file, "measurement.rate_window",
        w.by_strain ? fmt("strain %.4g to %.4g", w.from, w.to) : us_range(w.from, w.to, dt),
        w.by_strain ? fmt("a range inside the loading (strain 0 to %.4g)", r.max_strain)
                    : "a range inside the loading (faces' clock, as curve.csv's time_s: " +
                          us_range(r.time_s[0], r.time_s[loaded - 1], dt) + ")");
  r.window_strain_rate_1_s = sum / static_cast<double>(count);
}

}  // namespace

double ring_up_strain(const std::vector<double>& t, const std::vector<double>& strain,
                      const std::optional<double>& first_s) {
  double largest = 0;
  for (std::size_t i = 0; first_s && i < std::min(t.size(), strain.size()) && t[i] < *first_s; ++i)
    largest = std::max(largest, strain[i]);
  return largest;
}

ProcessingResult process_signals(const GaugeSignals& signals, const KolskySetup& k,
                                 const ProcessingOptions& options) {
  ProcessingResult r;
  r.warnings = signal_warnings(signals);
  const auto* inc_raw = signals.find(k.incident_gauge);
  const auto* tra_raw = signals.find(k.transmitted_gauge);
  if (!inc_raw || !tra_raw) throw std::logic_error("process_signals: gauge without a signal");
  const double dt = signals.dt_s;
  const auto& t = signals.time_s;
  require_delays_fit(k, dt, options.scene_file);
  const PreparedSignal inc = prepared_signal(signals, k.incident_gauge, options, r);
  const PreparedSignal tra = prepared_signal(signals, k.transmitted_gauge, options, r);
  const auto [on, end] = incident_samples(t, inc, options, r);
  require_pulse_fits_round_trip(k, t[end - 1] - t[on], options.scene_file);
  r.incident_window = {k.incident_gauge, t[on], t[end - 1], r.incident_window.detected};
  const PulseTiming timing = time_the_pulses(t, dt, on, end, inc, tra, k, options, r);
  warn_incident_overlap(k, dt, r);
  const FacePulses faces = pulses_at_faces(inc, tra, dt, timing, k, options, r);
  const RecordedAtFaces recorded = recorded_at_faces(t, faces, inc, tra, r);
  reduce_at_faces(t, dt, faces, recorded.time_s, timing, k, options, r);
  // Corrected before anything is read from the curve: its peaks are the corrected stresses'.
  r.corrections_removed =
      apply_specimen_corrections(r.curve, dt, options.specimen, options.corrections);
  warn_record_ends_in_loading(t, dt, recorded, timing, k, r);
  warn_transmitted_echo(k, timing, dt, r);

  // Summary numbers. The incident plateau over the whole incident pulse at the faces, from the
  // window's start to the pulse's end (or its next reflection), not where the record ends for the
  // reflected or transmitted pulse: a record cut in its reflected pulse read it over the part the
  // window kept (the LANL copper record cut at 215 us: the plateau 1.0 % high, the striker 1.5 %).
  const std::size_t a = index_at(t, r.face_start_s);
  const std::size_t held = std::min(index_at(t, window_end_held(dt, timing, k)) + 1, t.size());
  const std::size_t inc_end =
      std::min(held, index_at(t, timing.face_start + timing.duration)) - std::min(a, held);
  const std::span<const double> incident_held(faces.ei.data() + a, faces.ei.size() - a);
  r.incident_plateau_strain =
      plateau_level(incident_held, 0, first_step_end(k, 0, inc_end, dt), -1.0);
  PulseWindow incident_pulse;
  incident_pulse.onset = on, incident_pulse.end = end, incident_pulse.sign = -1;
  r.inferred_striker_velocity_m_s = striker_velocity_from_plateau(
      k, k.front_waveguide.viscoelastic() ? struck_end_plateau(k, inc.x, dt, incident_pulse)
                                          : r.incident_plateau_strain);
  const Curve& c = r.curve;
  const bool one_wave = options.primary == PrimaryReduction::kOneWave;
  r.primary = options.primary;
  const std::vector<double>& strain = one_wave ? c.strain_1wave : c.strain;
  const std::vector<double>& rate = one_wave ? c.strain_rate_1wave_1_s : c.strain_rate_1_s;
  // The specimen rings up over a few transits once the incident front has risen (Davies & Hunter);
  // without its wave speed no ring-up is assumed.
  const std::size_t ring_up =
      k.specimen_transit_s > 0
          ? index_at(r.time_s,
                     r.time_s[0] + r.incident_rise_s + (1 + kRingUpTransits) * k.specimen_transit_s)
          : 0;
  summarize_loading(one_wave, find_loading_end(strain, ring_up, options, r), k, tra.noise, r);
  judge_strain_rate(rate, r.loading_end, r);
  check_front_resolution(rate, dt, r);
  check_struck_end_band(k, r);
  check_stress_noise(inc.noise, tra.noise, k, one_wave, r);
  mean_rate_in_window(strain, rate, dt, options, r);
  r.area_ratio = k.front.area_m2 / k.specimen.area_m2;
  const ShiftStressError stress_change(r, k, dt);
  warn_reflected_offset(stress_change, k, dt, options, r);
  warn_window_shift(stress_change, t, dt, options.windows.reflected, "reflected",
                    timing.reflected_onset_s, r.reflected, k.front, r);
  warn_window_shift(stress_change, t, dt, options.windows.transmitted, "transmitted",
                    timing.transmitted_onset_s, r.transmitted, k.back, r);
  double peak_force = 0;
  for (std::size_t i = 0; i < r.loading_end; ++i)
    peak_force = std::max(peak_force, c.force_front_N[i] + c.force_back_N[i]);
  // The front face starts to unload where the incident pulse leaves its plateau's band for good
  // (not its peak's: a front that overshoots); the faces' forces part a ring-down (the ring-up's
  // transits) before, as the unloading edge crosses the specimen.
  const double incident_level = std::abs(r.incident_plateau_strain);
  std::size_t unloading = 0;
  for (std::size_t i = 0; i < r.loading_end; ++i)
    if (std::abs(r.incident[i]) >= (1 - kPlateauBand) * incident_level) unloading = i;
  const auto ring_down = static_cast<std::size_t>(kRingUpTransits * k.specimen_transit_s / dt);
  r.equilibrium = judge_equilibrium(c, r.time_s, r.loading_end, peak_force,
                                    unloading > ring_down ? unloading - ring_down : 0, ring_down);
  settle_peak_stress(options, r);
  check_one_wave_rate(c, k, r);
  check_inertia_corrected_faces(c, k, options, r);
  check_one_and_two_wave(c, r.loading_end, r, options, r.warnings);
  check_strain_resolution(c, r.time_s, r.loading_end, k, options, r);
  if (r.equilibrium.holds_from_s)
    r.time_to_equilibrium_s = *r.equilibrium.holds_from_s - r.time_s[0];
  return r;
}

}  // namespace shpb
