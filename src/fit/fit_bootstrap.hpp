#pragma once
// The fit's intervals (docs/methods.md §9, "Intervals"). The linearised standard errors assume a
// cost quadratic in the parameters over their uncertainty and residuals as independent as the
// noise; a parametric bootstrap checks both (Efron & Tibshirani 1993, An Introduction to the
// Bootstrap, ch. 6 and §13.3; Davison & Hinkley 1997, Bootstrap Methods and their Application,
// §2.2, §8.2): the fitted model stands for the truth, each refit sees the fitted simulation plus a
// noise draw and is fitted again by the same stages from the same start.
//  - The noise of a gauge is drawn by moving blocks (Künsch 1989, Ann. Stat. 17:1217) from the
//    fit's own residuals of that gauge over its fitted windows: the draws keep the record noise's
//    level, distribution and correlation (white or coloured) without a model of it.
//  - The bootstrap interval is the bias-corrected normal one: value − bias ± t(0.975, N−1) · sd of
//    the refits (t for the spread's own sampling error at a few tens of refits).
//  - The interval reported is the linearised one where it holds (the refits' root-mean-square
//    distance from the value within the sampling error of their spread of the standard error) and
//    the hull of both where it does not (method "bootstrap").
#include <random>
#include <vector>

#include "fit/fit_run.hpp"

namespace shpb {

// Block length of the residual resampling: at least ⌈L^(1/3)⌉ (Hall, Horowitz & Jing 1995,
// Biometrika 82:561) and twice the lag where the residuals' autocorrelation first falls below 1/e.
std::size_t residual_block_length(const std::vector<double>& residuals);

// A noise series of n samples made of blocks of `block` consecutive residuals from random starts.
std::vector<double> block_resample(const std::vector<double>& residuals, std::size_t n,
                                   std::size_t block, std::mt19937_64& rng);

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
