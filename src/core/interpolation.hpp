#pragma once
// Linear interpolation, the one rule behind every resampling in shpb (gauge records onto a common
// clock, pulses delayed by a fraction of a sample, dispersion tables, recorders onto the output
// grid, curves read at a strain).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>

namespace shpb {

// a + t·(b − a): a at t = 0, b at t = 1.
inline double lerp(double a, double b, double t) { return a + t * (b - a); }

// y(x) on increasing abscissae xs (non-empty, ys of the same size), held at the end values
// outside [xs.front(), xs.back()].
inline double interpolate(std::span<const double> xs, std::span<const double> ys, double x) {
  if (x <= xs.front()) return ys.front();
  if (x >= xs.back()) return ys.back();
  const auto j = static_cast<std::size_t>(std::upper_bound(xs.begin(), xs.end(), x) - xs.begin());
  return lerp(ys[j - 1], ys[j], (x - xs[j - 1]) / (xs[j] - xs[j - 1]));
}

// A uniformly sampled record y read at the fractional sample index k, as if every sample before
// it were `before` and every sample after it `after` (linear between the edge sample and those).
inline double sample_at(std::span<const double> y, double k, double before, double after) {
  const auto n = static_cast<double>(y.size());
  if (!(k > -1)) return before;
  if (!(k < n)) return after;
  const double lower = std::floor(k);
  const auto j = static_cast<std::ptrdiff_t>(lower);
  const auto size = static_cast<std::ptrdiff_t>(y.size());
  const double a = j < 0 ? before : y[static_cast<std::size_t>(j)];
  const double b = j + 1 >= size ? after : y[static_cast<std::size_t>(j + 1)];
  return lerp(a, b, k - lower);
}

}  // namespace shpb
