#include "dispersion/pochhammer_chree.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "dispersion/bessel.hpp"

namespace shpb {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
// Below this a/Λ the Rayleigh–Love curve 1/sqrt(1 + 2ν²π²x²) agrees with the exact mode to
// O(x⁴) ≈ 1e-16, and the frequency equation is too flat to bracket reliably.
constexpr double kLongWaveX = 1e-4;
// Root tolerance in c/c0 (the reference tables are solved to ~1e-12).
constexpr double kRootTolerance = 1e-14;
// Points of the bracketing scan over [0.9 c_R, c0]; the first mode is the only root in that
// range for small x and the lowest one for large x, where higher modes tend to c_T > c_R.
constexpr int kScanPoints = 400;
// Marching (a guess given): first bracket guess ± this in c/c0, grown by kMarchingGrowth up to
// kMarchingBand; a linear extrapolation on the table's grid (Δx = 5e-4) is off by ~1e-7.
constexpr double kMarchingHalfWidth = 1e-6;
constexpr double kMarchingGrowth = 16;
constexpr double kMarchingBand = 0.02;
// Relative step of the central differences for G_k and G_ω.
constexpr double kDerivativeStep = 1e-6;

struct Elastic {
  double cl2, ct2;  // (c_L/c0)², (c_T/c0)²
};
Elastic elastic(double nu) { return {(1 - nu) / ((1 + nu) * (1 - 2 * nu)), 1 / (2 * (1 + nu))}; }

// Frequency equation in (k, ω) with a = c0 = 1, divided by β and k⁴ (docs/methods.md §5).
double equation_k_omega(const Elastic& e, double k, double omega) {
  const double k2 = k * k;
  const double alpha2 = omega * omega / e.cl2 - k2;
  const double beta2 = omega * omega / e.ct2 - k2;
  const BesselFactors a = bessel_factors(alpha2);
  const BesselFactors b = bessel_factors(beta2);
  const double f = 2 * (beta2 + k2) * a.s_j1 * b.j1_over_s -
                   (beta2 - k2) * (beta2 - k2) * a.j0 * b.j1_over_s - 4 * k2 * a.s_j1 * b.j0;
  return f / (k2 * k2);
}

// Illinois regula falsi on a sign-changing bracket [lo, hi].
template <class F>
double refine_root(F&& f, double lo, double hi, double flo, double fhi) {
  int side = 0;
  for (int it = 0; it < 200 && hi - lo > kRootTolerance; ++it) {
    const double mid = (lo * fhi - hi * flo) / (fhi - flo);
    const double fm = f(mid);
    if (fm == 0) return mid;
    if ((fm > 0) == (fhi > 0)) {
      hi = mid;
      fhi = fm;
      if (side == 1) flo /= 2;
      side = 1;
    } else {
      lo = mid;
      flo = fm;
      if (side == -1) fhi /= 2;
      side = -1;
    }
  }
  return 0.5 * (lo + hi);
}

double rayleigh_love(double nu, double x) {
  return 1 / std::sqrt(1 + 2 * nu * nu * std::numbers::pi * std::numbers::pi * x * x);
}

}  // namespace

WaveSpeeds wave_speeds(double nu) {
  const Elastic e = elastic(nu);
  // Rayleigh equation in ξ = c/c_T: (2 − ξ²)² = 4 sqrt(1 − η²ξ²) sqrt(1 − ξ²), η = c_T/c_L;
  // the root lies in (0.8, 1) for 0 ≤ ν ≤ 0.5.
  const double eta2 = e.ct2 / e.cl2;
  auto r = [&](double xi) {
    const double x2 = xi * xi;
    return (2 - x2) * (2 - x2) - 4 * std::sqrt(1 - eta2 * x2) * std::sqrt(1 - x2);
  };
  const double lo = 0.8, hi = 1.0;
  const double xi = refine_root(r, lo, hi, r(lo), r(hi));
  const double ct = std::sqrt(e.ct2);
  return {std::sqrt(e.cl2), ct, xi * ct};
}

double frequency_equation(double nu, double x, double c) {
  const double k = kTwoPi * x;
  return equation_k_omega(elastic(nu), k, k * c);
}

