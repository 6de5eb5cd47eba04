#pragma once
// Bounded nonlinear least squares with Ceres Solver (Levenberg–Marquardt, box bounds) over a model
// whose residuals are expensive (a simulation each): docs/methods.md §9.
//  - Parameters are scaled to x = θ / scale (scale ≈ |start|) so that one relative step and
//    Ceres' trust region see all parameters alike; one whose step must be small against its value
//    (a bar's wave speed) is solved for as its change, x = (θ − offset) / scale.
//  - The Jacobian is by central differences, x ± h with h = relative_step · max(|x|, 1), one-sided
//    at a bound; all the residual groups and perturbations of one Jacobian are evaluated in
//    parallel (each group depends on a subset of parameters: a test on the law's parameters and its
//    own nuisances, so a nuisance column costs two simulations of its test only).
//  - Each residual is its own Ceres residual block so that a robust loss acts per sample.
//  - Standard errors and correlations from the sandwich (JᵀJ)⁻¹ Jᵀ S J (JᵀJ)⁻¹ (Ceres' (JᵀJ)⁻¹),
//    S each block's own residual variance (a block: a window of one noise level), plus each
//    group's clock error and common errors (rest levels) carried through the estimator:
//    σ_c² G Gᵀ with G = (JᵀJ)⁻¹ Jᵀ ∂r/∂t_c.
#include <Eigen/Dense>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "model/fit_spec.hpp"

namespace shpb {

struct LsParameter {
  std::string name;
  double start = 0, lower = 0, upper = 0;
  double scale = 1;   // x = (θ − offset) / scale
  double offset = 0;  // a parameter far from 0 whose step must be small against its value
  double to_x(double theta) const { return (theta - offset) / scale; }
  double to_theta(double x) const { return x * scale + offset; }
};

// An error common to many residuals that they do not show (a record's removed rest level): its
// standard deviation and the residuals' derivative in it.
struct LsCommonError {
  double sd = 0;
  std::vector<double> sensitivity;
};

// The residuals of one group (a test), from the full parameter vector θ (physical units).
struct LsGroup {
  std::vector<std::size_t> parameters;  // indices into θ the group depends on
  std::function<std::vector<double>(const std::vector<double>& theta)> residuals;
  std::vector<double> loss_scale;  // per residual: the residual of a 1·δ error (robust loss)
  // The residuals' blocks of one noise level, in order (their counts; empty: the group is one):
  // each block's own variance enters the covariance.
  std::vector<std::size_t> blocks;
  // A timing error of the group's clock that the residuals do not show (the measured reference
  // time's own noise): its standard deviation, and the residuals' derivative in it at θ (one more
  // evaluation, at the solution). Counted in the covariance when both are set.
  double clock_sd_s = 0;
  std::function<std::vector<double>(const std::vector<double>& theta)> clock_sensitivity;
  std::vector<LsCommonError> common_errors;  // counted in the covariance as the clock's
};

struct LsOptions {
  int threads = 0;
  double relative_step = 1e-4;
  int max_iterations = 40;
  FitLoss loss = FitLoss::kLinear;
  double loss_delta = 0.02;                          // robust loss threshold in units of loss_scale
  std::function<void(const std::string&)> progress;  // one line per iteration
};

struct LsResult {
  std::vector<double> value, std_error;  // std_error empty when the covariance failed
  Eigen::MatrixXd correlation;
  double cost_start = 0, cost = 0;  // ½ Σ ρ(r²)
  std::size_t residuals = 0;
  int iterations = 0;
  long evaluations = 0;  // group evaluations (a simulation each in the signals stage)
  std::string termination;
  bool converged = false;
  std::vector<double> step_check;  // per parameter: |J(h) − J(h/2)| / |J(h)| at the solution
  Eigen::MatrixXd jacobian;        // ∂r/∂x at the solution (x = θ / scale); empty if it failed
  std::vector<std::string> warnings;
};

// A value within a millionth of its bounds' span of a bound ends at that bound: the bound, not
// the data, holds it (the data may ask for a value beyond it), so the Jacobian's interval, which
// sees one side only, says nothing of it. The one judgement of `fit` (its warning, its bootstrap's
// refits) and `calibrate` (no uncertainty for such a parameter).
inline constexpr double kAtBoundSpan = 1e-6;
inline bool at_bound(double value, double lower, double upper) {
  const double span = upper - lower;
  return std::abs(value - lower) < kAtBoundSpan * span ||
         std::abs(upper - value) < kAtBoundSpan * span;
}

LsResult solve_least_squares(const std::vector<LsParameter>& parameters,
                             const std::vector<LsGroup>& groups, const LsOptions& options);

}  // namespace shpb
