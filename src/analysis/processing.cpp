#include "analysis/processing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <tuple>

#include "analysis/dispersion_cutoff.hpp"
#include "analysis/message_text.hpp"
#include "analysis/pulse_window.hpp"
#include "analysis/sample_index.hpp"
#include "analysis/signal_checks.hpp"
#include "core/csv_writer.hpp"  // format_double
#include "core/error.hpp"
#include "core/interpolation.hpp"

namespace shpb {
namespace {

// The face window runs this fraction of the incident duration past its end, so the
// transmitted pulse (delayed by the specimen transit) is not cut.
constexpr double kWindowTail = 0.15;
// Equilibrium is only judged where the mean force is above this fraction of its peak.
constexpr double kMeanForceForEquilibrium = 0.2;
// A detected onset may differ from the geometric one by this many samples (onset picking on a
// sampled, noisy front) or this fraction of the travel time (gauge positions measured to ~1 %,
// wave speeds known to ~1 %) before a gauge position or wave speed is suspected.
constexpr double kAlignmentSamples = 5;
constexpr double kAlignmentFraction = 0.02;
// The transmitted pulse rises over a few transits of the specimen (ring-up, Davies & Hunter).
constexpr double kRingUpTransits = 4;
// A strain-rate plateau: within ±10 % of its level (a constant-rate test is called so within
// about that) for at least 30 % of the loading.
constexpr double kPlateauBand = 0.10;
constexpr double kPlateauMinFraction = 0.30;
// The 1- and 2-wave stresses of a real test differ by tens of percent early in the loading (ring-
// up); a mean ratio beyond 1.5 is not a specimen out of equilibrium but a wrong set-up.
constexpr double kOneTwoWaveRatio = 1.5;
// What a record leaves unknown (an unresolved front's strain, its noise in the stress) is said
// beyond the few percent a curve is read to, of the max strain or the peak stress.
constexpr double kReadTo = 0.03;
// The fastest rate of the window's first samples (the rise and a thin wafer's first ring-up).
constexpr std::size_t kFrontSamples = 4;
// A specimen whose faces move relative to each other at less than this fraction of the incident
// pulse's particle velocity c0 ε_I: a 1 % error in one pulse's amplitude (a gauge factor, a bar's
// modulus) is then more than 20 % of its strain rate.
constexpr double kFaceVelocityDifference = 0.05;

// A fraction as a percentage: three significant digits, whole percent from 100 % up.
std::string percent(double fraction) {
  return fmt(100 * fraction < 99.95 ? "%.3g %%" : "%.0f %%", 100 * fraction);
}

// How far an onset may lie from the geometric one with nothing mistimed: a few samples or a
// fraction of its pulse's travel time from the specimen face to its gauge.
double alignment_tolerance_s(double dt, double travel_s) {
  return std::max(kAlignmentSamples * dt, kAlignmentFraction * travel_s);
}

// How far the reflected onset may lie from the geometric one: the alignment tolerance, and,
// earlier, by as much as the reflected front rises more slowly than the incident one. An onset is
// picked at the foot of its front, and a front that is wider — dispersed over its longer path,
// shaped by the specimen's ring-up, or spread by a model's elements at an interface — has its foot
// earlier by up to its extra rise with nothing mistimed.
double reflected_tolerance_s(const ProcessingResult& r, double dt, double travel_s) {
  const double wider = std::max(0.0, r.reflected_rise_s - r.incident_rise_s);
  return alignment_tolerance_s(dt, travel_s) + (*r.reflected_onset_offset_s < 0 ? wider : 0.0);
}

// A detected onset further from the geometric one than a few samples or 2 % of the travel time
// means a gauge position or a wave speed in the scene is wrong: the reflected pulse has travelled
// 2 d_I (so its offset δ_R = 2 e_I/c0), the transmitted one d_I + d_T (δ_T − δ_R/2 = e_T/c0).
// An incident gauge or bar mistimed moves the transmitted onset (timed from the same incident
// pulse) by half the reflected offset. A reflected offset the transmitted onset does not share,
// while that is on its geometric time, is the reflected pulse's own shape instead: its foot lies
// where the specimen starts to reflect (a thin, stiff wafer under a shaped ramp reflects next to
// nothing until it yields), and no gauge is suspected.
void check_alignment(ProcessingResult& r, const KolskySetup& k, double dt,
                     std::vector<std::string>& warnings) {
  const double c_f = k.front.c0_m_s, c_b = k.back.c0_m_s;
  const double travel_r = 2 * k.incident_distance_m / c_f;
  const double travel_t = k.transmitted_distance_m / c_b;
  // Later than geometry may also be a soft specimen's slow rise: its onset, picked at a few
  // percent of the peak, is uncertain by up to the front's rise.
  auto transmitted_tolerance = [&](double off) {
    return alignment_tolerance_s(dt, travel_t) + kRingUpTransits * k.specimen_transit_s +
           (off > 0 ? r.transmitted_rise_s : 0);
  };
  const bool reflected_off =
      r.reflected_onset_offset_s &&
      std::abs(*r.reflected_onset_offset_s) > reflected_tolerance_s(r, dt, travel_r);
  if (reflected_off && r.transmitted_onset_offset_s) {
    const double own = *r.transmitted_onset_offset_s;
    const double shared = own - 0.5 * *r.reflected_onset_offset_s;
    r.reflected_offset_is_shape = std::abs(own) <= transmitted_tolerance(own) &&
                                  std::abs(shared) > transmitted_tolerance(shared);
    if (r.reflected_offset_is_shape) return;
  }
  if (reflected_off) {
    const double off = *r.reflected_onset_offset_s;
    const double e = 0.5 * off * c_f;  // gauge farther (+) or closer (−) than the scene says
    const double speed = travel_r / (travel_r + off) - 1;  // signed: + faster
    warnings.push_back(
        "gauge \"" + k.incident_gauge + "\": the reflected pulse starts " +
        fmt("%.3g us ", std::abs(off) * 1e6) + (off < 0 ? "earlier" : "later") +
        fmt(" than the geometry predicts (2 x %.4g m / %.5g m/s): the incident gauge is likely "
            "%.3g mm ",
            k.incident_distance_m, c_f, std::abs(e) * 1e3) +
        (e < 0 ? "closer to" : "farther from") +
        fmt(" the specimen than the scene says (distance to specimen %.4g m, not %.4g m; a "
            "position measured from the wrong end?), or the incident bar's wave speed is off by "
            "%.2g %% (%.5g m/s)",
            k.incident_distance_m + e, k.incident_distance_m, 100 * speed, c_f * (1 + speed)));
    r.alignment_suspect = true;
  }
  if (r.transmitted_onset_offset_s) {
    const double off = *r.transmitted_onset_offset_s - 0.5 * r.reflected_onset_offset_s.value_or(0);
    if (std::abs(off) > transmitted_tolerance(off)) {
      const double e = off * c_b;
      warnings.push_back(
          "gauge \"" + k.transmitted_gauge + "\": the transmitted pulse starts " +
          fmt("%.3g us ", std::abs(off) * 1e6) + (off < 0 ? "earlier" : "later") +
          fmt(" than the geometry predicts (%.4g m / %.5g m/s after the specimen): ",
              k.transmitted_distance_m, c_b) +
          (off > 0 ? "a slowly loaded (soft) specimen, or " : "") +
          fmt("the transmitted gauge is likely %.3g mm ", std::abs(e) * 1e3) +
          (e < 0 ? "closer to" : "farther from") +
          fmt(" the specimen than the scene says (distance to specimen %.4g m, not %.4g m), or the "
              "transmitter bar's wave speed is off by %+.2g %%",
              k.transmitted_distance_m + e, k.transmitted_distance_m,
              100 * (travel_t / (travel_t + off) - 1)));
      r.alignment_suspect = true;
    }
  }
}

// The 3-wave strain rate is the difference of the face velocities over L_s (docs/methods.md §6).
// A specimen much stiffer than the bars that stays elastic (a thin metal wafer) moves with them:
// its faces move relative to each other at a small fraction of c0 ε_I, and that fraction divides
// every error of the pulses' amplitudes. The stress, from the forces, is unaffected.
void check_strain_resolution(const Curve& c, const std::vector<double>& t, std::size_t n,
                             const KolskySetup& k, const ProcessingOptions& o,
                             ProcessingResult& r) {
  if (n < 2 || !(r.incident_plateau_strain > 0) || !(k.specimen.length_m > 0)) return;
  const double rate = std::abs(c.strain[n - 1] - c.strain[0]) / (t[n - 1] - t[0]);
  const double part = rate * k.specimen.length_m / (k.front.c0_m_s * r.incident_plateau_strain);
  if (part >= kFaceVelocityDifference) return;
  r.warnings.push_back(
      "the specimen's faces move relative to each other at only " + percent(part) +
      " of the incident pulse's particle velocity (mean 3-wave strain rate " +
      fmt("%.4g 1/s", rate) + " x L_s against c0 x incident strain): a specimen this stiff " +
      "against the bars moves with them, so its strain and strain rate are a small difference " +
      "of face velocities and an error of 1 % in a gauge factor or a bar's modulus is " +
      percent(0.01 / part) + " of them (its " + (o.tension ? "tensile" : "compressive") +
      " stress, from the forces, is not affected)");
}

// A polymer bar's pulse moved back to the struck end (struck_end_plateau) is low-passed where the
// law would grow it more than kMaxLawGain (law_band_limit_Hz). Below kStrikerPulseCycles cycles
// over the striker's pulse the low-passed rise, about half a period, takes a quarter of the pulse
// or more and the plateau read is too low (0.84 of V with 0.9 cycles: a 0.2 GPa long-term
// modulus, the gauge 1.5 m from the struck end).
constexpr double kStrikerPulseCycles = 2.0;
void check_struck_end_band(const KolskySetup& k, ProcessingResult& r) {
  if (!k.striker_round_trip_s || k.pulse_shaper) return;
  const double cutoff_Hz = law_band_limit_Hz(k.front_waveguide, k.incident_gauge_position_m);
  if (cutoff_Hz * *k.striker_round_trip_s >= kStrikerPulseCycles) return;
  r.warnings.push_back(
      "the inferred striker velocity, " + fmt("%.4g m/s", r.inferred_striker_velocity_m_s) +
      ", reads low: moved back to the struck end, " +
      fmt("%.4g m from the incident gauge", k.incident_gauge_position_m) +
      ", the incident pulse is low-passed at " + fmt("%.3g kHz", cutoff_Hz * 1e-3) +
      " (the bar's law would grow it more than " + fmt("%.0f", kMaxLawGain) + " x above), " +
      fmt("%.2g cycles", cutoff_Hz * *k.striker_round_trip_s) + " over the striker's " +
      fmt("%.4g us", *k.striker_round_trip_s * 1e6) +
      " pulse, and its rise does not reach the plateau: set measurement.striker_velocity, or put " +
      "a gauge nearer the struck end");
}

// The incident pulse rising from the rest band to half its peak within a sample interval: the
// record does not say where in that interval the front lies, so the strain the specimen took while
// it rose is known to about ±½ dt × the rate (the trapezoid rule over the window, which opens at
// rest, takes the middle; docs/methods.md §6). That offset is every strain's on the curve.
void check_front_resolution(const std::vector<double>& rate, double dt, ProcessingResult& r) {
  if (r.incident_rise_s > 1.5 * dt || r.loading_end < 2 || !(r.max_strain > 0)) return;
  double fastest = 0;
  for (std::size_t i = 0; i < std::min(r.loading_end, kFrontSamples); ++i)
    fastest = std::max(fastest, std::abs(rate[i]));
  const double uncertain = 0.5 * dt * fastest;
  if (uncertain <= kReadTo * r.max_strain) return;
  r.warnings.push_back(
      fmt("the incident pulse rises from rest to half its peak within a sample interval (%.3g us): "
          "the record does not resolve its front, so the strain the specimen took while it rose "
          "(at up to %.4g 1/s) is known to about %.2g, ",
          dt * 1e6, fastest, uncertain) +
      percent(uncertain / r.max_strain) +
      fmt(" of the max strain %.3g, and every strain of the curve carries that offset; record "
          "at a higher sample rate",
          r.max_strain));
}

// The records' noise (σ of their quiet starts, as the pulse search takes it) reaches the primary
// stress sample by sample multiplied by the bar/specimen area ratio: the 3-wave stress carries
// √(2 (E_f A_f σ_I)² + (E_b A_b σ_T)²) / 2A_s (the incident gauge gives the incident and the
// reflected pulse), the 1-wave E_b A_b σ_T / A_s (docs/methods.md §6).
void check_stress_noise(double incident_noise, double transmitted_noise, const KolskySetup& k,
                        bool one_wave, ProcessingResult& r) {
  const double front = k.front.youngs_modulus_Pa * k.front.area_m2 * incident_noise;
  const double back = k.back.youngs_modulus_Pa * k.back.area_m2 * transmitted_noise;
  const double noise = one_wave
                           ? back / k.specimen.area_m2
                           : std::sqrt(2 * front * front + back * back) / (2 * k.specimen.area_m2);
  if (!(r.peak_stress_Pa > 0) || noise <= kReadTo * r.peak_stress_Pa) return;
  r.warnings.push_back(
      fmt("the records' noise (standard deviation %.3g on the incident gauge, %.3g on the "
          "transmitted one, from their quiet starts) reaches the ",
          incident_noise, transmitted_noise) +
      (one_wave ? "1-wave" : "3-wave") +
      fmt(" stress multiplied by the bar/specimen area ratio (%.3g): ±%.3g MPa sample by "
          "sample, ",
          k.front.area_m2 / k.specimen.area_m2, noise * 1e-6) +
      percent(noise / r.peak_stress_Pa) +
      " of its peak; read the curve smoothed, or record with less noise or a larger specimen");
}

// A plateau of the strain rate: the longest run of samples within ±10 % of the plateau level
// (plateau_level) spans at least 30 % of the loading (the samples with a positive rate). Without
// one, no plateau rate is quoted, only the mean over the loading.
void judge_strain_rate(const std::vector<double>& rate, std::size_t n, ProcessingResult& r) {
  const double level = plateau_level(rate, 0, n, 1.0);
  std::size_t positive = 0, run = 0, longest = 0;
  double sum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (rate[i] > 0) ++positive, sum += rate[i];
    run = std::abs(rate[i] - level) <= kPlateauBand * level ? run + 1 : 0;
    longest = std::max(longest, run);
  }
  r.mean_strain_rate_1_s = positive ? sum / static_cast<double>(positive) : 0;
  r.strain_rate_plateau_fraction =
      positive ? static_cast<double>(longest) / static_cast<double>(positive) : 0;
  r.strain_rate_has_plateau = level > 0 && r.strain_rate_plateau_fraction >= kPlateauMinFraction;
  r.plateau_strain_rate_1_s = level;
}

// The 1-wave (transmitted) and 2-wave (incident + reflected) stresses of one specimen agree
// within tens of percent once it is loaded; a larger disagreement is said with its size, and with
// a cause only where the record shows one: a first pulse of the other polarity than the test's,
// or a reflected onset off its geometric position by enough to move the 2-wave stress.
// Loaded: where the 1-wave stress is at least 20 % of its peak (the front face's start-up
// ringing, large on a thin specimen, would otherwise set the scale).
void check_one_and_two_wave(const Curve& c, std::size_t n, const ProcessingResult& r,
                            const ProcessingOptions& o, std::vector<std::string>& warnings) {
  const double peak = *std::max_element(c.stress_1wave_Pa.begin(),
                                        c.stress_1wave_Pa.begin() + static_cast<std::ptrdiff_t>(n));
  double one = 0, two = 0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (peak > 0 && c.stress_1wave_Pa[i] >= kMeanForceForEquilibrium * peak) {
      one += c.stress_1wave_Pa[i], two += c.stress_2wave_Pa[i];
      ++count;
    }
  if (count == 0) return;
  one /= static_cast<double>(count), two /= static_cast<double>(count);
  const double ratio = two / one;
  if (ratio > 1 / kOneTwoWaveRatio && ratio < kOneTwoWaveRatio) return;
  std::string text =
      fmt("the 1-wave and 2-wave stresses disagree over the loading (means %.4g and %.4g MPa, "
          "ratio %.3g)",
          one * 1e-6, two * 1e-6, ratio);
  std::string evidence;
  for (const std::string& g : r.inverted_gauges)
    evidence += (evidence.empty() ? "" : "; ") + ("gauge \"" + g + "\"'s first pulse was ") +
                (o.tension ? "compressive" : "tensile") + " and was inverted (a " +
                (o.tension ? "compressive" : "tensile") + " record, or its channel's `invert`?)";
  if (r.incident_overlap_s > 0)
    evidence += (evidence.empty() ? "" : "; ") +
                fmt("the incident pulse overlaps the reflected one at its gauge for %.3g us",
                    r.incident_overlap_s * 1e6);
  if (r.reflected_onset_offset_s && !r.reflected_at_onset && !r.reflected_offset_is_shape &&
      r.reflected_offset_stress_error && *r.reflected_offset_stress_error > kShiftStressError)
    evidence += (evidence.empty() ? "" : "; ") +
                fmt("the reflected pulse starts %.3g us off its geometric position, which alone "
                    "moves the 2-wave stress by up to ",
                    *r.reflected_onset_offset_s * 1e6) +
                percent(2 * *r.reflected_offset_stress_error) + " of the 1-wave peak";
  if (!evidence.empty())
    text += ": " + evidence;
  else
    text += std::string(": the first pulses have the polarity of the test and ") +
            (r.reflected_at_onset ? "the reflected pulse was aligned at its onset"
                                  : "the onsets agree with the geometry") +
            ", so the record's polarity and timing do not explain it; the forces of the two "
            "faces differ (bar areas or moduli, a channel's scale or bridge factor, which gauge "
            "is which)";
  warnings.push_back(text);
}

// One gauge sees the incident and the reflected pulse pass in turn. A pulse longer than its round
// trip 2d/c0 to the specimen and back (a long striker, a gauge near the specimen, a polymer bar's
// creep tail) still passes when its reflection arrives, and the record holds their sum: the
// reflected pulse, the 2-wave stress and the strain carry what overlaps (docs/methods.md §6).
// Overlapping by more than this many samples is said.
constexpr double kOverlapSamples = 2;
void warn_incident_overlap(const KolskySetup& k, double dt, ProcessingResult& r) {
  const double overlap = r.incident_window.end_s - r.reflected_window.start_s;
  if (!(overlap > kOverlapSamples * dt)) return;
  r.incident_overlap_s = overlap;
  const double length = r.incident_window.end_s - r.incident_window.start_s;
  r.warnings.push_back(
      "gauge \"" + k.incident_gauge + "\": " +
      fmt("the incident pulse still passes it %.3g us after the reflected pulse arrives (round "
          "trip 2d/c0 %.3g us, the pulse %.3g us long there), and one gauge records their sum: ",
          overlap * 1e6, 2 * k.incident_distance_m / k.front.c0_m_s * 1e6, length * 1e6) +
      fmt("the reflected pulse, the 2-wave stress, the strain and its rate carry the overlap; a "
          "gauge at least c0 T/2 = %.3g m from the specimen separates them",
          0.5 * k.front.c0_m_s * length));
}

// Largest |y(t + shift) − y(t)| over the flagged samples: how much a pulse at the faces changes
// when it is moved by `shift_samples` (linear between samples, zero outside the window).
double largest_change_on_shift(const std::vector<double>& y, double shift_samples,
                               const std::vector<char>& where) {
  double worst = 0;
  for (std::size_t i = 0; i < y.size(); ++i)
    if (where[i])
      worst = std::max(worst,
                       std::abs(sample_at(y, static_cast<double>(i) + shift_samples, 0, 0) - y[i]));
  return worst;
}

// Loaded: from the first to the last sample where the mean force is at least 20 % of its peak.
// Among those, the fraction with R ≤ 5 %, the longest run of them, and the run that reaches the
// unloading (equilibrium that holds until unloading): the sample `unloading` where the incident
// pulse's falling edge, less the specimen's ring-down, reaches the front face, or the last loaded
// sample before it. The front face unloads first, so R rises on that edge in every test. A run
// shorter than `ring_down` samples is not equilibrium.
Equilibrium judge_equilibrium(const Curve& c, const std::vector<double>& t, std::size_t n,
                              double peak_force, std::size_t unloading, std::size_t ring_down) {
  Equilibrium e;
  std::size_t first = n, last = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (c.force_front_N[i] + c.force_back_N[i] >= kMeanForceForEquilibrium * peak_force) {
      first = std::min(first, i);
      last = i;
    }
  if (first > last) return e;
  e.loaded_s = {t[first], t[last]};
  auto in_equilibrium = [&](std::size_t i) {
    return c.equilibrium_ratio[i] <= kEquilibriumThreshold;
  };
  std::size_t held = 0, run_start = first, best_start = first, best_length = 0;
  for (std::size_t i = first; i <= last; ++i) {
    const bool ok = in_equilibrium(i);
    held += ok;
    if (!ok) {
      run_start = i + 1;
      continue;
    }
    if (i + 1 - run_start > best_length) best_start = run_start, best_length = i + 1 - run_start;
  }
  e.fraction = static_cast<double>(held) / static_cast<double>(last + 1 - first);
  if (best_length > 0) e.longest_s = {t[best_start], t[best_start + best_length - 1]};
  // The run of R ≤ 5 % through `until`, if it lasts a ring-down at least (forces that agree over
  // a few transits, not at one sample the ringing passes through).
  const std::size_t until = std::min(last, std::max(first, unloading));
  std::size_t from = until + 1, to = until;
  for (std::size_t i = until + 1; i-- > first && in_equilibrium(i);) from = i;
  while (to < last && in_equilibrium(to + 1)) ++to;
  if (from <= until && to + 1 - from >= std::max<std::size_t>(1, ring_down))
    e.holds_from_s = t[from];
  return e;
}

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
  RestSignal s = signal_from_rest(*signals.find(gauge), -1.0);
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
  const double expected_t = t[on] + d_i / c_front + k.specimen_transit_s + d_t / c_back +
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
  // It is sought from the incident pulse's first sample at rest, and only a pulse rising beyond
  // twice the band the incident pulse ended within is one: a smaller one (a specimen matched to
  // the bar reflects next to nothing, docs/methods.md §6) cannot be told from the incident's tail.
  const double travel_r = 2 * d_i / c_front;
  const bool apart = t[end - 1] < t[on] + travel_r - alignment_tolerance_s(dt, travel_r);
  const auto i1 = index_at(t, expected_r + p.duration);
  const double min_peak = 2 * rest_band(inc.noise, incident_peak);
  if (const auto o = apart
                         ? find_onset(inc.x, {0.0, inc.noise}, reflected_sign(k), end, i1, min_peak)
                         : std::nullopt) {
    p.reflected_onset_s = t[o->onset];
    r.reflected_onset_offset_s = t[o->onset] - expected_r;
    r.reflected_rise_s = t[o->half] - t[o->onset];
  }
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
                   WaveQuantity q) {
    PropagationOptions o = po;
    o.amplitude = a;
    o.quantity = q;
    o.cutoff_fa_over_c0 = cutoff_fa_over_c0(ds, w);
    if (!ds.correction) {
      Propagator p(w, o);
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
    return delayed(p.propagate(x, dt, distance), extra);
  };
  const double d_i = k.incident_distance_m, d_t = k.transmitted_distance_m;
  const auto kin = ds.amplitude_factors ? AmplitudeFactor::kStrain : AmplitudeFactor::kNone;
  // The kinematic pulses give the faces' velocities, the force pulses their forces: one pulse in
  // an elastic bar without amplitude factors, two in a viscoelastic one (methods.md §5.1).
  constexpr auto kVelocity = WaveQuantity::kVelocity, kForce = WaveQuantity::kForce;
  FacePulses f;
  f.ei = moved(inc.x, k.front_waveguide, front, d_i, 0, kin, kVelocity);
  f.er = moved(inc.x, k.front_waveguide, front, -d_i, timing.extra_r, kin, kVelocity);
  f.et = moved(tra.x, k.back_waveguide, back, -d_t, timing.extra_t, kin, kVelocity);
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

// The pulses cut to a common window at the faces — the incident duration plus a tail, never
// reaching the next reflection of the incident pulse (2 d_I / c0 later) nor the record's end —
// and reduced to the curve.
void reduce_at_faces(const std::vector<double>& t, double dt, const FacePulses& f,
                     const PulseTiming& timing, const KolskySetup& k,
                     const ProcessingOptions& options, ProcessingResult& r) {
  double face_end = timing.face_start + (1 + kWindowTail) * timing.duration;
  face_end = std::min(
      {face_end, timing.face_start + 2 * k.incident_distance_m / k.front.c0_m_s - dt, t.back()});
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
    throw input_error(options.scene_file, "measurement", "gauge \"" + k.incident_gauge + "\"",
                      "the pulse window at the specimen faces lies outside the record");
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

// Peaks and strains over the loading, and a warning when a load drop ended the curve well short
// of the record's strain maximum.
void summarize_loading(bool one_wave, bool dropped, ProcessingResult& r) {
  const Curve& c = r.curve;
  const std::size_t loaded = r.loading_end;
  auto largest = [loaded](const std::vector<double>& v) {
    return *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(loaded));
  };
  r.peak_stress_3wave_Pa = largest(c.stress_3wave_Pa);
  r.max_strain_3wave = largest(c.strain);
  r.peak_stress_1wave_Pa = largest(c.stress_1wave_Pa);
  r.max_strain_1wave = largest(c.strain_1wave);
  r.peak_stress_Pa = one_wave ? r.peak_stress_1wave_Pa : r.peak_stress_3wave_Pa;
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
              : "a specimen that broke there, or set ") +
        "measurement.load_drop to false to keep the whole loading");
  }
}

