#include "analysis/comparison.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "analysis/pulse_window.hpp"
#include "analysis/signal_checks.hpp"
#include "core/correlation.hpp"

namespace shpb {
namespace {

// Index of the largest |x| in [begin, end).
std::size_t peak_index(std::span<const double> x, std::size_t begin, std::size_t end) {
  std::size_t k = begin;
  for (std::size_t i = begin; i < end; ++i)
    if (std::abs(x[i]) > std::abs(x[k])) k = i;
  return k;
}

// Fractional position where |x| crosses `level` between samples i − 1 and i.
double crossing(std::span<const double> x, std::size_t i, double level) {
  const double a = std::abs(x[i - 1]), b = std::abs(x[i]);
  return static_cast<double>(i - 1) + (b != a ? (level - a) / (b - a) : 0.0);
}

// Σ m[i]·s[i + lag] over the window (s outside [0, size) counts as 0).
double cross_product(std::span<const double> m, std::span<const double> s, std::size_t begin,
                     std::size_t end, long lag) {
  double sum = 0;
  for (std::size_t i = begin; i < end; ++i) {
    const long j = static_cast<long>(i) + lag;
    if (j >= 0 && j < static_cast<long>(s.size())) sum += m[i] * s[static_cast<std::size_t>(j)];
  }
  return sum;
}

}  // namespace

double rise_time_samples(std::span<const double> x, std::size_t begin, std::size_t end) {
  const std::size_t k = peak_index(x, begin, end);
  const double peak = std::abs(x[k]);
  if (peak == 0) return 0;
  // Walk back from the peak to the last sample below 10 %, then forward to the 10 % and 90 %
  // crossings of that excursion.
  std::size_t start = k;
  while (start > begin && std::abs(x[start - 1]) >= 0.1 * peak) --start;
  if (start == begin) return 0;
  double t10 = 0, t90 = 0;
  bool have10 = false;
  for (std::size_t i = start; i <= k; ++i) {
    if (!have10 && std::abs(x[i]) >= 0.1 * peak) t10 = crossing(x, i, 0.1 * peak), have10 = true;
    if (std::abs(x[i]) >= 0.9 * peak) {
      t90 = i > begin ? crossing(x, i, 0.9 * peak) : static_cast<double>(i);
      break;
    }
  }
  return std::max(0.0, t90 - t10);
}

double half_peak_width_samples(std::span<const double> x, std::size_t begin, std::size_t end) {
  const double half = 0.5 * std::abs(x[peak_index(x, begin, end)]);
  std::size_t first = end, last = begin;
  for (std::size_t i = begin; i < end; ++i)
    if (std::abs(x[i]) >= half) first = std::min(first, i), last = i;
  if (first >= end) return 0;
  const double t0 = first > begin ? crossing(x, first, half) : static_cast<double>(first);
  const double t1 = last + 1 < end ? crossing(x, last + 1, half) : static_cast<double>(last);
  return t1 - t0;
}

PulseComparison compare_pulse(std::span<const double> measured, std::span<const double> simulated,
                              double dt_s, std::size_t begin, std::size_t end,
                              const ClippedSamples* clipped) {
  PulseComparison c;
  end = std::min({end, measured.size(), simulated.size()});
  if (begin + 2 >= end) return c;
  c.window_start_s = static_cast<double>(begin) * dt_s;
  c.window_end_s = static_cast<double>(end) * dt_s;

  // Arrival shift: the lag of the largest cross-correlation, refined by a parabola through it
  // and its neighbours (exactly 0 for identical signals).
  const long half = static_cast<long>(end - begin) / 2;
  long best = 0;
  double best_value = cross_product(measured, simulated, begin, end, 0);
  for (long lag = -half; lag <= half; ++lag) {
    const double v = cross_product(measured, simulated, begin, end, lag);
    if (v > best_value) best_value = v, best = lag;
  }
  double lag = static_cast<double>(best);
  const double vm = cross_product(measured, simulated, begin, end, best - 1);
  const double vp = cross_product(measured, simulated, begin, end, best + 1);
  const double curvature = vm - 2 * best_value + vp;
  if (curvature < 0) lag += 0.5 * (vm - vp) / curvature;
  c.arrival_shift_s = lag * dt_s;

  const double peak_m = std::abs(measured[peak_index(measured, begin, end)]);
  const double peak_s = std::abs(simulated[peak_index(simulated, begin, end)]);
  c.peak_ratio = peak_m > 0 ? peak_s / peak_m : 0;
  const double sign = measured[peak_index(measured, begin, end)] < 0 ? -1.0 : 1.0;
  const double plateau_m = std::abs(plateau_level(measured.subspan(0, end), begin, end, sign));
  const double plateau_s = std::abs(plateau_level(simulated.subspan(0, end), begin, end, sign));
  c.plateau_ratio = plateau_m > 0 ? plateau_s / plateau_m : 0;
  const double width_m = half_peak_width_samples(measured, begin, end);
  c.duration_ratio = width_m > 0 ? half_peak_width_samples(simulated, begin, end) / width_m : 0;
  c.rise_time_measured_s = rise_time_samples(measured, begin, end) * dt_s;
  c.rise_time_simulated_s = rise_time_samples(simulated, begin, end) * dt_s;

  // The error's squares run on the signals divided by the larger peak, so that no square
  // overflows whatever the record's scale (a bridge factor off by 1e300 gave an NRMSE of inf);
  // the figure is scale-free, so this changes only its rounding.
  const double n = static_cast<double>(end - begin);
  const double unit_e = std::max({peak_m, peak_s, 1e-300});
  double se = 0;
  for (std::size_t i = begin; i < end; ++i) {
    const double e = clipped ? clipped->residual(i, simulated[i], measured[i]).value / unit_e
                             : simulated[i] / unit_e - measured[i] / unit_e;
    se += e * e;
  }
  c.nrmse = peak_m > 0 ? std::sqrt(se / n) * (unit_e / peak_m) : 0;
  c.correlation = correlation_coefficient(measured.subspan(begin, end - begin),
                                          simulated.subspan(begin, end - begin));
  return c;
}

}  // namespace shpb
