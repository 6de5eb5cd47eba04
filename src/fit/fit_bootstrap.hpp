#pragma once
// The fit's intervals (docs/methods.md §9, "Intervals"). The linearised standard errors assume a
// cost quadratic in the parameters over their uncertainty and residuals as independent as the
// noise; a parametric bootstrap checks both (Efron & Tibshirani 1993, An Introduction to the
// Bootstrap, ch. 6 and §13.3; Davison & Hinkley 1997, Bootstrap Methods and their Application,
// §2.2, §8.2): the fitted model stands for the truth, each refit sees the fitted simulation plus a
// noise draw and is fitted again by the same stages from the same start.
//  - The noise of a gauge is drawn by the autoregressive sieve (Kreiss 1992; Bühlmann 1997,
//    Bernoulli 3:123) from the fit's own residuals of that gauge over its fitted windows: an AR(p)
//    model by Yule–Walker with p chosen by AIC, driven by its own centred innovations drawn with
//    replacement. A draw keeps the record noise's level, distribution and whole autocorrelation
//    (white: p = 0), so the spread of a sum over many samples — what a fitted parameter is — is
//    that of the record noise. (Moving blocks as long as twice the correlation time lose the
//    correlation across every block join: the variance of such a sum falls by about the
//    correlation time over the block length, a third to a half, and the intervals under-cover.)
//  - The bootstrap interval is the bias-corrected normal one: value − bias ± t(0.975, N−1) · sd of
//    the refits (t for the spread's own sampling error at a few tens of refits).
//  - The interval reported is the linearised one where it holds (the refits' root-mean-square
//    distance from the value within the sampling error of their spread of the standard error) and
//    the hull of both where it does not (method "bootstrap").
#include <random>
#include <vector>

#include "fit/fit_run.hpp"

namespace shpb {

// The residuals' noise model: AR coefficients a_1..a_p (x_t = Σ a_j x_{t−j} + e_t) and the
// centred innovations e_t of the residuals.
struct NoiseModel {
  std::vector<double> ar;
  std::vector<double> innovations;
};

// Yule–Walker (Levinson–Durbin) AR fits of order 0 … min(n/10, kMaxNoiseOrder), the order by AIC
// (Akaike 1974): n ln σ²_p + 2p.
inline constexpr std::size_t kMaxNoiseOrder = 40;
NoiseModel fit_noise_model(const std::vector<double>& residuals);

// n samples of the model driven by innovations drawn with replacement, after a burn-in as long as
// the residuals (the start forgotten).
std::vector<double> draw_noise(const NoiseModel& model, std::size_t n, std::mt19937_64& rng);

// The options.bootstrap refits of `run` (after run_fit's stages), in parallel over run.threads
// (each refit on one thread); fills run.bootstrap. Interrupted propagates; a refit that fails
// (unstable simulation, pulses not found) is counted and left out.
void run_bootstrap(FitRun& run, const FitOptions& options);

// Each unknown's interval from the last stage's standard errors and the bootstrap (if run), and
// the weak-identification verdicts (warnings in run.warnings).
void set_intervals(FitRun& run);

// Two-sided 95 % quantile of Student's t with `dof` degrees of freedom (Cornish–Fisher expansion,
// Abramowitz & Stegun 26.7.5; better than 1e-3 relative for dof ≥ 3).
double student_t95(double dof);

}  // namespace shpb