double phase_velocity(double nu, double x, double guess) {
  if (!(nu >= 0 && nu < 0.5) || !(x >= 0))
    throw std::invalid_argument("phase_velocity: need 0 <= nu < 0.5 and a/lambda >= 0");
  if (x < kLongWaveX) return rayleigh_love(nu, x);
  auto f = [&](double c) { return frequency_equation(nu, x, c); };
  const double c_hi_limit = 1.0 + 1e-9;
  double lo = 0.9 * wave_speeds(nu).rayleigh;
  double hi = c_hi_limit;
  int points = kScanPoints;
  if (guess > 0) {
    // Marching: the root lies close to the guess (the neighbouring x's root, or extrapolated
    // from two of them). A bracket grown from a small half-width around it costs two to four
    // evaluations where a scan costs forty; failing that, the narrow band below the guess (the
    // first mode's phase velocity decreases with x), then the full range.
    for (double half = kMarchingHalfWidth; half <= kMarchingBand; half *= kMarchingGrowth) {
      const double a = std::max(lo, guess - half), b = std::min(c_hi_limit, guess + half);
      const double fa = f(a), fb = f(b);
      if (fa == 0) return a;
      if ((fa > 0) != (fb > 0)) return refine_root(f, a, b, fa, fb);
    }
    lo = std::max(lo, guess - kMarchingBand);
    hi = std::min(c_hi_limit, guess + 1e-3);
    points = 40;
  }
  for (int attempt = 0; attempt < 2; ++attempt) {
    double c_prev = lo, f_prev = f(lo);
    for (int i = 1; i <= points; ++i) {
      const double c = lo + (hi - lo) * i / points;
      const double fc = f(c);
      if (f_prev == 0) return c_prev;
      if ((fc > 0) != (f_prev > 0)) return refine_root(f, c_prev, c, f_prev, fc);
      c_prev = c;
      f_prev = fc;
    }
    lo = 0.9 * wave_speeds(nu).rayleigh;
    hi = c_hi_limit;
    points = kScanPoints;
  }
  throw std::runtime_error("phase_velocity: no root of the Pochhammer–Chree equation found");
}

double group_velocity(double nu, double x, double c) {
  if (x < kLongWaveX) {
    const double a = 2 * nu * nu * std::numbers::pi * std::numbers::pi;
    return c - a * x * x * c * c * c;  // c + x dc/dx of the Rayleigh–Love curve
  }
  const Elastic e = elastic(nu);
  const double k = kTwoPi * x, omega = k * c;
  const double hk = kDerivativeStep * k, hw = kDerivativeStep * omega;
  const double g_k =
      (equation_k_omega(e, k + hk, omega) - equation_k_omega(e, k - hk, omega)) / (2 * hk);
  const double g_w =
      (equation_k_omega(e, k, omega + hw) - equation_k_omega(e, k, omega - hw)) / (2 * hw);
  return -g_k / g_w;
}

namespace {
struct ModeFactors {
  double surface;      // surface strain × common scale
  double mean_strain;  // mean strain × the same scale
  double mean_stress;  // mean stress / E × the same scale
};

// Axial strain of the mode, ε_zz(r) ∝ J0(αr) + Q J0(βr), Q = 2αβ J1(αa)/((k²−β²) J1(βa)) (from
// σ_rz = 0 at r = a), and σ_zz = λ ∇·u + 2μ ε_zz with ∇·u ∝ (α² + k²)/k² J0(αr). Multiplied
// through by (k²−β²)·J1(βa)/β so nothing divides by zero except the true pole of m1.
ModeFactors mode_factors(double nu, double x, double c) {
  const Elastic e = elastic(nu);
  const double k = kTwoPi * x, omega = k * c, k2 = k * k;
  const double alpha2 = omega * omega / e.cl2 - k2;
  const double beta2 = omega * omega / e.ct2 - k2;
  const BesselFactors a = bessel_factors(alpha2);
  const BesselFactors b = bessel_factors(beta2);
  const double kb = (k2 - beta2) / k2;
  const double d = kb * a.j1_over_s + 2 * a.s_j1 / k2;  // mean strain without the factor 2·TJ1β
  const double lambda_over_e = nu / ((1 + nu) * (1 - 2 * nu));
  const double mu_over_e = 1 / (2 * (1 + nu));
  const double n2 = lambda_over_e * (alpha2 + k2) / k2 * kb * a.j1_over_s + 2 * mu_over_e * d;
  return {kb * a.j0 * b.j1_over_s + 2 * a.s_j1 / k2 * b.j0, 2 * b.j1_over_s * d,
          2 * b.j1_over_s * n2};
}
}  // namespace

double surface_over_mean_strain(double nu, double x, double c) {
  if (x < kLongWaveX) return 1.0;
  const ModeFactors m = mode_factors(nu, x, c);
  return m.surface / m.mean_strain;
}

AmplitudeFactors amplitude_factors(double nu, double x, double c) {
  if (x < kLongWaveX) return {};
  const ModeFactors m = mode_factors(nu, x, c);
  return {m.mean_strain / m.surface, m.mean_stress / m.surface};
}

}  // namespace shpb
