#include "analysis/pulse_window.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>
#include <vector>

#include "core/median.hpp"

namespace shpb {
namespace {

constexpr double kNoiseSigmas = 5.0;           // band of the baseline, in σ
constexpr double kBandOfPeak = 0.03;           // … and at least this fraction of the peak
constexpr double kDetectFractionOfPeak = 0.5;  // a pulse is found at half its height
constexpr double kMadToSigma = 1.4826;         // σ of Gaussian noise from its MAD
// A grid of more levels than a 24-bit digitizer's is not told apart from floating point: its
// q/√12 would be below 2·10⁻⁸ of the record's range, far under any gauge's noise.
constexpr double kMaxGridLevels = 16777216.0;
// A value on the grid is an integer number of steps from the lowest one to within this fraction
// of a step: a channel's scale (a bridge factor, mV to strain) leaves rounding errors of ~10⁻¹⁶
// of the range, i.e. < 10⁻⁸ of a step even on a 24-bit grid.
constexpr double kGridTolerance = 1e-6;
// An export prints each value to so many significant digits (6: LeCroy, PicoScope, a %g): a
// digitizer's level whose step is no round decimal (10 V over 256 levels) is then off the grid by
// up to half a unit of its last digit, 5·10⁻⁶ of its magnitude, which the grid check allows. A
// grid whose levels the digits cannot tell apart to a tenth of a step is none.
constexpr double kPrintedRounding = 5e-6;
constexpr double kMaxPrintedRoundingSteps = 0.1;
// σ of a uniform rounding error over one step (Widrow & Kollár 2008, Quantization Noise, §4.1).
const double kQuantizationSigma = 1 / std::sqrt(12.0);

}  // namespace

std::size_t baseline_samples(std::size_t record, double fraction) {
  return std::min(record, std::max<std::size_t>(
                              kMinRestSamples,
                              static_cast<std::size_t>(fraction * static_cast<double>(record))));
}

double rest_level_sd(double noise, std::size_t samples) {
  return samples > 0 ? std::sqrt(std::numbers::pi / 2 / static_cast<double>(samples)) * noise : 0.0;
}

double quantization_step(std::span<const double> x) {
  std::vector<double> levels(x.begin(), x.end());
  std::sort(levels.begin(), levels.end());
  levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
  if (levels.size() < 2 || !std::isfinite(levels.front()) || !std::isfinite(levels.back()))
    return 0;
  const double range = levels.back() - levels.front();
  double q = range;
  for (std::size_t i = 1; i < levels.size(); ++i) q = std::min(q, levels[i] - levels[i - 1]);
  // The step from the whole range: the smallest difference carries the rounding of two values.
  const double span = std::round(range / q);
  if (!(span <= kMaxGridLevels)) return 0;
  q = range / span;
  // A value's steps from the lowest carry the printed rounding of both (each at most that of the
  // record's largest magnitude) and that of the step, the range's over the span (through up to
  // all of it): bounds the same for the record turned over, whose lowest value is this one's
  // highest. Bounding the lowest value's rounding by its own left an 8-bit grid whose lowest
  // value lay nearer zero than its highest 10⁻⁴ of a step off: read as none, its rest's noise 0.
  const double largest = std::max(std::abs(levels.front()), std::abs(levels.back()));
  const double of_step =
      kPrintedRounding * (std::abs(levels.front()) + std::abs(levels.back())) / q;
  for (double v : levels) {
    const double steps = (v - levels.front()) / q;
    const double printed = kPrintedRounding * (std::abs(v) + largest) / q;
    if (printed > kMaxPrintedRoundingSteps ||
        std::abs(steps - std::round(steps)) > std::max(kGridTolerance, printed + of_step))
      return 0;
  }
  return q;
}

namespace {

// The noise of a quiet segment most of whose samples read one level (its MAD is 0; `deviations`
// are |x − that level|): a digitizer of step q rounds Gaussian noise of σ_n < q to that level
// unless it exceeds q/2, so the share p of samples off it gives σ_n = q / (2√2 erfc⁻¹(p)) (a count,
// as robust as the MAD it stands in for); each sample also carries the rounding error, q/√12
// (Widrow & Kollár 2008, §4.1): σ² = σ_n² + q²/12. A record on no grid (q = 0) has no step: 0.
double one_level_noise(double q, const std::vector<double>& deviations) {
  if (!(q > 0)) return 0;
  const double off = static_cast<double>(std::count_if(deviations.begin(), deviations.end(),
                                                       [](double d) { return d > 0; })) /
                     static_cast<double>(deviations.size());
  double sigma_n = 0;
  if (off > 0) {
    // erfc⁻¹(p) by bisection: erfc falls monotonically from 1 at 0 (p ≤ ½ here).
    double lo = 0, hi = 6;
    for (int i = 0; i < 60; ++i) {
      const double mid = 0.5 * (lo + hi);
      (std::erfc(mid) > off ? lo : hi) = mid;
    }
    sigma_n = q / (2 * std::numbers::sqrt2 * 0.5 * (lo + hi));
  }
  return std::sqrt(sigma_n * sigma_n + kQuantizationSigma * kQuantizationSigma * q * q);
}

// The noise of a quiet segment on a grid of step q whose MAD is not 0 (`seg` its samples, `level`
// their median, `mad` their median absolute deviation). That median is one of the grid's values:
// for noise σ_n from q/2 to 3q/2 it is q, read as σ = 1.48 q whatever σ_n (40 % high at σ_n = q,
// an 8-bit record of 1 % noise). The segment's standard deviation counts every sample and is the
// noise itself, rounding included (σ² = σ_n² + q²/12, Sheppard's correction, Widrow & Kollár 2008
// §4.1); the samples beyond kTrimSigmas of the MAD's σ (or of a step) are left out, as the MAD
// ignores a spike.
double rounded_noise(const std::vector<double>& seg, double level, double mad, double q) {
  constexpr double kTrimSigmas = 5.0;  // Gaussian noise beyond 5 σ: 6·10⁻⁷ of the samples
  const double limit = kTrimSigmas * std::max(kMadToSigma * mad, q);
  double sum = 0, sum2 = 0;
  std::size_t n = 0;
  for (double v : seg)
    if (std::abs(v - level) <= limit) sum += v - level, sum2 += (v - level) * (v - level), ++n;
  const double mean = sum / static_cast<double>(n);
  return std::sqrt(std::max(0.0, sum2 / static_cast<double>(n) - mean * mean));
}

// The median of a rest segment `seg` (not empty) of a record on a grid of step q > 0
// (quantization_step). Each sample stands for the values within ±q/2 of its grid level, and the
// median is interpolated within that interval of the median level (the median of grouped data):
// noise of about a step spreads the samples over the neighbouring levels in the proportions of
// where the rest lies between them. The plain median snaps to a level: up to q/2 off, an offset of
// every sample read from it, which the bar/specimen area ratio multiplies in the 2- and 3-wave
// stresses (an 8-bit record of a ±1.25 × peak range: q/2 is 0.5 % of the peak). An even count
// whose two middle values lie on different levels is split in half by any value between their
// intervals: their midpoint (the edge between adjacent levels), which the record turned over gives
// too (the lower edge of the upper one's interval was its upper edge of the lower one's; a front's
// middle values can lie levels apart).
double grid_median(const std::vector<double>& seg, double q) {
  const double level = median(seg);  // the upper middle value for an even count
  const double low = level - 0.5 * q, high = level + 0.5 * q;
  // B samples below the level's interval, A in it, C above: L − q/2 + q (N/2 − B)/A written as
  // L + q (C − B)/(2A), whose rounding is the same for the record turned over.
  double below = 0, above = 0, under = level;
  for (double v : seg) {
    if (v < low)
      ++below, under = below == 1 ? v : std::max(under, v);
    else if (v > high)
      ++above;
  }
  const auto n = static_cast<double>(seg.size());
  if (2 * below == n) return 0.5 * (under + level);
  return level + q * (above - below) / (2 * (n - below - above));
}

// The level of a rest segment `seg` (not empty) of a record on a grid of step q (0: on none): the
// median of grouped data on a grid (grid_median: the negation of the record turned over's), else
// the plain median (of an even count the upper middle value, the record turned over's the lower
// one: half their gap apart; kept, as the measured records on no grid are read so).
double segment_level(const std::vector<double>& seg, double q) {
  return q > 0 ? grid_median(seg, q) : median(seg);
}

// Level and noise of the record's first n samples (n ≥ 1).
Baseline quiet_segment(std::span<const double> x, std::size_t n, double q) {
  const std::vector<double> seg(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(n));
  Baseline b;
  // On a grid, the deviations from a centre the record turned over has too (its noise then the
  // same for either polarity).
  const double centre = q > 0 ? symmetric_median(seg) : median(seg);
  std::vector<double> deviations(seg.size());
  for (std::size_t i = 0; i < seg.size(); ++i) deviations[i] = std::abs(seg[i] - centre);
  const double mad = median(deviations);
  if (mad == 0)
    b.noise = one_level_noise(q, deviations);
  else
    b.noise = q > 0 ? rounded_noise(seg, centre, mad, q) : kMadToSigma * mad;
  b.level = segment_level(seg, q);
  b.step = q;
  return b;
}

// The level y holds longest: the median of the sorted samples' widest count within ±band of one
// of them; of equally wide counts, the one whose median lies nearest y's zero (its start level:
// the same count for the record turned over, where the first of them in sorted order is the last).
double held_level(std::span<const double> y, double band) {
  std::vector<double> sorted(y.begin(), y.end());
  std::sort(sorted.begin(), sorted.end());
  std::size_t best = 0, lo = 0, hi = 0;
  double level = 0;
  for (std::size_t k = 0; k < sorted.size(); ++k) {
    while (sorted[lo] < sorted[k] - band) ++lo;
    while (hi < sorted.size() && sorted[hi] <= sorted[k] + band) ++hi;
    if (hi - lo < best) continue;
    // The median of sorted[lo, hi), its two middle values' mean for an even count.
    const double m = 0.5 * (sorted[(lo + hi - 1) / 2] + sorted[(lo + hi) / 2]);
    if (hi - lo > best || std::abs(m) < std::abs(level)) best = hi - lo, level = m;
  }
  return level;
}

}  // namespace

Baseline estimate_baseline(std::span<const double> x, double fraction) {
  const double q = quantization_step(x);
  std::size_t n = baseline_samples(x.size(), fraction);
  // A scope triggered on the pulse keeps a pre-trigger of a few percent of the record: its first
  // 5 % may hold the pulse, whose level the median then takes for the rest (a compressive pulse
  // read as tensile). The segment ends before the first pulse found against the level of the
  // first samples, by one rise (rest_samples_before); never shorter than those samples.
  if (n > kMinRestSamples && x.size() >= kMinRestSamples)
    if (const auto w = find_first_pulse(x, quiet_segment(x, kMinRestSamples, q)))
      n = std::clamp(rest_samples_before(*w), kMinRestSamples, n);
  return quiet_segment(x, std::min(n, x.size()), q);
}

std::optional<double> rest_level_before(std::span<const double> x, std::size_t samples) {
  if (samples < kMinRestSamples || samples > x.size()) return std::nullopt;
  return segment_level({x.begin(), x.begin() + static_cast<std::ptrdiff_t>(samples)},
                       quantization_step(x));
}

std::size_t rest_samples_before(const PulseWindow& w) {
  const std::size_t rise = w.half > w.onset ? w.half - w.onset : 0;
  return std::max(w.onset - std::min(rise, w.onset / 2), std::min(kMinRestSamples, w.onset));
}

double rest_band(double noise, double peak) {
  return std::max(kNoiseSigmas * noise, kBandOfPeak * peak);
}

double following_pulse_min_peak(double noise, double previous_peak) {
  return 2 * rest_band(noise, previous_peak);
}

std::optional<PulseWindow> find_first_pulse(std::span<const double> x, const Baseline& b,
                                            std::size_t from) {
  double peak = 0;
  for (std::size_t i = from; i < x.size(); ++i) peak = std::max(peak, std::abs(x[i] - b.level));
  const double band = rest_band(b.noise, peak);
  if (!(peak > 2 * band) && !(peak > 0 && b.noise == 0)) return std::nullopt;
  const double detect = kDetectFractionOfPeak * peak;
  std::size_t i = from;
  while (i < x.size() && std::abs(x[i] - b.level) < detect) ++i;
  if (i == x.size()) return std::nullopt;
  PulseWindow w;
  w.sign = x[i] - b.level < 0 ? -1.0 : 1.0;
  w.half = i;
  auto level = [&](std::size_t k) { return w.sign * (x[k] - b.level); };
  std::size_t on = i;
  while (on > from && level(on - 1) > band) --on;
  w.onset = on;
  // Last half-peak sample of this pulse: follow it while it stays above the band.
  std::size_t last_half = i;
  std::size_t k = i;
  while (k < x.size() && level(k) > band) {
    if (level(k) >= detect) last_half = k;
    w.peak = std::max(w.peak, level(k));
    ++k;
  }
  // Short dips inside the band (noise on a plateau) do not end the pulse: look ahead for a
  // return above half height within a tenth of the length so far.
  while (k < x.size()) {
    const std::size_t look = std::max<std::size_t>(3, (k - on) / 10);
    std::size_t j = k;
    while (j < x.size() && j < k + look && level(j) < detect) ++j;
    if (j >= x.size() || j >= k + look) break;
    k = j;
    while (k < x.size() && level(k) > band) {
      if (level(k) >= detect) last_half = k;
      w.peak = std::max(w.peak, level(k));
      ++k;
    }
  }
  std::size_t end = last_half;
  while (end < x.size() && level(end) > band) ++end;
  w.end = end;
  return w;
}

RecordStart record_start(std::span<const double> x, double step) {
  // A chance trend of white noise beyond 4 σ: 3·10⁻⁵ of records (one-sided), and the rate must be
  // the pulse's as well. The rate: the rest records of the survey of outside set-ups reach 0.19 (a
  // polymer bar's foot within the band, 17 samples after the trigger), its fronts 1.0 to 1.4 at
  // 5.6 to 8.6 σ (docs/validation.md, "Set-ups of an outside laboratory").
  constexpr double kFrontTrendSigmas = 4;
  constexpr double kFrontRateFraction = 0.3;
  // A front moves through all three thirds (the middle one 0.2 to 0.5 of the change from either
  // end); a short rest before a slow pulse's foot inside the band only in its last (−0.11 to 0.0:
  // 10 to 12 samples of rest before an 80-sample rise at 2 % noise).
  constexpr double kFrontEvenness = 0.1;
  RecordStart r;
  if (x.size() < kMinRestSamples) return r;
  const std::size_t m = baseline_samples(x.size());
  std::vector<double> steps(m - 1);
  for (std::size_t i = 0; i + 1 < m; ++i) steps[i] = x[i + 1] - x[i];
  const double centre = symmetric_median(steps);
  for (double& d : steps) d = std::abs(d - centre);
  // A difference of two samples carries √2 σ; on a digitizer's grid, at least the rounding's.
  r.noise = std::max(kMadToSigma * median(steps) / std::numbers::sqrt2, kQuantizationSigma * step);
  const double start_level =
      symmetric_median({x.begin(), x.begin() + static_cast<std::ptrdiff_t>(kMinRestSamples)});
  r.first = find_first_pulse(x, {start_level, r.noise});
  const std::size_t n = r.first ? r.first->onset : 0, third = n / 3;
  if (third == 0) return r;
  auto level = [&](std::size_t from) {
    return symmetric_median({x.begin() + static_cast<std::ptrdiff_t>(from),
                             x.begin() + static_cast<std::ptrdiff_t>(from + third)});
  };
  const PulseWindow& w = *r.first;
  const double first = level(0), middle = level((n - third) / 2), last = level(n - third);
  r.change = w.sign * (last - first);
  // The rate at which the pulse goes on rising: the mean from the last sample before the onset to
  // the half-height one, or, where its front stops below half height (a pulse shaper's elastic
  // step to 0.40–0.49 of the peak and a shoulder there for µs before the shaper's ramp crosses
  // half), to that first top: the front's own rise. The mean to half the peak took in the
  // shoulder, 3 to 10 times slower than the step, and the step's foot inside the rest band (a few
  // samples at 10 MS/s, 40 to 70 at 100 MS/s, after 10 to 50 of rest) read as a front at 0.3 to
  // 2.4 of it (docs/validation.md, "Where a record starts"). The front stops where, beyond twice
  // the band (a pulse's least height), it rises by no further band for longer than the record
  // took to get there: a rising front, even a noisy one (σ ≤ a fifth of the band), climbs each
  // band in about the time its previous band took, less than all the time before it.
  const double band = rest_band(r.noise, w.peak);
  auto height = [&](std::size_t k) { return w.sign * (x[k] - start_level); };
  std::size_t top = n, end = w.half;
  for (std::size_t k = n; k < w.half; ++k) {
    if (height(k) > height(top) + band) {
      top = k;
    } else if (height(top) >= 2 * band && k - top > top) {
      end = top;
      break;
    }
  }
  const double rise = w.sign * (x[end] - x[n - 1]) / static_cast<double>(end - n + 1);
  r.rate_fraction = r.change / static_cast<double>(n - third) / rise;
  // The difference of two medians of `third` samples of white noise: √2 · √(π/2) σ/√third.
  const double sd = std::sqrt(std::numbers::pi / static_cast<double>(third)) * r.noise;
  const double through = std::min(w.sign * (middle - first), w.sign * (last - middle));
  r.on_front = r.change > kFrontTrendSigmas * sd && r.rate_fraction >= kFrontRateFraction &&
               through >= kFrontEvenness * r.change;
  r.moves_away = -r.change > std::max(band, kFrontTrendSigmas * sd);
  return r;
}

std::optional<RestElsewhere> rest_elsewhere(std::span<const double> x, const PulseWindow& first,
                                            double noise) {
  if (first.onset >= x.size()) return std::nullopt;
  const std::span<const double> y = x.subspan(first.onset);
  const double band = rest_band(noise, first.peak), far = kRestElsewhereFraction * first.peak;
  const double level = held_level(y, band);
  if (!(std::abs(level) >= far)) return std::nullopt;
  // Reached from the start in one step, not past it by `far` on its side (a pulse's tail settling
  // there, a polymer bar's creep after its pulse, peaks first; the pulse the record started on may
  // go on the other way first, away from that rest: a shaper's ramp); rests there (kMinRestSamples
  // in a row within the band, not trending through it), left by `far`, rests there again.
  const double side = level > 0 ? 1.0 : -1.0;
  std::optional<std::size_t> rest;
  bool left = false;
  for (std::size_t i = 0; i < y.size();) {
    if (std::abs(y[i] - level) > band) {
      if (!rest && side * y[i] > std::abs(level) + far) return std::nullopt;
      left = left || (rest && std::abs(y[i] - level) >= far);
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < y.size() && std::abs(y[j] - level) <= band) ++j;
    // At rest, not a front crossing the band: its first and last thirds' medians within half
    // the band of each other (a front through the band moves by about 4/3 of it).
    const std::size_t third = (j - i) / 3;
    auto median_from = [&](std::size_t a) {
      return symmetric_median(
          std::vector<double>(y.begin() + static_cast<std::ptrdiff_t>(a),
                              y.begin() + static_cast<std::ptrdiff_t>(a + third)));
    };
    if (j - i >= kMinRestSamples &&
        std::abs(median_from(j - third) - median_from(i)) <= 0.5 * band) {
      if (rest && left) return RestElsewhere{level, first.onset + *rest, first.onset + i};
      if (!rest) rest = i;
    }
    i = j;
  }
  return std::nullopt;
}

std::optional<Onset> find_onset(std::span<const double> x, const Baseline& b, double sign,
                                std::size_t from, std::size_t to, double min_peak) {
  to = std::min(to, x.size());
  if (from >= to) return std::nullopt;
  // The pulse's first half-peak sample above `level`, with the band below which it is at rest.
  auto front = [&](double level) {
    double peak = 0;
    for (std::size_t i = from; i < to; ++i) peak = std::max(peak, sign * (x[i] - level));
    std::size_t i = from;
    while (i < to && sign * (x[i] - level) < kDetectFractionOfPeak * peak) ++i;
    return std::tuple{i, peak, rest_band(b.noise, peak)};
  };
  // The level at rest is the median from `from` to the half-peak sample: the record there is
  // mostly at rest (a preceding pulse's tail, a staircase's later step), the front's rise is short.
  double level = b.level;
  if (const auto [half, peak, band] = front(b.level); half - from >= kMinRestSamples)
    level = symmetric_median(std::vector<double>(x.begin() + static_cast<std::ptrdiff_t>(from),
                                                 x.begin() + static_cast<std::ptrdiff_t>(half)));
  const auto [half, peak, band] = front(level);
  if (!(peak > 2 * band) || !(peak > min_peak) || half == to) return std::nullopt;
  Onset o{half, half};
  while (o.onset > from && sign * (x[o.onset - 1] - level) > band) --o.onset;
  return o;
}

double plateau_level(std::span<const double> x, std::size_t begin, std::size_t end, double sign) {
  std::vector<double> v;
  for (std::size_t i = begin; i < end && i < x.size(); ++i) v.push_back(sign * x[i]);
  if (v.empty()) return 0;
  std::vector<double> sorted(v);
  std::sort(sorted.begin(), sorted.end());
  const double p95 =
      sorted[static_cast<std::size_t>(0.95 * static_cast<double>(sorted.size() - 1))];
  std::vector<double> top;
  for (double y : v)
    if (y >= 0.5 * p95) top.push_back(y);
  return median(top);
}

}  // namespace shpb