// The mean strain rate over measurement.rate_window (by strain or by time on the faces' clock).
void mean_rate_in_window(const std::vector<double>& strain, const std::vector<double>& rate,
                         const ProcessingOptions& options, ProcessingResult& r) {
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
    throw input_error(options.scene_file, "measurement.rate_window",
                      w.by_strain ? fmt("strain %.4g to %.4g", w.from, w.to)
                                  : fmt("%.6g to %.6g us", w.from * 1e6, w.to * 1e6),
                      w.by_strain
                          ? fmt("a range inside the loading (strain 0 to %.4g)", r.max_strain)
                          : fmt("a range inside the loading (faces' clock, as curve.csv's time_s: "
                                "%.6g to %.6g us)",
                                r.time_s[0] * 1e6, r.time_s[loaded - 1] * 1e6));
  r.window_strain_rate_1_s = sum / static_cast<double>(count);
}

// What a time shift of a pulse at the faces does to the stress: the largest change of the 3-wave
// stress, ½ E_f A_f |Δε| / A_s, over the transmitted face's loading (1-wave stress ≥ 20 % of its
// peak), as a fraction of the 1-wave peak (docs/methods.md §6).
class ShiftStressError {
 public:
  ShiftStressError(const ProcessingResult& r, const KolskySetup& k, double dt)
      : k_(k), dt_(dt), s1_peak_(max_of(r.curve.stress_1wave_Pa)) {
    const std::vector<double>& s1 = r.curve.stress_1wave_Pa;
    loaded_.resize(s1.size());
    for (std::size_t i = 0; i < s1.size(); ++i)
      loaded_[i] = s1[i] >= kMeanForceForEquilibrium * s1_peak_;
  }
  bool has_scale() const { return s1_peak_ > 0; }
  double operator()(const std::vector<double>& pulse, const BarSide& bar, double shift_s) const {
    const double change = largest_change_on_shift(pulse, shift_s / dt_, loaded_);
    return 0.5 * bar.youngs_modulus_Pa * bar.area_m2 * change / (k_.specimen.area_m2 * s1_peak_);
  }

