#pragma once
// `shpb fit` as a library (docs/methods.md §9): prepare_fit() reads the campaign, every test's
// scene and measurement and lays out the unknowns (all input errors, before anything is written);
// run_fit() simulates every test with the starting law, runs the stages (`curve`: the law's flow
// stress against the processed curves; `signals`: simulated against measured reflected and
// transmitted pulses, law and nuisance parameters) and checks identifiability. The result holds
// everything fit/fit_report.hpp writes.
#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/clock.hpp"
#include "core/units.hpp"
#include "fit/fit_case.hpp"
#include "fit/fit_interval.hpp"
#include "fit/least_squares.hpp"
#include "model/campaign.hpp"
#include "model/fit_spec.hpp"

namespace shpb {

struct FitOptions {
  int threads = 0;          // simulations of one Jacobian in parallel; 0: all cores
  int max_iterations = 40;  // per stage
  // Central-difference step of the signals stage, relative to each parameter: well above the
  // simulator's sensitivity noise (docs/methods.md §9; docs/validation.md (shpb fit) gives the
  // measurement).
  double relative_step = 0.05;
  // Refits of the parametric bootstrap that checks the linearised intervals (fit/fit_bootstrap.hpp;
  // 0: linearised only), and the seed of its noise draws: 30 give its spread to ±13 %
  // (1/√(2·29)), enough to tell a linearised standard error that is right from one that is too
  // small by half.
  int bootstrap = 30;
  unsigned long seed = 1;
  std::function<void(const std::string&)> progress;  // one line at a time; empty: silent
  // Ceres' Solver::Options::IsValid: false with the reason in `error` for options out of range.
  bool IsValid(std::string* error) const;
};

// One unknown: a law parameter (test < 0) or a test's nuisance parameter.
struct FitUnknown {
  std::string name;     // "A", or "<test>:striker_velocity"
  std::size_t law = 0;  // index into spec.free if a law parameter
  int test = -1;        // the test of a nuisance parameter
  NuisanceKind nuisance = NuisanceKind::kStrikerVelocity;
  double lower = 0, upper = 0, start = 0;
  Dimension dimension = Dimension::kDimensionless;
};

struct FitStageReport {
  FitStage stage = FitStage::kCurve;
  LsResult result;
  std::vector<std::size_t> unknowns;  // indices into FitRun::unknowns
  double wall_time_s = 0, cpu_time_s = 0;
  long simulations = 0;
};

struct FitRun {
  std::chrono::steady_clock::time_point started;
  Campaign campaign;
  FitSpec spec;
  std::vector<std::unique_ptr<FitCase>> cases;
  std::vector<FitUnknown> unknowns;  // the law's free parameters, then each test's nuisances
  std::vector<std::string> warnings;
  int threads = 1;
  double relative_step = 0;
  // Filled by run_fit():
  std::vector<double> current;      // every unknown's value after the last stage
  std::vector<double> after_curve;  // law values after the curve stage (empty if not run)
  std::vector<Overlay> before, after;
  std::vector<FitStageReport> stages;
  long simulations = 0;
  FitBootstrapSummary bootstrap;
  std::vector<ParameterInterval> intervals;  // per unknown (fit/fit_bootstrap.hpp)

  std::vector<double> law_values(const std::vector<double>& v) const;
  Nuisance nuisance_of(std::size_t test, const std::vector<double>& v) const;
  MaterialSpec law_with(const std::vector<double>& law_values) const;
};

// Reads and checks everything (InputError, exit 2).
FitRun prepare_fit(const std::filesystem::path& campaign_file, const FitOptions& options);
// A fit of the same campaign on other records (a bootstrap draw): `base`'s campaign, spec and
// options, `signals[k]` standing for test k's measured record.
FitRun prepare_fit(const FitRun& base, const std::vector<GaugeSignals>& signals);
// The files the fit reads: its output folder may hold none of them.
std::vector<std::filesystem::path> fit_inputs(const FitRun& run);
// The stages, then the intervals (with the bootstrap's refits when options.bootstrap > 0);
// NumericalError for an unstable simulation.
void run_fit(FitRun& run, const FitOptions& options);

}  // namespace shpb
