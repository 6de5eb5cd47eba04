#include "analysis/signal_checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "analysis/message_text.hpp"
#include "core/correlation.hpp"
#include "core/csv_writer.hpp"  // format_double
#include "core/error.hpp"

namespace shpb {
namespace {

// The clipping warning of the record of gauge `name` (signal_checks.hpp), if it looks clipped or
// may be: an established clip first.
std::optional<std::string> clipping_warning(const std::string& name, const std::vector<double>& x,
                                            const FullScale& range) {
  const std::vector<ClippedLevel> levels = clipped_levels(x, range);
  if (levels.empty()) return std::nullopt;
  const auto found = std::find_if(levels.begin(), levels.end(),
                                  [](const ClippedLevel& l) { return l.established; });
  const ClippedLevel& c = found != levels.end() ? *found : levels.front();
  const std::string seen = "gauge \"" + name + "\": " + std::to_string(c.run) +
                           " consecutive samples at the record's extreme " +
                           format_double(c.level) + " (" + std::to_string(c.at_level) +
                           " samples at that level, " + std::to_string(c.at_next) +
                           " at the next one)";
  if (c.established)
    return seen +
           ": the signal looks clipped (amplifier or digitizer range); pulses and the striker "
           "velocity inferred from it are too small";
  return seen +
         ": the signal may be clipped (amplifier or digitizer range), or its top is flat: its "
         "noise is too small against the digitizer's step to tell; its samples are read as "
         "values (state the channel's full scale, measurement.channels[].range, to settle it)";
}

// The widest stretch around level c's run whose samples lie within `depth` of its level.
std::size_t width_within(const std::vector<double>& x, const ClippedLevel& c, double depth,
                         double inward) {
  std::size_t a = c.run_start, b = c.run_start + c.run;
  while (a > 0 && inward * (c.level - x[a - 1]) <= depth) --a;
  while (b < x.size() && inward * (c.level - x[b]) <= depth) ++b;
  return b - a;
}

// Whether a smooth top on a grid of step q explains level c's run (signal_checks.hpp): a parabola
// rounded to the grid stays at its top level (within q/2 below it) over w₀, within 2½ steps over
// w₂, w₂² − w₀² = 16q/κ, and its top lies within a step of the level's lower edge: w₀² ≤ 8q/κ, so
// 3 w₀² ≤ w₂². Counted widths are within a sample of the crossings': w₀ − 1 and w₂ + 1.
bool smooth_top(const std::vector<double>& x, const ClippedLevel& c, double q, double inward) {
  const double w0 = static_cast<double>(c.run) - 1;
  const double w2 = static_cast<double>(width_within(x, c, 2.5 * q, inward)) + 1;
  return 3 * w0 * w0 <= w2 * w2;
}

// Whether the record's noise rules out an unclipped signal held at level c for its run
// (signal_checks.hpp). The baseline's noise carries the rounding q²/12 (estimate_baseline), which
// holds no sample on a level: the analog noise is what is left.
bool noise_rules_out(const std::vector<double>& x, const ClippedLevel& c, double q) {
  const double total = estimate_baseline(x).noise;
  const double analog2 = total * total - q * q / 12;
  if (!(analog2 > 0)) return false;
  const double in_step = std::erf(q / (2 * std::sqrt(2 * analog2)));
  const double runs = static_cast<double>(x.size() - c.run + 1);
  return runs * std::pow(in_step, static_cast<double>(c.run)) < kClipFalseAlarm;
}

}  // namespace

std::vector<ClippedLevel> clipped_levels(const std::vector<double>& x, const FullScale& range) {
  std::vector<ClippedLevel> out;
  if (x.empty()) return out;
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  const double q = quantization_step(x);
  for (const double extreme : {*hi, *lo}) {
    if (extreme == 0 || (!out.empty() && extreme == out.front().level)) continue;
    // The level histogram at the extreme: its count, and that of the next level inward.
    ClippedLevel c{extreme};
    std::size_t run = 0;
    double next = extreme == *hi ? *lo : *hi;
    for (std::size_t i = 0; i < x.size(); ++i) {
      run = x[i] == extreme ? run + 1 : 0;
      if (run > c.run) c.run = run, c.run_start = i + 1 - run;
      c.at_level += x[i] == extreme;
      if (x[i] != extreme && std::abs(extreme - x[i]) < std::abs(extreme - next)) next = x[i];
    }
    for (double v : x) c.at_next += v == next;
    const double inward = extreme == *hi ? 1 : -1;
    if (range) {  // the stated full scale settles it
      const double limit = extreme == *hi ? (*range)[1] : (*range)[0];
      c.established = true;
      if (inward * (limit - extreme) <= kRangeSteps * q + kRangePrinted * std::abs(limit))
        out.push_back(c);
      continue;
    }
    const bool piles_up =
        static_cast<double>(c.at_level) >= kClippedPileUp * static_cast<double>(c.at_next);
    if (c.run < kClippedRun || !piles_up) continue;
    c.established = !(q > 0) || noise_rules_out(x, c, q);
    if (c.established || !smooth_top(x, c, q, inward)) out.push_back(c);
  }
  return out;
}

std::optional<ClippedSamples> clipped_samples(const std::vector<double>& raw,
                                              const std::vector<double>& from_rest,
                                              const FullScale& range) {
  std::vector<ClippedLevel> levels = clipped_levels(raw, range);
  std::erase_if(levels, [](const ClippedLevel& c) { return !c.established; });
  if (levels.empty()) return std::nullopt;
  // Whether from_rest runs with raw or against it (a turned channel): from the record's extremes.
  const auto [lo, hi] = std::minmax_element(raw.begin(), raw.end());
  const bool turned = from_rest[static_cast<std::size_t>(hi - raw.begin())] <
                      from_rest[static_cast<std::size_t>(lo - raw.begin())];
  ClippedSamples out;
  out.at.assign(raw.size(), 0);
  for (const ClippedLevel& c : levels) {
    // The raw record's upper level bounds from below; turned over, from above.
    const signed char side = (c.level == *hi) != turned ? 1 : -1;
    for (std::size_t i = 0; i < raw.size(); ++i)
      if (raw[i] == c.level) {
        out.at[i] = side;
        (side > 0 ? out.upper : out.lower) = from_rest[i];
      }
  }
  return out;
}

ClippedSamples::Residual ClippedSamples::residual(std::size_t i, double model,
                                                  double measured) const {
  if (at[i] == 0) return {model - measured, 1};
  const double level = at[i] > 0 ? *upper : *lower;
  const double beyond = at[i] * (model - level);  // > 0: the model reaches the level
  if (!(noise > 0)) return beyond >= 0 ? Residual{0, 0} : Residual{model - level, 1};
  const double z = beyond / noise;
  // −2 ln Φ(z), from the tail that keeps its digits: Φ(z) = 1 − ½ erfc(z/√2) above 0, and below
  // −30 (erfc underflows) the Mills-ratio limit z² + 2 ln(−z √(2π)).
  const double tail = 0.5 * std::erfc(std::abs(z) / std::numbers::sqrt2);
  const double loss = z >= 0    ? -2 * std::log1p(-tail)
                      : z > -30 ? -2 * std::log(tail)
                                : z * z + 2 * std::log(-z * std::sqrt(2 * std::numbers::pi));
  const double root = std::sqrt(loss);
  if (!(root > 0)) return {0, 0};
  // dr/dmodel = φ(z)/(Φ(z) √loss) for r = −σ √loss, signed by the side (the level bounds from
  // below at +1: a larger model helps).
  const double density = std::exp(-0.5 * z * z) / std::sqrt(2 * std::numbers::pi);
  const double cdf = z >= 0 ? 1 - tail : tail;
  const double ratio = cdf > 0 ? density / cdf : -z;  // Mills ratio where Φ underflows
  return {-at[i] * noise * root, ratio / root};
}

std::vector<std::string> signal_warnings(const GaugeSignals& signals) {
  std::vector<std::string> warnings;
  if (signals.time_s.size() < kMinRecordSamples)
    warnings.push_back("the record has only " + std::to_string(signals.time_s.size()) +
                       " samples: too few to resolve a pulse (check the sample rate)");
  for (std::size_t g = 0; g < signals.gauges.size(); ++g)
    if (auto w = clipping_warning(signals.gauges[g], signals.strain[g],
                                  signals.range_of(signals.gauges[g])))
      warnings.push_back(*w);
  for (std::size_t g = 0; g < signals.gauges.size(); ++g)
    for (std::size_t h = g + 1; h < signals.gauges.size(); ++h) {
      const std::vector<double>& a = signals.strain[g];
      const std::vector<double>& b = signals.strain[h];
      if (a.size() != b.size() || a.empty()) continue;
      const double r = correlation_coefficient(a, b);
      if (std::abs(r) >= 1 - kCopiedChannelCorrelation)
        warnings.push_back("gauges \"" + signals.gauges[g] + "\" and \"" + signals.gauges[h] +
                           "\" hold the same record" + (r < 0 ? " inverted" : "") +
                           " (correlation " + (r < 0 ? "-1" : "1") + " within " +
                           format_double(kCopiedChannelCorrelation) +
                           "): one channel was read twice (check the measurement's channels "
                           "and the export)");
    }
  return warnings;
}

void require_rest_before_pulse(const GaugeSignals& signals, const std::string& gauge,
                               const RestSignal& s, const std::string& scene_file) {
  if (s.start.on_front)
    throw channel_error(
        signals, gauge, scene_file,
        fmt("it starts on its first pulse's front: its %.0f samples before that pulse's onset "
            "move %.3g towards it, beyond their noise and at %.2g of the rate at which the pulse "
            "goes on rising, so no rest level can be read before the pulse (record with a longer "
            "pre-trigger: the rest level and noise are read from the record only)",
            static_cast<double>(s.start.first->onset), s.start.change, s.start.rate_fraction));
  // The rest level and noise are read from the first kMinRestSamples at least: all at rest. Its
  // first pulse as the record's first samples see it, too: a record starting partway up a sharp
  // front reads a level on the pulse, whose noise band hides that onset, from its first 5 %.
  const std::optional<PulseWindow>& first =
      s.start.first && (!s.first || s.start.first->onset < s.first->onset) ? s.start.first
                                                                           : s.first;
  if (first && first->onset < kMinRestSamples)
    throw channel_error(
        signals, gauge, scene_file,
        fmt("its first pulse starts %.0f samples into the record: at least %.0f samples at rest "
            "before it are needed to read its rest level and noise (record with a longer "
            "pre-trigger)",
            static_cast<double>(first->onset), static_cast<double>(kMinRestSamples)));
  if (s.start.moves_away)
    throw channel_error(
        signals, gauge, scene_file,
        fmt("it starts inside a pulse: its %.0f samples before the onset of what its first "
            "samples see as its first pulse move %.3g away from that pulse (%.0f %% of its peak), "
            "beyond the band a rest stays within, so its first samples lie on another pulse, "
            "which was read as the rest level (record with a longer pre-trigger: the rest level "
            "and noise are read from the record before its first pulse only)",
            static_cast<double>(s.start.first->onset), -s.start.change,
            -100 * s.start.change / s.start.first->peak));
  // The rests are told within the band of the noise of successive differences where it is the
  // smaller: a record that starts on its front's last samples reads them into its "rest" noise
  // (LANL copper at 1 MS/s starting 1 µs up its 6 µs foot: 2.6 × the noise), and a band that wide
  // joins its reflected pulse's tail to the rest after it, which then trends and is no rest. A
  // record whose first samples lie on a long ramp (a pulse shaper's) reads their slope as its
  // baseline noise, so wide that no pulse rises above it: its first pulse is then the one its
  // first samples see, with the noise of their successive differences.
  const std::optional<PulseWindow>& seen = s.first ? s.first : s.start.first;
  if (seen)
    if (const auto r = rest_elsewhere(s.x, *seen, std::min(s.noise, s.start.noise)))
      throw channel_error(
          signals, gauge, scene_file,
          fmt("it starts inside a pulse: after its first pulse it rests %.3g from the level it "
              "starts at, not at that level (%.0f %% of the peak, from sample %.0f, and again "
              "from sample %.0f after a later pulse: the level it holds longest)",
              s.inverted ? -r->level : r->level, 100 * std::abs(r->level) / seen->peak,
              static_cast<double>(r->first), static_cast<double>(r->again)) +
              ", so its start lies on a pulse of that height, on its plateau or upper front, "
              "which was read as the rest level (record with a longer pre-trigger: the rest "
              "level and noise are read from the record before its first pulse only)");
}

namespace {
RestSignal signal_from_rest(const std::vector<double>& raw, double expected_sign) {
  const Baseline b = estimate_baseline(raw);
  RestSignal s{std::vector<double>(raw.size()), b.noise, std::nullopt, false,
               record_start(raw, b.step)};
  for (std::size_t i = 0; i < raw.size(); ++i) s.x[i] = raw[i] - b.level;
  s.first = find_first_pulse(s.x, {0.0, b.noise});
  if (s.first && expected_sign != 0 && s.first->sign != expected_sign) {
    for (double& v : s.x) v = -v;
    s.first->sign = expected_sign, s.inverted = true;
  }
  return s;
}

}  // namespace

RestSignal rest_signal(const GaugeSignals& signals, const std::string& gauge, double expected_sign,
                       const std::string& scene_file) {
  RestSignal s = signal_from_rest(*signals.find(gauge), expected_sign);
  require_rest_before_pulse(signals, gauge, s, scene_file);
  return s;
}

std::string inverted_gauge_warning(const std::string& gauge, bool tension) {
  return "gauge \"" + gauge +
         (tension ? "\": its first pulse is compressive; a tension test's first pulse is tensile, "
                    "so the signal was inverted (check the channel's `invert` and the "
                    "measurement's `test`)"
                  : "\": its first pulse is tensile; a compression test's first pulse is "
                    "compressive, so the signal was inverted (check the channel's `invert`, or "
                    "\"test\": \"tension\")");
}

void require_pulse_fits_round_trip(const std::string& gauge, const std::string& pulse,
                                   double pulse_s, double round_trip_s,
                                   const std::string& round_trip, const std::string& scene_file) {
  if (!(round_trip_s > 0) || pulse_s <= kMaxPulseRoundTrips * round_trip_s) return;
  char value[300];
  std::snprintf(value, sizeof value, "gauge \"%s\": %s %.3g s long, %.3g round trips %s",
                gauge.c_str(), pulse.c_str(), pulse_s, pulse_s / round_trip_s,
                fmt(round_trip.c_str(), round_trip_s).c_str());
  throw input_error(scene_file, "measurement.time.unit", value,
                    "expected a pulse shorter than its round trip (its reflection would overlap "
                    "it): is the time unit right? (a column in ms read as s makes every pulse "
                    "1000 times longer)");
}

void require_pulse_fits_round_trip(const KolskySetup& k, double pulse_s,
                                   const std::string& scene_file) {
  require_pulse_fits_round_trip(k.incident_gauge, "incident pulse", pulse_s,
                                2 * k.incident_distance_m / k.front.c0_m_s,
                                "2d/c0 = %.3g s of its gauge to the specimen and back", scene_file);
}

}  // namespace shpb
