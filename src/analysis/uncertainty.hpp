#pragma once
// Monte Carlo propagation of measurement.uncertainty through the reduction of one test (GUM
// Supplement 1, JCGM 101:2008; docs/methods.md §10): every uncertain input is drawn from a normal
// distribution with its standard uncertainty, the test is reduced again with each draw (the
// record's signals scaled by the drawn bridge factors, the set-up rebuilt from the drawn bars and
// gauges), and the draws give the 95 % band of the curve at each strain, each headline figure's
// standard uncertainty and 95 % interval, and each input's share of its variance.
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "analysis/gauge_signals.hpp"
#include "analysis/monte_carlo.hpp"
#include "analysis/processing.hpp"
#include "model/scene.hpp"

namespace shpb {

// 1000 draws: the 2.5 % and 97.5 % quantiles are then each the mean of order statistics whose
// probability level has a standard error sqrt(p(1-p)/M) = 0.5 %, so a band edge moves by about
// 0.1 standard uncertainty from one seed to the next (5 % of a normal band's half-width): stable
// to the two significant digits a band is quoted with. JCGM 101 §7.2 asks M >> 1/(1-p) = 20.
inline constexpr std::size_t kDefaultDraws = 1000;
inline constexpr std::uint64_t kDefaultSeed = 1;
// Poisson's ratio enters through the Pochhammer–Chree table, solved once per value (≈ 16 ms):
// drawn values are rounded to a grid of half a standard uncertainty, which keeps the variance it
// contributes within 2 % (a uniform rounding error of ±σ/4 adds σ²/48) with 13 tables over ±3σ.
inline constexpr double kPoissonGridSigma = 0.5;

// --draws: a spread needs two draws; the upper bound, the option's since it was added, stops a
// mistyped count before the draws' results are allocated.
inline constexpr std::size_t kMinDraws = 2;
inline constexpr std::size_t kMaxDraws = 10000000;
struct MonteCarloOptions {
  std::size_t draws = kDefaultDraws;
  std::uint64_t seed = kDefaultSeed;
  int threads = 0;  // ≤ 0: all cores
  // Ceres' Solver::Options::IsValid: false with the one-line reason (--draws) in `error`.
  bool IsValid(std::string* error) const;
};

// One scalar input drawn: its name (the scene value it perturbs), nominal value and standard
// uncertainty, both SI (a trigger delay and a window start are 0 nominally).
struct UncertainInput {
  std::string name;  // in words: "gauge factor of channel 0 (gauge incident)"
  std::string key;   // the scene's JSON path that gave its uncertainty
  double nominal = 0;
  double standard_uncertainty = 0;
  std::string unit;  // SI unit of the two values ("" for a plain number)
};

struct UncertaintyResult {
  std::size_t draws = 0, failed = 0;
  std::uint64_t seed = 0;
  std::vector<UncertainInput> inputs;
  std::vector<FigureUncertainty> figures;
  std::vector<std::string> failures;  // why draws failed (the first few distinct reasons)
  // At each row of the nominal curve (its primary strain): 2.5, 50 and 97.5 % of the draws'
  // 3-wave stress, 1-wave stress and primary strain rate at that strain. A draw whose loading
  // ends before that strain gives its value at its end of loading.
  std::vector<double> stress_3wave[3], stress_1wave[3], strain_rate[3];
};

// The scene's measurement.uncertainty propagated through the reduction `nominal` of `signals`
// (as process_test made it with `options`); `m` is the measurement whose channels were read.
// Throws InputError for an uncertainty of something the reduction does not use.
UncertaintyResult propagate_uncertainty(const Scene& scene, const MeasurementSpec& m,
                                        const GaugeSignals& signals,
                                        const ProcessingOptions& options,
                                        const ProcessingResult& nominal,
                                        const MonteCarloOptions& mc);

// The refusals of the scene's measurement.uncertainty, which the scene and its record decide
// without a reduction (propagate_uncertainty's own checks, before any draw): what `shpb validate`
// applies, so that it refuses what process would.
void check_uncertainty(const Scene& scene, const GaugeSignals& signals);

// curve.csv's band columns (docs/outputs.md), in their order.
std::vector<std::pair<const char*, const std::vector<double>*>> uncertainty_band_columns(
    const UncertaintyResult& u);
// summary.json's "uncertainty" (docs/outputs.md).
nlohmann::json uncertainty_summary(const UncertaintyResult& u);
// What `process` prints: the flow stress at strain 0.1 (else the peak stress) with its 95 %
// interval, and the three largest contributors to its variance.
std::string uncertainty_headline(const UncertaintyResult& u);

}  // namespace shpb
