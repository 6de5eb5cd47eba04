#include "dispersion/bessel.hpp"

#include <cmath>
#include <numbers>

namespace shpb {
namespace {

// Above this argument e^{q} would overflow std::cyl_bessel_i; use the asymptotic series
// I_n(q) e^{−q} ≈ (2πq)^{−1/2} (1 − (4n²−1)/(8q) + (4n²−1)(4n²−9)/(2!(8q)²) − …) (Abramowitz &
// Stegun 9.7.1), whose fourth term is below 1e-9 there.
constexpr double kAsymptoticArgument = 500.0;
// J1(s)/s → 1/2 − s²/16: below this the series is exact to double precision.
constexpr double kSmallArgument = 1e-6;

double scaled_bessel_i(int n, double q) {
  if (q < kAsymptoticArgument) return std::cyl_bessel_i(static_cast<double>(n), q) * std::exp(-q);
  const double mu = 4.0 * n * n;
  const double z = 8.0 * q;
  const double series = 1.0 - (mu - 1) / z + (mu - 1) * (mu - 9) / (2 * z * z) -
                        (mu - 1) * (mu - 9) * (mu - 25) / (6 * z * z * z);
  return series / std::sqrt(2.0 * std::numbers::pi * q);
}

}  // namespace

BesselFactors bessel_factors(double s_squared) {
  BesselFactors b;
  if (s_squared >= 0) {
    const double s = std::sqrt(s_squared);
    if (s < kSmallArgument) {
      b.j0 = 1.0 - s_squared / 4;
      b.s_j1 = s_squared / 2;
      b.j1_over_s = 0.5 - s_squared / 16;
      return b;
    }
    const double j1 = std::cyl_bessel_j(1.0, s);
    b.j0 = std::cyl_bessel_j(0.0, s);
    b.s_j1 = s * j1;
    b.j1_over_s = j1 / s;
    return b;
  }
  const double q = std::sqrt(-s_squared);
  if (q < kSmallArgument) {
    b.j0 = 1.0 + q * q / 4;
    b.s_j1 = -q * q / 2;
    b.j1_over_s = 0.5 + q * q / 16;
    return b;
  }
  const double i1 = scaled_bessel_i(1, q);
  b.j0 = scaled_bessel_i(0, q);
  b.s_j1 = -q * i1;
  b.j1_over_s = i1 / q;
  return b;
}

}  // namespace shpb