 private:
  static double max_of(const std::vector<double>& v) {
    return *std::max_element(v.begin(), v.end());
  }
  const KolskySetup& k_;
  double dt_, s1_peak_;
  std::vector<char> loaded_;
};

// The reflected pulse's onset offset, when it is not applied and changes the stress by more than
// kShiftStressError: said, beside the gauge-position warning check_alignment may have given.
void warn_reflected_offset(const ShiftStressError& stress_change, const KolskySetup& k, double dt,
                           const ProcessingOptions& options, ProcessingResult& r) {
  if (stress_change.has_scale() && r.reflected_onset_offset_s)
    r.reflected_offset_stress_error =
        stress_change(r.reflected, k.front, *r.reflected_onset_offset_s);
  if (!(stress_change.has_scale() && r.reflected_offset_stress_error &&
        !options.windows.reflected && !r.reflected_at_onset && !r.reflected_offset_is_shape &&
        std::abs(*r.reflected_onset_offset_s) > reflected_tolerance_s(r, dt, 0) &&
        *r.reflected_offset_stress_error > kShiftStressError))
    return;
  const std::string effect =
      fmt("at this bar/specimen area ratio (%.3g) and strain rate (%.4g 1/s) that offset "
          "changes the 3-wave stress by up to ",
          r.area_ratio,
          r.strain_rate_has_plateau ? r.plateau_strain_rate_1_s : r.mean_strain_rate_1_s) +
      percent(*r.reflected_offset_stress_error) +
      " of the 1-wave peak (the 2-wave stress twice that): if the onsets are right (a trigger "
      "delay, a gauge position), set \"align\": \"onsets\"; \"primary\": \"1-wave\" "
      "reports a stress that does not use the reflected pulse";
  // One warning per offset: added to the gauge-position warning when check_alignment gave one.
  const std::string position = "gauge \"" + k.incident_gauge + "\": the reflected pulse starts";
  const auto given = std::find_if(r.warnings.begin(), r.warnings.end(),
                                  [&](const auto& w) { return w.rfind(position, 0) == 0; });
  if (given != r.warnings.end())
    *given += "; " + effect;
  else
    r.warnings.push_back(
        fmt("the reflected pulse starts %.3g us ", std::abs(*r.reflected_onset_offset_s) * 1e6) +
        (*r.reflected_onset_offset_s < 0 ? "earlier" : "later") +
        " than the gauge distances and wave speed put it; " + effect);
}

