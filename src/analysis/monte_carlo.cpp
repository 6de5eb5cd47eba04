#include "analysis/monte_carlo.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "core/finite_values.hpp"

namespace shpb {
namespace {

constexpr double kTwoPow53 = 9007199254740992.0;

// The samples where x reaches a new maximum: x is increasing along them, so a strain is first
// reached between two of them (binary search).
struct FirstReach {
  std::vector<std::size_t> at;
  FirstReach(const std::vector<double>& x, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i)
      if (at.empty() || x[i] > x[at.back()]) at.push_back(i);
  }
  // y where x first reaches v; beyond x's maximum, y at that maximum (`beyond`: that value, or NaN
  // for a strain the reduction never reaches). Linear between the two samples, or (`nearest`) the
  // one of them nearer v.
  double operator()(const std::vector<double>& x, const std::vector<double>& y, double v,
                    bool beyond = true, bool nearest = false) const {
    if (at.empty()) return 0;
    if (v <= x[at.front()]) return y[at.front()];
    if (v > x[at.back()]) return beyond ? y[at.back()] : std::numeric_limits<double>::quiet_NaN();
    if (v == x[at.back()]) return y[at.back()];
    const auto hi = std::upper_bound(at.begin(), at.end(), v,
                                     [&](double value, std::size_t i) { return value < x[i]; });
    const std::size_t b = *hi, a = *(hi - 1);
    const double w = (v - x[a]) / (x[b] - x[a]);
    if (nearest) return w < 0.5 ? y[a] : y[b];
    return y[a] + w * (y[b] - y[a]);
  }
};

// Each input's share of a figure's variance: the squared correlation r² of the figure's draws y
// (mean, variance var) with the input's draws (z, k a draw), adjusted for the draws' number M,
// max(0, 1 − (1 − r²)(M − 1)/(M − 2)) (Ezekiel 1930): an input the figure does not depend on
// correlates by chance, r² = 1/(M − 1) on average (14 % at 8 draws), which this removes; none from
// two draws. Largest first.
std::vector<std::pair<std::size_t, double>> variance_shares(const std::vector<double>& y,
                                                            const std::vector<std::size_t>& from,
                                                            double mean, double var,
                                                            const std::vector<double>& z,
                                                            std::size_t k) {
  const double n = static_cast<double>(y.size());
  std::vector<std::pair<std::size_t, double>> shares;
  for (std::size_t i = 0; i < k; ++i) {
    double zm = 0;
    for (std::size_t d : from) zm += z[d * k + i];
    zm /= n;
    double szz = 0, szy = 0;
    for (std::size_t j = 0; j < from.size(); ++j) {
      const double dz = z[from[j] * k + i] - zm;
      szz += dz * dz;
      szy += dz * (y[j] - mean);
    }
    const double denominator = szz * var * (n - 1);
    const double r2 = denominator > 0 ? szy * szy / denominator : 0.0;
    shares.emplace_back(i, n > 2 ? std::max(0.0, 1 - (1 - r2) * (n - 1) / (n - 2)) : 0.0);
  }
  std::stable_sort(shares.begin(), shares.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  return shares;
}

}  // namespace

double NormalDraws::operator()() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  double u1 = 0;
  while (u1 == 0) u1 = static_cast<double>(engine_() >> 11) / kTwoPow53;
  const double u2 = static_cast<double>(engine_() >> 11) / kTwoPow53;
  const double r = std::sqrt(-2 * std::log(u1));
  spare_ = r * std::sin(2 * std::numbers::pi * u2);
  has_spare_ = true;
  return r * std::cos(2 * std::numbers::pi * u2);
}

double NormalDraws::uniform() { return static_cast<double>(engine_() >> 11) / kTwoPow53; }

