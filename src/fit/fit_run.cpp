// The fit's stages (docs/methods.md §9). The incident pulse is left out of the signals stage: it
// carries no information on the law, and with it the rise time traded the incident's front
// against the others (LANL Cu transmitted 0.052 with it, 0.041 without).
#include "fit/fit_run.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>

#include "analysis/message_text.hpp"
#include "core/error.hpp"
#include "core/json_value.hpp"
#include "core/median.hpp"
#include "core/number_format.hpp"
#include "core/options_check.hpp"
#include "core/parallel_runner.hpp"
#include "fit/fit_bootstrap.hpp"
#include "model/law_parameters.hpp"
#include "model/scene_inputs.hpp"

namespace shpb {
namespace {

// Identifiability (docs/methods.md §9): correlations this close to ±1 mean two parameters trade
// against each other within the noise.
constexpr double kCorrelationLimit = 0.98;
// C needs two well-separated strain rates: below this ratio of the tests' highest to lowest
// plateau rate, C·ln(ratio) moves the stress by less than the usual scatter of a campaign.
constexpr double kRateRatioForC = 2.0;
// A Jacobian that changes by more than this when its step is halved is dominated by noise.
constexpr double kStepCheckLimit = 0.25;
// The curve stage evaluates a closed-form law: its only noise is double round-off (~1e-16), so
// the classic √ε ≈ 1e-8 would do; 1e-4 keeps the truncation error of the central difference
// (h²) far below the data scatter too. The signals stage uses FitOptions::relative_step.
constexpr double kCurveRelativeStep = 1e-4;
constexpr int kCurveIterations = 200;  // closed-form residuals: iterations are cheap
// A fitted window whose residuals' RMS exceeds its record's noise this many times holds a misfit
// the noise cannot explain (three quarters of its variance): the law cannot reproduce the test.
constexpr double kMisfitOverNoise = 2.0;
// Robust loss threshold in units of each residual's scale (least_squares.hpp).
constexpr double kLossDelta = 0.02;

// A wave speed is solved for as its change from the start, in units of half its bounds' width
// (least_squares.hpp: the difference step is FitOptions::relative_step of max(|x|, 1)): relative
// to its own value the step would be 5 % of c0, moving the LANL copper reflected pulse (0.76 m
// beyond its gauge) by 7.7 µs, far more than its rise; ±5 % bounds step it by 0.25 % (0.4 µs).
bool solved_as_change(const FitUnknown& u) {
  return u.test >= 0 && nuisance_is_wave_speed(u.nuisance);
}

double scale_of(const FitUnknown& u) {
  if (solved_as_change(u)) return 0.5 * (u.upper - u.lower);
  if (u.start != 0) return std::abs(u.start);
  return std::max(std::abs(u.lower), std::abs(u.upper));
}

void say(const FitOptions& options, const std::string& line) {
  if (options.progress) options.progress(line);
}

// Each test's nuisances, within their bounds (a start outside them is clamped, with a warning).
void add_nuisances(FitRun& run) {
  for (std::size_t k = 0; k < run.cases.size(); ++k)
    for (const NuisanceSpec& n : run.spec.nuisance) {
      FitUnknown u;
      u.name = run.cases[k]->name() + ":" + to_string(n.kind);
      u.test = static_cast<int>(k);
      u.nuisance = n.kind;
      u.start = run.cases[k]->start()[n.kind];
      u.dimension = nuisance_dimension(n.kind);
      if (n.relative) {
        u.lower = u.start * (1 - *n.relative), u.upper = u.start * (1 + *n.relative);
        if (!(u.upper > u.lower))
          throw input_error(run.campaign.display, n.json_path, "\"" + to_string(n.kind) + "\"",
                            "a relative range needs a nonzero start (test " + run.cases[k]->name() +
                                " starts at 0): give absolute bounds");
      } else {
        std::tie(u.lower, u.upper) = *n.bounds;
        const double clamped = std::clamp(u.start, u.lower, u.upper);
        if (clamped != u.start)
          run.warnings.push_back(u.name + ": the start " + JsonValue::format(u.start, u.dimension) +
                                 " lies outside the bounds; started at " +
                                 JsonValue::format(clamped, u.dimension));
        u.start = clamped;
      }
      run.unknowns.push_back(u);
    }
}

std::vector<Overlay> simulate_all(const FitRun& run, const std::vector<double>& v) {
  std::vector<Overlay> o(run.cases.size());
  const MaterialSpec law = run.law_with(run.law_values(v));
  run_parallel(run.cases.size(), run.threads,
               [&](std::size_t k) { o[k] = run.cases[k]->simulate(law, run.nuisance_of(k, v)); });
  return o;
}

// The curve stage's groups: each test's processed samples after equilibrium against the law's
// flow stress, relative to the test's peak. Empty (with a warning) when the stage cannot run.
std::vector<LsGroup> curve_groups(FitRun& run, FitStageReport& report) {
  const FitSpec& spec = run.spec;
  if (spec.free.empty() || !law_flow_stress(spec.material, 0.1, 1000, 293)) {
    run.warnings.push_back("stage curve skipped: " +
                           std::string(spec.free.empty() ? "no law parameter is free"
                                                         : "the law has no flow stress to fit"));
    return {};
  }
  for (std::size_t i = 0; i < spec.free.size(); ++i) report.unknowns.push_back(i);
  std::vector<LsGroup> groups;
  for (const auto& test : run.cases) {
    const auto& pts = test->curve();
    if (pts.empty()) {
      run.warnings.push_back(
          test->name() + ": no processed sample after equilibrium; left out of the curve stage");
      continue;
    }
    double peak = 0;
    for (const auto& p : pts) peak = std::max(peak, std::abs(p.stress_Pa));
    const double c = std::sqrt(test->weight() / static_cast<double>(pts.size()));
    LsGroup g;
    for (std::size_t i = 0; i < spec.free.size(); ++i) g.parameters.push_back(i);
    g.loss_scale.assign(pts.size(), c);
    g.residuals = [&run, &pts, c, peak](const std::vector<double>& theta) {
      const MaterialSpec law = run.law_with(theta);
      std::vector<double> r;
      r.reserve(pts.size());
      for (const auto& p : pts)
        r.push_back(c *
                    (*law_flow_stress(law, p.plastic_strain, p.strain_rate_1_s, p.temperature_K) -
                     p.stress_Pa) /
                    peak);
      return r;
    };
    groups.push_back(std::move(g));
  }
  if (groups.empty())
    run.warnings.push_back("stage curve skipped: no test has processed samples after equilibrium");
  return groups;
}

// The signals stage's groups: one per test, the law's parameters and the test's own nuisances.
std::vector<LsGroup> signal_groups(const FitRun& run, FitStageReport& report) {
  for (std::size_t i = 0; i < run.unknowns.size(); ++i) report.unknowns.push_back(i);
  std::vector<LsGroup> groups;
  for (std::size_t k = 0; k < run.cases.size(); ++k) {
    const FitCase& test = *run.cases[k];
    LsGroup g;
    for (std::size_t i = 0; i < run.unknowns.size(); ++i)
      if (run.unknowns[i].test < 0 || run.unknowns[i].test == static_cast<int>(k))
        g.parameters.push_back(i);
    g.loss_scale = test.residual_scales();
    for (const OverlaidPulse& w : test.fitted_windows()) g.blocks.push_back(w.end - w.begin);
    g.clock_sd_s = test.clock_sd_s();
    g.common_errors = test.rest_level_errors();
    g.clock_sensitivity = [&run, &test, k](const std::vector<double>& theta) {
      return test.clock_sensitivity(
          test.simulate(run.law_with(run.law_values(theta)), run.nuisance_of(k, theta)));
    };
    g.residuals = [&run, &test, k](const std::vector<double>& theta) {
      return test.residuals(
          test.simulate(run.law_with(run.law_values(theta)), run.nuisance_of(k, theta)));
    };
    groups.push_back(std::move(g));
  }
  return groups;
}

// The curve stage only proposes a start: the signals stage starts from it or from the material
// file's values, whichever reproduces the signals better.
void choose_signals_start(FitRun& run, const FitOptions& options) {
  auto cost_at = [&](const std::vector<double>& v) {
    std::vector<double> cost(run.cases.size());
    const MaterialSpec law = run.law_with(run.law_values(v));
    run_parallel(run.cases.size(), run.threads, [&](std::size_t k) {
      for (double r : run.cases[k]->residuals(run.cases[k]->simulate(law, run.nuisance_of(k, v))))
        cost[k] += 0.5 * r * r;
    });
    double sum = 0;
    for (double c : cost) sum += c;
    return sum;
  };
  std::vector<double> file_start = run.current;
  for (std::size_t i = 0; i < run.spec.free.size(); ++i) file_start[i] = run.unknowns[i].start;
  const double from_curve = cost_at(run.current), from_file = cost_at(file_start);
  run.simulations += 2 * static_cast<long>(run.cases.size());
  if (from_file < from_curve) {
    run.current = file_start;
    run.warnings.push_back(
        "stage signals started from the material file's values: they fit the "
        "signals better (cost " +
        format_number(from_file) +
        ") than the curve "
        "stage's (" +
        format_number(from_curve) + ")");
  }
  say(options, "signals cost at the curve stage's values " + format_number(from_curve) +
                   ", at the material file's " + format_number(from_file));
}

// One stage from the current values; false when it was skipped.
bool run_stage(FitRun& run, FitStage stage, const FitOptions& options) {
  const auto ts = std::chrono::steady_clock::now();
  const double cpu_start = cpu_seconds();
  FitStageReport report;
  report.stage = stage;
  const std::vector<LsGroup> groups =
      stage == FitStage::kCurve ? curve_groups(run, report) : signal_groups(run, report);
  if (groups.empty()) return false;
  if (stage == FitStage::kSignals && !run.after_curve.empty()) choose_signals_start(run, options);
  std::vector<LsParameter> params;
  for (std::size_t i : report.unknowns) {
    const FitUnknown& u = run.unknowns[i];
    params.push_back(
        {u.name, run.current[i], u.lower, u.upper, scale_of(u), solved_as_change(u) ? u.start : 0});
  }
  say(options,
      "stage " + to_string(stage) + ": " + std::to_string(params.size()) + " parameter(s)");
  LsOptions ls{run.threads, options.relative_step, options.max_iterations, run.spec.loss,
               kLossDelta,  options.progress};
  if (stage == FitStage::kCurve) {
    ls.relative_step = kCurveRelativeStep;
    ls.max_iterations = std::max(options.max_iterations, kCurveIterations);
  }
  report.result = solve_least_squares(params, groups, ls);
  for (std::size_t j = 0; j < report.unknowns.size(); ++j)
    run.current[report.unknowns[j]] = report.result.value[j];
  report.wall_time_s = seconds_since(ts);
  report.cpu_time_s = cpu_seconds() - cpu_start;
  if (stage == FitStage::kSignals) report.simulations = report.result.evaluations;
  run.simulations += report.simulations;
  if (stage == FitStage::kCurve) run.after_curve = run.law_values(run.current);
  std::string line = "stage " + to_string(stage) + " done: cost " +
                     format_number(report.result.cost_start) + " -> " +
                     format_number(report.result.cost) + ", " +
                     std::to_string(report.result.evaluations) + " evaluations, " +
                     format_number(report.wall_time_s) + " s (processor " +
                     format_number(report.cpu_time_s) + " s);";
  for (std::size_t j = 0; j < params.size(); ++j)
    line += " " + params[j].name + " " +
            JsonValue::format(report.result.value[j], run.unknowns[report.unknowns[j]].dimension);
  say(options, line);
  for (const auto& w : report.result.warnings)
    run.warnings.push_back("stage " + to_string(stage) + ": " + w);
  run.stages.push_back(std::move(report));
  return true;
}

// Identifiability, from the last stage run: standard errors, correlations, bounds, Jacobian steps.
void check_identifiability(FitRun& run) {
  if (run.stages.empty()) return;
  const FitStageReport& last = run.stages.back();
  const auto& r = last.result;
  const auto& idx = last.unknowns;
  for (std::size_t a = 0; a < idx.size(); ++a) {
    const FitUnknown& u = run.unknowns[idx[a]];
    if (!r.std_error.empty() && r.std_error[a] > std::abs(r.value[a]))
      run.warnings.push_back(u.name + " is not identifiable: its standard error " +
                             JsonValue::format(r.std_error[a], u.dimension) +
                             " exceeds its value " + JsonValue::format(r.value[a], u.dimension));
    for (std::size_t b = a + 1; b < idx.size(); ++b)
      if (!r.std_error.empty() &&
          std::abs(r.correlation(static_cast<long>(a), static_cast<long>(b))) > kCorrelationLimit)
        run.warnings.push_back(
            u.name + " and " + run.unknowns[idx[b]].name +
            " are not separately identifiable: correlation " +
            format_number(r.correlation(static_cast<long>(a), static_cast<long>(b))));
    if (at_bound(r.value[a], u.lower, u.upper))
      run.warnings.push_back(u.name + " ends at a bound (" +
                             JsonValue::format(r.value[a], u.dimension) +
                             "): widen the bounds or fix it");
    if (a < r.step_check.size() && r.step_check[a] > kStepCheckLimit)
      run.warnings.push_back(u.name + ": the Jacobian changes by " +
                             format_number(r.step_check[a]) +
                             " of itself when the step is halved (round-off or a kink)");
  }
}

// C (the rate term) needs tests at well-separated strain rates.
void check_rate_span(FitRun& run) {
  for (const auto& f : run.spec.free)
    if (f.name == "C") {
      double lo = 0, hi = 0;
      for (const auto& c : run.cases) {
        if (c->curve().empty()) continue;
        std::vector<double> rates;
        for (const auto& p : c->curve()) rates.push_back(p.strain_rate_1_s);
        const double rate = median(std::move(rates));
        lo = lo == 0 ? rate : std::min(lo, rate);
        hi = std::max(hi, rate);
      }
      if (!(lo > 0) || hi / lo < kRateRatioForC)
        run.warnings.push_back("C is not identifiable: the tests' strain rates span only " +
                               (lo > 0 ? format_number(hi / lo) + "x" : std::string("(none)")) +
                               " (" + std::to_string(run.cases.size()) +
                               " test(s)); the rate term needs at least two well-separated rates");
    }
}

// Lack of fit: the intervals describe the best fit of this law, which is not the material's law
// when the residuals are far above the record's noise (docs/methods.md §9, "Lack of fit").
void check_misfit(FitRun& run) {
  for (std::size_t k = 0; k < run.cases.size(); ++k) {
    const FitCase& test = *run.cases[k];
    const std::vector<double> ratio = test.misfit_over_noise(run.after[k]);
    for (std::size_t j = 0; j < ratio.size(); ++j)
      if (ratio[j] > kMisfitOverNoise)
        run.warnings.push_back(
            test.name() + ": " + test.fitted_windows()[j].name +
            fmt(" pulse: the fitted model leaves residuals %.3g times the record's noise",
                ratio[j]) +
            " (RMS over the fitted window against the baseline's): the "
            "law (or the nuisances freed) cannot reproduce this test, and the standard errors and "
            "intervals are those of the best fit of this law, not bounds on the material's");
  }
}

}  // namespace

bool FitOptions::IsValid(std::string* error) const {
  if (!threads_problem(threads).empty())
    *error = threads_problem(threads);
  else if (max_iterations < 1 || max_iterations > 10000)
    *error =
        input_error("--max-iterations", "", std::to_string(max_iterations), "expected 1 to 10000")
            .what();
  else if (!(relative_step >= 1e-8 && relative_step <= 0.1))
    *error =
        input_error("--relative-step", "", format_number(relative_step), "expected 1e-8 to 0.1")
            .what();
  else if (bootstrap < 0 || bootstrap > 100000)
    *error =
        input_error("--bootstrap", "", std::to_string(bootstrap), "expected 0 to 100000").what();
  else
    return true;
  return false;
}

std::vector<double> FitRun::law_values(const std::vector<double>& v) const {
  return std::vector<double>(v.begin(), v.begin() + static_cast<long>(spec.free.size()));
}

Nuisance FitRun::nuisance_of(std::size_t test, const std::vector<double>& v) const {
  Nuisance n = cases[test]->start();
  for (std::size_t i = 0; i < unknowns.size(); ++i)
    if (unknowns[i].test == static_cast<int>(test)) n[unknowns[i].nuisance] = v[i];
  return n;
}

MaterialSpec FitRun::law_with(const std::vector<double>& law_values) const {
  MaterialSpec m = spec.material;
  for (std::size_t i = 0; i < spec.free.size(); ++i)
    set_law_parameter(m, spec.free[i].name, law_values[i]);
  return m;
}

namespace {

// The unknowns (the law's free parameters, then each test's nuisances) and the test warnings.
void lay_out(FitRun& run, int threads, double relative_step) {
  for (std::size_t i = 0; i < run.spec.free.size(); ++i) {
    const auto& f = run.spec.free[i];
    run.unknowns.push_back({f.name, i, -1, NuisanceKind::kStrikerVelocity, f.lower, f.upper,
                            f.start, law_parameter_dimension(f.name)});
  }
  add_nuisances(run);
  for (const auto& c : run.cases)
    run.warnings.insert(run.warnings.end(), c->warnings().begin(), c->warnings().end());
  run.threads = resolve_threads(threads);
  run.relative_step = relative_step;
}

}  // namespace

FitRun prepare_fit(const std::filesystem::path& campaign_file, const FitOptions& options) {
  FitRun run;
  run.started = std::chrono::steady_clock::now();
  run.campaign = read_campaign(campaign_file);
  // Read with the file; a file without the fit's keys is refused for the missing material.
  run.spec = run.campaign.fit ? *run.campaign.fit : read_fit_spec(run.campaign);
  for (const auto& test : fit_tests(run.campaign))
    run.cases.push_back(std::make_unique<FitCase>(test, run.campaign, run.spec));
  lay_out(run, options.threads, options.relative_step);
  return run;
}

FitRun prepare_fit(const FitRun& base, const std::vector<GaugeSignals>& signals) {
  FitRun run;
  run.started = std::chrono::steady_clock::now();
  run.campaign = base.campaign;
  run.spec = base.spec;
  const std::vector<CampaignTest> tests = fit_tests(run.campaign);
  for (std::size_t k = 0; k < tests.size(); ++k)
    run.cases.push_back(std::make_unique<FitCase>(tests[k], run.campaign, run.spec, &signals[k]));
  lay_out(run, 1, base.relative_step);
  return run;
}

std::vector<std::filesystem::path> fit_inputs(const FitRun& run) {
  std::vector<std::filesystem::path> inputs = {run.campaign.file, run.spec.material_file};
  for (const auto& c : run.cases)
    for (const auto& f : scene_inputs(c->scene())) inputs.push_back(f);
  return inputs;
}

void run_fit(FitRun& run, const FitOptions& options) {
  run.current.resize(run.unknowns.size());
  for (std::size_t i = 0; i < run.unknowns.size(); ++i) run.current[i] = run.unknowns[i].start;
  // Start: the windows and NRMSE before.
  run.before = simulate_all(run, run.current);
  for (std::size_t k = 0; k < run.cases.size(); ++k) run.cases[k]->set_windows(run.before[k]);
  run.simulations = static_cast<long>(run.cases.size());
  for (FitStage stage : run.spec.stages) run_stage(run, stage, options);
  run.after = simulate_all(run, run.current);
  run.simulations += static_cast<long>(run.cases.size());
  check_identifiability(run);
  check_rate_span(run);
  check_misfit(run);
  if (options.bootstrap > 0) run_bootstrap(run, options);
  set_intervals(run);
}

}  // namespace shpb
