#include "dispersion/dispersion_table.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "core/interpolation.hpp"
#include "core/interrupt.hpp"
#include "dispersion/pochhammer_chree.hpp"

namespace shpb {

DispersionTable::DispersionTable(double poisson, double max_x, int points)
    : DispersionTable(poisson, max_x, points, std::numeric_limits<double>::infinity()) {}

DispersionTable DispersionTable::up_to(double poisson, double fa_over_c0) {
  return DispersionTable(poisson, kMaxAOverLambda, kPoints, fa_over_c0);
}

const DispersionTable& DispersionTableCache::up_to(double poisson, double fa_over_c0) {
  // 30 % above the cut-off asked: a few standard uncertainties of a cut-off known to 10 %.
  constexpr double kHeadroom = 1.3;
  const std::lock_guard lock(mutex_);
  for (const auto& t : tables_)
    if (t->poisson() == poisson && t->max_normalized_frequency() >= fa_over_c0) return *t;
  tables_.push_back(
      std::make_unique<DispersionTable>(DispersionTable::up_to(poisson, kHeadroom * fa_over_c0)));
  return *tables_.back();
}

DispersionTable::DispersionTable(double poisson, double max_x, int points, double stop_fa)
    : poisson_(poisson) {
  if (points < 2 || !(max_x > 0)) throw std::invalid_argument("DispersionTable: bad grid");
  fa_.reserve(points);
  c_.reserve(points);
  m1_.reserve(points);
  m1m2_.reserve(points);
  double prev_surface = 1.0;
  for (int i = 0; i < points; ++i) {
    throw_if_interrupted();  // root finding: a long table stops within a second of a signal
    const double x = max_x * i / (points - 1);
    // Marching guess: the root at the previous x, linearly extrapolated once two are known.
    const double guess = i == 0 ? 0.0 : i == 1 ? c_[0] : 2 * c_[i - 1] - c_[i - 2];
    const double c = shpb::phase_velocity(poisson, x, guess);
    fa_.push_back(x * c);
    c_.push_back(c);
    const AmplitudeFactors a = amplitude_factors(poisson, x, c);
    m1_.push_back(a.m1);
    m1m2_.push_back(a.m1_m2);
    const double surface = 1 / a.m1;  // surface over mean strain: changes sign at the m1 pole
    if (m1_pole_fa_ == 0 && i > 0 && (surface > 0) != (prev_surface > 0)) {
      const double t = prev_surface / (prev_surface - surface);
      m1_pole_fa_ = lerp(fa_[i - 1], fa_[i], t);
    }
    prev_surface = surface;
    if (fa_.back() >= stop_fa && m1_pole_fa_ > 0 && i > 0) break;
  }
}

double DispersionTable::interpolate(const std::vector<double>& y, double fa) const {
  return shpb::interpolate(fa_, y, fa);  // the grid starts at f·a/c0 = 0
}

double DispersionTable::phase_velocity(double fa) const { return interpolate(c_, fa); }
double DispersionTable::m1(double fa) const { return interpolate(m1_, fa); }
double DispersionTable::m1_m2(double fa) const { return interpolate(m1m2_, fa); }

}  // namespace shpb
