#pragma once
// Figures of a square pulse recorded by a gauge: arrival and duration (half-level crossings,
// interpolated between samples), plateau mean and standard deviation over 15–85 % of the
// duration (the measure of docs/methods.md §2).
#include <cmath>
#include <vector>

namespace shpb::test {

struct PulseFigures {
  bool found = false;
  double arrival_s = 0, duration_s = 0, mean = 0, std = 0;
};

inline PulseFigures square_pulse(const std::vector<double>& t, const std::vector<double>& x,
                                 double expected, double from_s = 0) {
  PulseFigures p;
  long first = -1, last = -1;
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (t[k] < from_s) continue;
    const bool in = x[k] / expected > 0.5;
    if (in && first < 0) first = static_cast<long>(k);
    if (first >= 0) {
      if (!in) break;
      last = static_cast<long>(k);
    }
  }
  if (first < 0) return p;
  p.found = true;
  // Half-level crossings, interpolated linearly between samples.
  auto crossing = [&](long before, long after) {
    const double a = x[before] / expected - 0.5, b = x[after] / expected - 0.5;
    return t[before] + (t[after] - t[before]) * a / (a - b);
  };
  p.arrival_s = first > 0 ? crossing(first - 1, first) : t[first];
  const double end = last + 1 < static_cast<long>(x.size()) ? crossing(last, last + 1) : t[last];
  p.duration_s = end - p.arrival_s;
  const long a = first + static_cast<long>(0.15 * (last - first));
  const long b = first + static_cast<long>(0.85 * (last - first));
  double sum = 0, sq = 0;
  for (long k = a; k <= b; ++k) sum += x[k];
  p.mean = sum / (b - a + 1);
  for (long k = a; k <= b; ++k) sq += (x[k] - p.mean) * (x[k] - p.mean);
  p.std = std::sqrt(sq / (b - a + 1));
  return p;
}

// Mean of x over [t0, t1].
inline double window_mean(const std::vector<double>& t, const std::vector<double>& x, double t0,
                          double t1) {
  double sum = 0;
  long n = 0;
  for (std::size_t k = 0; k < x.size(); ++k)
    if (t[k] >= t0 && t[k] <= t1) {
      sum += x[k];
      ++n;
    }
  return n ? sum / n : std::nan("");
}

}  // namespace shpb::test