// A hand-set reflected or transmitted window is a time shift: one whose start is far from the
// detected onset moves the pulse by that much (docs/scene-format.md).
void warn_window_shift(const ShiftStressError& stress_change, const std::vector<double>& t,
                       double dt, const std::optional<TimeWindow>& w, const std::string& name,
                       const std::optional<double>& onset_s, const std::vector<double>& pulse,
                       const BarSide& bar, ProcessingResult& r) {
  if (!w || !onset_s || !stress_change.has_scale()) return;
  const double off = t[nearest_sample(t, w->start_s)] - *onset_s;
  if (std::abs(off) <= kAlignmentSamples * dt) return;
  const double error = stress_change(pulse, bar, -off);
  if (error <= kShiftStressError) return;
  r.warnings.push_back(
      "measurement.windows." + name + fmt(" starts %.3g us ", std::abs(off) * 1e6) +
      (off < 0 ? "before" : "after") +
      fmt(" the pulse's detected onset (%.6g us): a window is a time shift, so it moves the "
          "pulse %.3g us at the faces, which changes the 3-wave stress by up to ",
          *onset_s * 1e6, std::abs(off) * 1e6) +
      percent(error) +
      " of the 1-wave peak; start the window at the onset, or leave it to detection");
}

}  // namespace

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
  reduce_at_faces(t, dt, pulses_at_faces(inc, tra, dt, timing, k, options, r), timing, k, options,
                  r);
  warn_transmitted_echo(k, timing, dt, r);

  // Summary numbers.
  const std::size_t inc_end =
      std::min(r.time_s.size(), index_at(r.time_s, timing.face_start + timing.duration));
  r.incident_plateau_strain = plateau_level(r.incident, 0, first_step_end(k, 0, inc_end, dt), -1.0);
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
  summarize_loading(one_wave, find_loading_end(strain, ring_up, options, r), r);
  judge_strain_rate(rate, r.loading_end, r);
  check_front_resolution(rate, dt, r);
  check_struck_end_band(k, r);
  check_stress_noise(inc.noise, tra.noise, k, one_wave, r);
  mean_rate_in_window(strain, rate, options, r);
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
  check_one_and_two_wave(c, r.loading_end, r, options, r.warnings);
  check_strain_resolution(c, r.time_s, r.loading_end, k, options, r);
  if (r.equilibrium.holds_from_s)
    r.time_to_equilibrium_s = *r.equilibrium.holds_from_s - r.time_s[0];
  return r;
}

}  // namespace shpb
