#pragma once
// Pearson's correlation coefficient of two records of one length: the
// covariance over the product of the standard deviations, 0 where either is constant. Each record
// is divided by its largest magnitude first, so no square overflows whatever its scale (a bridge
// factor off by 1e300); the coefficient is scale-free, so this changes only its rounding.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>

namespace shpb {

inline double correlation_coefficient(std::span<const double> a, std::span<const double> b) {
  double unit_a = 0, unit_b = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    unit_a = std::max(unit_a, std::abs(a[i])), unit_b = std::max(unit_b, std::abs(b[i]));
  if (a.empty() || unit_a == 0 || unit_b == 0) return 0;
  const double n = static_cast<double>(a.size());
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) ma += a[i] / unit_a, mb += b[i] / unit_b;
  ma /= n, mb /= n;
  double ab = 0, aa = 0, bb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double da = a[i] / unit_a - ma, db = b[i] / unit_b - mb;
    ab += da * db, aa += da * da, bb += db * db;
  }
  return aa > 0 && bb > 0 ? ab / std::sqrt(aa * bb) : 0;
}

}  // namespace shpb
