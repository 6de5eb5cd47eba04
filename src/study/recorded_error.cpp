#include "study/recorded_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/record_filter.hpp"

namespace shpb {

double recorded_gauge_error(const TimeSeries& gauges, const GaugeReference& reference,
                            bool filtered) {
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
    if (!filtered) run = record_smoothed(run);
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
