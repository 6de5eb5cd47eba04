#include "study/recorded_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace shpb {

namespace {
// Half-width of the smoothing kernel in standard deviations (weights below 3e-4 of the peak).
constexpr int kKernelHalfWidth = 4;

std::vector<double> smoothed(const std::vector<double>& x) {
  std::vector<double> w(2 * kKernelHalfWidth + 1);
  for (int j = -kKernelHalfWidth; j <= kKernelHalfWidth; ++j)
    w[j + kKernelHalfWidth] = std::exp(-0.5 * j * j);
  std::vector<double> y(x.size());
  const long n = static_cast<long>(x.size());
  for (long k = 0; k < n; ++k) {
    double s = 0, weight = 0;
    for (int j = -kKernelHalfWidth; j <= kKernelHalfWidth; ++j) {
      const long i = k + j;
      if (i < 0 || i >= n) continue;
      s += w[j + kKernelHalfWidth] * x[i];
      weight += w[j + kKernelHalfWidth];
    }
    y[k] = s / weight;
  }
  return y;
}
}  // namespace

double recorded_gauge_error(const TimeSeries& gauges, const GaugeReference& reference) {
  if (!std::isfinite(gauge_error(gauges, reference)))  // the same window and checks
    return std::numeric_limits<double>::quiet_NaN();
  std::size_t n = reference.exact ? gauges.samples() : reference.fine.samples();
  for (std::size_t k = 0; k < n; ++k)
    if (!(gauges.time_s[k] < reference.window_end_s)) {
      n = k;
      break;
    }
  double diff = 0, norm = 0;
  for (std::size_t c = 0; c < gauges.values.size(); ++c) {
    std::vector<double> run(gauges.values[c].begin(), gauges.values[c].begin() + n), ref(n);
    for (std::size_t k = 0; k < n; ++k)
      ref[k] =
          reference.exact ? reference.strain(c, gauges.time_s[k]) : reference.fine.values[c][k];
    run = smoothed(run);
    ref = smoothed(ref);
    for (std::size_t k = 0; k < n; ++k) {
      diff += (run[k] - ref[k]) * (run[k] - ref[k]);
      norm += ref[k] * ref[k];
    }
  }
  return std::sqrt(diff / norm);
}

}  // namespace shpb