double quantile(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) return 0;
  const double h = p * static_cast<double>(sorted.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (h - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
}

bool states_interval(std::size_t with_value, std::size_t draws) {
  return with_value >= 2 &&
         static_cast<double>(with_value) >= kBandQuantiles[2] * static_cast<double>(draws);
}

void quantile_bands(const std::vector<const std::vector<double>*>& draws, std::size_t rows,
                    std::vector<double> (&band)[3]) {
  for (auto& b : band) b.assign(rows, std::numeric_limits<double>::quiet_NaN());
  std::vector<double> column;
  for (std::size_t j = 0; j < rows; ++j) {
    column.clear();
    for (const auto* d : draws)
      if (std::isfinite((*d)[j])) column.push_back((*d)[j]);
    if (!states_interval(column.size(), draws.size())) continue;
    std::sort(column.begin(), column.end());
    for (int q = 0; q < 3; ++q) band[q][j] = quantile(column, kBandQuantiles[q]);
  }
}

CurveAtStrains curve_at_strains(const std::vector<double>& x, const std::vector<double>& stress3,
                                const std::vector<double>& stress1, const std::vector<double>& rate,
                                std::size_t n, const std::vector<double>& strains, std::size_t rows,
                                bool nearest) {
  if (n == 0 || !all_finite({x.data(), n}) || !all_finite({stress3.data(), n}) ||
      !all_finite({stress1.data(), n}) || !all_finite({rate.data(), n}))
    throw std::domain_error("the reduction produced a non-finite value");
  const FirstReach reach(x, n);
  CurveAtStrains out;
  out.stress3.resize(rows);
  out.stress1.resize(rows);
  out.rate.resize(rows);
  for (std::size_t j = 0; j < rows; ++j) {
    out.stress3[j] = reach(x, stress3, strains[j], false, nearest);
    out.stress1[j] = reach(x, stress1, strains[j], false, nearest);
    out.rate[j] = reach(x, rate, strains[j], false, nearest);
  }
  return out;
}

CurveAtStrains curve_at_strains(const ProcessingResult& r, bool one_wave,
                                const std::vector<double>& strains, std::size_t rows,
                                bool nearest) {
  const Curve& c = r.curve;
  return curve_at_strains(one_wave ? c.strain_1wave : c.strain, c.stress_3wave_Pa,
                          c.stress_1wave_Pa, one_wave ? c.strain_rate_1wave_1_s : c.strain_rate_1_s,
                          r.loading_end, strains, rows, nearest);
}

double value_at_first_reach(const std::vector<double>& x, const std::vector<double>& y,
                            std::size_t n, double at) {
  return FirstReach(x, n)(x, y, at);
}

std::vector<FigureSpec> figure_specs(const ProcessingResult& nominal, bool one_wave,
                                     bool pulse_shaper) {
  std::vector<FigureSpec> f;
  f.push_back({"peak_stress_Pa", "Pa", [](const ProcessingResult& r) { return r.peak_stress_Pa; }});
  f.push_back({"max_strain", "", [](const ProcessingResult& r) { return r.max_strain; }});
  for (const double e : kFlowStressStrains) {
    if (e > nominal.max_strain) break;
    char name[64];
    std::snprintf(name, sizeof name, "flow_stress_Pa_at_strain_%g", e);
    f.push_back({name, "Pa", [e, one_wave](const ProcessingResult& r) {
                   const Curve& c = r.curve;
                   const auto& x = one_wave ? c.strain_1wave : c.strain;
                   const auto& y = one_wave ? c.stress_1wave_Pa : c.stress_3wave_Pa;
                   if (e > r.max_strain || e <= ring_up_strain(r.time_s, x, r.equilibrium.first_s))
                     return std::nan("");
                   return value_at_first_reach(x, y, r.loading_end, e);
                 }});
  }
  f.push_back({"mean_strain_rate_1_s", "1/s",
               [](const ProcessingResult& r) { return r.mean_strain_rate_1_s; }});
  if (nominal.strain_rate_has_plateau)
    f.push_back({"plateau_strain_rate_1_s", "1/s",
                 [](const ProcessingResult& r) { return r.plateau_strain_rate_1_s; }});
  if (nominal.window_strain_rate_1_s)
    f.push_back({"mean_strain_rate_over_window_1_s", "1/s", [](const ProcessingResult& r) {
                   return r.window_strain_rate_1_s.value_or(std::nan(""));
                 }});
  if (!pulse_shaper)
    f.push_back({"striker_velocity_m_s", "m/s",
                 [](const ProcessingResult& r) { return r.inferred_striker_velocity_m_s; }});
  return f;
}

std::optional<FigureUncertainty> figure_statistics(std::string name, std::string unit,
                                                   double nominal,
                                                   const std::vector<double>& values,
                                                   const std::vector<std::size_t>& good,
                                                   const std::vector<double>& z, std::size_t k,
                                                   bool remainder) {
  FigureUncertainty fu;
  fu.name = std::move(name);
  fu.unit = std::move(unit);
  fu.nominal = nominal;
  std::vector<double> y;
  std::vector<std::size_t> from;
  for (std::size_t d : good)
    if (std::isfinite(values[d])) {
      y.push_back(values[d]);
      from.push_back(d);
    }
  fu.draws = y.size();
  if (!states_interval(y.size(), good.size())) return std::nullopt;
  const double n = static_cast<double>(y.size());
  double mean = 0;
  for (double v : y) mean += v;
  mean /= n;
  double var = 0;
  for (double v : y) var += (v - mean) * (v - mean);
  var /= n - 1;
  fu.standard_uncertainty = std::sqrt(var);
  std::vector<double> sorted = y;
  std::sort(sorted.begin(), sorted.end());
  fu.low95 = quantile(sorted, kBandQuantiles[0]);
  fu.median = quantile(sorted, kBandQuantiles[1]);
  fu.high95 = quantile(sorted, kBandQuantiles[2]);
  fu.shares = variance_shares(y, from, mean, var, z, k);
  if (remainder) {
    double explained = 0;
    for (const auto& [i, share] : fu.shares) explained += share;
    const double rest = std::max(0.0, 1 - explained);
    const auto at = std::find_if(fu.shares.begin(), fu.shares.end(),
                                 [&](const auto& s) { return s.second < rest; });
    fu.shares.insert(at, {k, rest});
  }
  return fu;
}

}  // namespace shpb
