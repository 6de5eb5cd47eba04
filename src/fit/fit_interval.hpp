#pragma once
// What a fit reports of each parameter's uncertainty (docs/methods.md §9, "Intervals"): the
// linearised interval, the parametric bootstrap's (fit/fit_bootstrap.hpp) and the one that holds.
#include <string>
#include <vector>

namespace shpb {

// The two-sided 95 % quantile of the standard normal distribution: a 95 % interval is this many
// standard uncertainties either side (normal errors; many more residuals than parameters).
constexpr double kNormalZ95 = 1.959963984540054;

struct ParameterInterval {
  bool known = false;           // false: no covariance and no bootstrap (nothing to report)
  double lower = 0, upper = 0;  // the 95 % interval reported
  std::string method;           // "linearised" or "bootstrap": which one set the interval
  double linear_lower = 0, linear_upper = 0;  // value ± 1.96 std_error (if the covariance exists)
  bool has_linear = false;
  // The bootstrap's figures over its refits (draws > 0): spread, bias (mean − value), bias-
  // corrected normal interval, fraction of refits that ended at a bound.
  double bootstrap_sd = 0, bootstrap_bias = 0, bootstrap_lower = 0, bootstrap_upper = 0;
  double at_bound = 0;
  bool has_bootstrap = false;
  bool weak = false;        // weakly identified
  std::string weak_reason;  // why, when weak
};

struct FitBootstrapSummary {
  int draws = 0;   // asked
  int failed = 0;  // refits that failed (an unstable simulation, pulses not found)
  unsigned long seed = 0;
  long simulations = 0;
  double wall_time_s = 0;
  std::vector<std::vector<double>> estimates;  // per finished refit: the last stage's unknowns
};

}  // namespace shpb
