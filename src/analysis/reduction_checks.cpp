#include "analysis/reduction_checks.hpp"

#include <algorithm>
#include <cmath>

#include "analysis/message_text.hpp"
#include "analysis/pulse_window.hpp"
#include "analysis/sample_index.hpp"
#include "core/interpolation.hpp"
#include "core/median.hpp"
#include "core/number_format.hpp"
#include "dispersion/propagation.hpp"

namespace shpb {
namespace {

// Equilibrium is only judged where the mean force is above this fraction of its peak.
constexpr double kMeanForceForEquilibrium = 0.2;
// A detected onset may differ from the geometric one by this many samples (onset picking on a
// sampled, noisy front) or this fraction of the travel time (gauge positions measured to ~1 %,
// wave speeds known to ~1 %) before a gauge position or wave speed is suspected.
constexpr double kAlignmentSamples = 5;
constexpr double kAlignmentFraction = 0.02;
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
// A shift of a pulse at the faces that changes the 3-wave stress by more than 5 % of the 1-wave
// peak is warned about: beyond the 5 % spread of the two face forces accepted as equilibrium, it
// changes what is read as the specimen's response.
constexpr double kShiftStressError = 0.05;

// A fraction as a percentage: three significant digits, whole percent from 100 % up.
std::string percent(double fraction) {
  return fmt(100 * fraction < 99.95 ? "%.3g %%" : "%.0f %%", 100 * fraction);
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

}  // namespace

double alignment_tolerance_s(double dt, double travel_s) {
  return std::max(kAlignmentSamples * dt, kAlignmentFraction * travel_s);
}

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

void check_inertia_corrected_faces(const Curve& c, const KolskySetup& k, const ProcessingOptions& o,
                                   ProcessingResult& r) {
  if (!o.corrections.inertia || !(o.specimen.density_kg_m3 > 0) || !r.equilibrium.loaded_s) return;
  const std::size_t first = index_at(r.time_s, r.equilibrium.loaded_s->first);
  const std::size_t last = index_at(r.time_s, r.equilibrium.loaded_s->second);
  const std::vector<double> corrected = equilibrium_ratio(c.stress_2wave_Pa, c.stress_1wave_Pa);
  std::vector<double> apart, stray;
  for (std::size_t i = first; i <= last && i < corrected.size(); ++i)
    if (c.equilibrium_ratio[i] <= kEquilibriumThreshold && c.stress_3wave_Pa[i] > 0) {
      apart.push_back(corrected[i]);
      stray.push_back(std::abs(c.stress_1wave_Pa[i] / c.stress_3wave_Pa[i] - 1));
    }
  const double span_us = static_cast<double>(apart.size()) * (r.time_s[1] - r.time_s[0]) * 1e6;
  const double median_apart = median(std::move(apart));
  if (!(median_apart > kEquilibriumThreshold)) return;
  std::string text =
      fmt("where the specimen's faces' forces agree (R = 2|P1 - P2|/|P1 + P2| <= %.3g, %.3g us "
          "of its loading), its inertia correction parts them: the corrected 2-wave and 1-wave "
          "stresses there have R a median %.3g. The correction takes the specimen to strain "
          "uniformly (its velocity linear from face to face), its faces' forces then differing by "
          "its mass times the mean of its faces' accelerations; forces that agree while its faces "
          "accelerate apart say that its mass does not follow their mean, and its corrected "
          "1-wave (transmitted face's) and 2-wave (incident face's) stresses stray a median ",
          kEquilibriumThreshold, span_us, median_apart) +
      percent(median(std::move(stray))) +
      " each way from the 3-wave one, the faces' average, which does not depend on the "
      "specimen's acceleration as a whole and is the one to read. A specimen strains uniformly "
      "once a strain increment crosses it several times within the rise: ";
  if (k.specimen_transit_s > 0)
    text += fmt("elastically in L/c0 = %.3g us here, against the incident rise of %.3g us, ",
                k.specimen_transit_s * 1e6, r.incident_rise_s * 1e6);
  text +=
      "and, where it flows, at sqrt((dsigma/deps)/rho), slow where its stress-strain curve is "
      "flat (a perfectly plastic specimen's only from its growing area)";
  r.warnings.push_back(text);
}

void check_one_wave_rate(const Curve& c, const KolskySetup& k, ProcessingResult& r) {
  if (r.primary != PrimaryReduction::kOneWave || !r.equilibrium.loaded_s) return;
  const std::size_t first = index_at(r.time_s, r.equilibrium.loaded_s->first);
  const std::size_t last = index_at(r.time_s, r.equilibrium.loaded_s->second);
  std::vector<double> difference, ratio, gain;
  double sum = 0;
  for (std::size_t i = first; i <= last && i < r.time_s.size(); ++i) {
    const double rate = c.strain_rate_1_s[i];
    if (!(rate > 0)) continue;
    const double mean_force = 0.5 * (c.force_front_N[i] + c.force_back_N[i]);
    sum += rate;
    difference.push_back(std::abs(c.strain_rate_1wave_1_s[i] - rate));
    ratio.push_back(c.equilibrium_ratio[i]);
    gain.push_back(k.front.c0_m_s * mean_force /
                   (k.front.youngs_modulus_Pa * k.front.area_m2 * k.specimen.length_m * rate));
  }
  if (difference.empty()) return;
  const double mean_rate = sum / static_cast<double>(difference.size());
  const double off = median(difference) / mean_rate;
  if (off <= kOneWaveRateError) return;
  // The strains part by the integral of the difference: small where the mismatch changes sign.
  double apart = 0;
  for (std::size_t i = 0; i < r.loading_end; ++i)
    apart = std::max(apart, std::abs(c.strain_1wave[i] - c.strain[i]));
  r.warnings.push_back(
      "the 1-wave strain rate (the primary) is the 3-wave rate plus c0 (P2 - P1)/(E A L_s): it "
      "assumes the faces' forces equal, and differs from the 3-wave rate, which needs no "
      "equilibrium, by a median " +
      percent(off) +
      fmt(" of the mean 3-wave rate %.4g 1/s over the loading (its strain by up to ", mean_rate) +
      percent(apart / std::max(r.max_strain, 1e-300)) +
      fmt(" of the max strain %.3g): the face forces differ by a median R = ", r.max_strain) +
      percent(median(ratio)) +
      fmt(", and the specimen's force as a particle velocity in the incident bar is a median %.3g "
          "x its faces' relative velocity, the factor R takes into the rate (large for a "
          "specimen near the bar's impedance or strong against its rate: a transmitted pulse "
          "large against the reflected one); \"primary\": \"3-wave\" gives the strain and "
          "its rate without that assumption",
          median(gain)));
}

void warn_incident_overlap(const KolskySetup& k, double dt, ProcessingResult& r) {
  const double length =
      std::max(r.incident_window.end_s - r.incident_window.start_s, r.incident_length_s);
  const double overlap = r.incident_window.start_s + length - r.reflected_window.start_s;
  if (!(overlap > kOverlapSamples * dt)) return;
  r.incident_overlap_s = overlap;
  r.warnings.push_back(
      "gauge \"" + k.incident_gauge + "\": " +
      fmt("the incident pulse still passes it %.3g us after the reflected pulse arrives (round "
          "trip 2d/c0 %.3g us, the pulse %.3g us long there), and one gauge records their sum: ",
          overlap * 1e6, 2 * k.incident_distance_m / k.front.c0_m_s * 1e6, length * 1e6) +
      fmt("the reflected pulse, the 2-wave stress, the strain and its rate carry the overlap; a "
          "gauge at least c0 T/2 = %.3g m from the specimen separates them",
          0.5 * k.front.c0_m_s * length));
}

void settle_peak_stress(const ProcessingOptions& options, ProcessingResult& r) {
  const Equilibrium& e = r.equilibrium;
  r.peak_in_equilibrium = options.peak_in_equilibrium.value_or(
      e.peak_3wave_Pa && (e.holds_from_s.has_value() || e.fraction >= kMostlyInEquilibrium));
  if (r.peak_in_equilibrium) {
    if (e.peak_3wave_Pa) r.peak_stress_3wave_Pa = *e.peak_3wave_Pa;
  } else if (e.loaded_s && !options.peak_in_equilibrium.has_value()) {
    r.warnings.push_back(
        fmt("the specimen is in equilibrium (R = 2|P1-P2|/|P1+P2| <= %.3g) over only %.3g %% of "
            "its loading and not until it unloads: outside equilibrium its stresses are the face "
            "forces over its area, not a material's stress, and the peak 3-wave stress %.4g MPa "
            "is read over the whole loading, its ring-up and unloading fronts included, from the "
            "line fitted over the half period both bars resolve (the 1-wave, transmitted face's, "
            "%.4g MPa)",
            kEquilibriumThreshold, 100 * e.fraction, r.peak_stress_3wave_Pa / 1e6,
            r.peak_stress_1wave_Pa / 1e6));
  }
  r.peak_stress_Pa = headline_peak_stress(r).stress_Pa;
}

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
    if (ok && !e.first_s) e.first_s = t[i];
    held += ok;
    if (!ok) {
      run_start = i + 1;
      continue;
    }
    e.peak_3wave_Pa =
        std::max(e.peak_3wave_Pa.value_or(c.stress_3wave_Pa[i]), c.stress_3wave_Pa[i]);
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

ShiftStressError::ShiftStressError(const ProcessingResult& r, const KolskySetup& k, double dt)
    : k_(k), dt_(dt), s1_peak_(max_of(r.curve.stress_1wave_Pa)) {
  const std::vector<double>& s1 = r.curve.stress_1wave_Pa;
  loaded_.resize(s1.size());
  for (std::size_t i = 0; i < s1.size(); ++i)
    loaded_[i] = s1[i] >= kMeanForceForEquilibrium * s1_peak_;
}

double ShiftStressError::operator()(const std::vector<double>& pulse, const BarSide& bar,
                                    double shift_s) const {
  const double change = largest_change_on_shift(pulse, shift_s / dt_, loaded_);
  return 0.5 * bar.youngs_modulus_Pa * bar.area_m2 * change / (k_.specimen.area_m2 * s1_peak_);
}

double ShiftStressError::max_of(const std::vector<double>& v) {
  return *std::max_element(v.begin(), v.end());
}

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
      (off < 0 ? "before" : "after") + " the pulse's detected onset (" +
      format_resolved(*onset_s * 1e6, dt * 1e6, 6) +
      fmt(" us): a window is a time shift, so it moves the pulse %.3g us at the faces, which "
          "changes the 3-wave stress by up to ",
          std::abs(off) * 1e6) +
      percent(error) +
      " of the 1-wave peak; start the window at the onset, or leave it to detection");
}

}  // namespace shpb
