#include "study/recorded_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace shpb {

namespace {
// Half-width of the smoothing kernel in standard deviations (weights below 3e-4 of the peak).
constexpr int kKernelHalfWidth = 4;
}  // namespace

std::vector<double> record_smoothed(const std::vector<double>& x, int sigma, int stride) {
  const int half = kKernelHalfWidth * sigma;
  std::vector<double> w(2 * half + 1);
  for (int j = -half; j <= half; ++j)
    w[j + half] =
        std::exp(-0.5 * (static_cast<double>(j) / sigma) * (static_cast<double>(j) / sigma));
  const long n = static_cast<long>(x.size());
  std::vector<double> y;
  y.reserve(x.size() / stride + 1);
  for (long k = 0; k < n; k += stride) {
    double s = 0, weight = 0;
    for (int j = -half; j <= half; ++j) {
      const long i = k + j;
      if (i < 0 || i >= n) continue;
      s += w[j + half] * x[i];
      weight += w[j + half];
    }
    y.push_back(s / weight);
  }
  return y;
}

double recorded_gauge_error(const TimeSeries& gauges, const GaugeReference& reference) {
  if (!std::isfinite(gauge_error(gauges, reference)))  // the same window and checks
    return std::numeric_limits<double>::quiet_NaN();
  std::size_t n = reference.exact ? gauges.samples() : reference.fine.samples();
  for (std::size_t k = 0; k < n; ++k)
    if (!(gauges.time_s[k] < reference.window_end_s)) {
      n = k;
      break;
    }
  const double sample_s = n > 1 ? gauges.time_s[1] - gauges.time_s[0] : 0.0;
  double diff = 0, norm = 0;
  for (std::size_t c = 0; c < gauges.values.size(); ++c) {
    std::vector<double> run(gauges.values[c].begin(), gauges.values[c].begin() + n), ref(n);
    // An exact reference is smoothed analytically, its fronts at their exact arrival times: a
    // step sampled first would put its front on the sample grid (up to half a sample off).
    // A fine-mesh reference recorded at a multiple of the sample rate is smoothed there likewise.
    const bool analytic = reference.exact && reference.recorded && sample_s > 0;
    const bool oversampled = !reference.exact && !reference.recorded_fine.values.empty();
    for (std::size_t k = 0; k < n; ++k)
      ref[k] = analytic          ? reference.recorded(c, gauges.time_s[k], sample_s)
               : reference.exact ? reference.strain(c, gauges.time_s[k])
               : oversampled     ? reference.recorded_fine.values[c][k]
                                 : reference.fine.values[c][k];
    run = record_smoothed(run);
    if (!analytic && !oversampled) ref = record_smoothed(ref);
    for (std::size_t k = 0; k < n; ++k) {
      diff += (run[k] - ref[k]) * (run[k] - ref[k]);
      norm += ref[k] * ref[k];
    }
  }
  return std::sqrt(diff / norm);
}

double recorded_reference_difference(const GaugeReference& a, const GaugeReference& b) {
  double diff = 0, norm = 0;
  for (std::size_t c = 0; c < b.recorded_fine.values.size(); ++c)
    for (std::size_t k = 0; k < b.recorded_fine.samples(); ++k) {
      const double d = a.recorded_fine.values[c][k] - b.recorded_fine.values[c][k];
      diff += d * d;
      norm += b.recorded_fine.values[c][k] * b.recorded_fine.values[c][k];
    }
  return std::sqrt(diff / norm);
}

}  // namespace shpb
