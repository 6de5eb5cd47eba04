#pragma once
// What every Monte Carlo of shpb shares (GUM Supplement 1, JCGM 101:2008 §7; docs/methods.md §10):
// the seeded draws, the 2.5 / 50 / 97.5 % bands of a curve over the draws, a reduction's curve read
// at given strains, its headline figures, and a figure's statistics over the draws. Used by
// `process` with measurement.uncertainty (analysis/uncertainty.hpp) and by `study --sweep
// monte-carlo` (study/monte_carlo_sweep.hpp): one rule for a band and an interval.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "analysis/processing.hpp"
#include "model/scene.hpp"

namespace shpb {

// Standard normal draws, Box–Muller on a 64-bit Mersenne twister, and uniform draws on [0, 1):
// the same numbers from every standard library (std::normal_distribution's algorithm is the
// library's own).
class NormalDraws {
 public:
  explicit NormalDraws(std::uint64_t seed) : engine_(seed) {}
  double operator()();
  double uniform();

 private:
  std::mt19937_64 engine_;
  double spare_ = 0;
  bool has_spare_ = false;
};

// A bar's diameter set to a drawn d: its area scaled by (d/d0)² (a section of another shape keeps
// it).
inline void set_bar_diameter(BarSpec& b, double d) {
  b.area_m2 *= (d / b.diameter_m) * (d / b.diameter_m);
  b.diameter_m = d;
}

// The quantiles of a band: 2.5, 50 and 97.5 %.
inline constexpr double kBandQuantiles[3] = {0.025, 0.5, 0.975};

// Quantile p of sorted values, linear between order statistics (Hyndman & Fan type 7).
double quantile(const std::vector<double>& sorted, double p);

// Whether `with_value` of `draws` draws give a 95 % band or interval: at least two, and at least
// kBandQuantiles[2] of them, as more than 2.5 % of the draws without a value leave no 2.5 %
// quantile of them all (the quantiles of those that have one are of a selection: the draws whose
// loading reaches a strain, docs/methods.md §10).
bool states_interval(std::size_t with_value, std::size_t draws);

// band[q][j]: quantile kBandQuantiles[q] of the draws' values at point j, for j < rows (every
// draw at least `rows` long), over the draws that have a finite value there; NaN (no band) where
// they do not state an interval (states_interval).
void quantile_bands(const std::vector<const std::vector<double>*>& draws, std::size_t rows,
                    std::vector<double> (&band)[3]);

// A reduction's 3-wave stress, 1-wave stress and primary strain rate where its primary strain
// first reaches each of the first `rows` of `strains` (NaN beyond its largest strain: a draw whose
// loading ends short of a strain has no state there). Linear between the two samples the strain
// lies between, or (`nearest`) the nearer of them: a draw carrying the record's noise keeps its
// noise there, as the nominal curve's own samples do, where interpolating would average two
// samples' noise (by √(w² + (1 − w)²), 0.82 on average: docs/methods.md §10). Throws
// std::domain_error when the reduction holds a non-finite value or no loading.
struct CurveAtStrains {
  std::vector<double> stress3, stress1, rate;
};
CurveAtStrains curve_at_strains(const ProcessingResult& r, bool one_wave,
                                const std::vector<double>& strains, std::size_t rows,
                                bool nearest = false);
// The same from a curve's columns: strain x, the stresses and the rate over samples [0, n).
CurveAtStrains curve_at_strains(const std::vector<double>& x, const std::vector<double>& stress3,
                                const std::vector<double>& stress1, const std::vector<double>& rate,
                                std::size_t n, const std::vector<double>& strains, std::size_t rows,
                                bool nearest = false);

// The value of `y` where `x` first reaches `at` along the samples [0, n) (linear between the
// samples where x reaches a new maximum); y at the last of them beyond x's maximum.
double value_at_first_reach(const std::vector<double>& x, const std::vector<double>& y,
                            std::size_t n, double at);

// Engineering strains at which the flow stress is quoted with its uncertainty (those the nominal
// curve reaches).
inline constexpr double kFlowStressStrains[] = {0.05, 0.1, 0.2, 0.3};

// The headline figures of a reduction (those the nominal one gives); NaN where a draw gives none.
struct FigureSpec {
  std::string name, unit;
  std::function<double(const ProcessingResult&)> of;
};
std::vector<FigureSpec> figure_specs(const ProcessingResult& nominal, bool one_wave,
                                     bool pulse_shaper);

// A figure over the draws: nominal, median, standard deviation (its standard uncertainty) and the
// probabilistically symmetric 95 % interval; each input's share of its variance (squared
// correlation of the figure with that input's draws: the linear first-order share for independent
// inputs, Saltelli et al. 2008), largest first.
struct FigureUncertainty {
  std::string name;
  std::string unit;
  double nominal = 0, median = 0, standard_uncertainty = 0, low95 = 0, high95 = 0;
  std::size_t draws = 0;  // draws that gave it (a draw that does not reach a strain gives none)
  std::vector<std::pair<std::size_t, double>> shares;  // (index into inputs, share)
};

// The statistics of values[d] over the draws `from` where it is finite; none (nullopt) where those
// do not state an interval (states_interval). The shares against inputs[d * k + i] (input i of
// draw d, any affine scale). With `remainder`, one more input, index k, drawn as no scalar (a
// record's noise, a whole series per draw): its share is what the k scalar inputs leave,
// max(0, 1 − Σ shares), for a figure linear in independent inputs the share of that input.
std::optional<FigureUncertainty> figure_statistics(std::string name, std::string unit,
                                                   double nominal,
                                                   const std::vector<double>& values,
                                                   const std::vector<std::size_t>& from,
                                                   const std::vector<double>& inputs, std::size_t k,
                                                   bool remainder = false);

}  // namespace shpb
