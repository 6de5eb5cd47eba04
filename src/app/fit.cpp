// shpb fit CAMPAIGN.json -o DIR: calibrate a specimen law from measured tests (docs/methods.md §9).
//  1. read the campaign (tests[], material, free, nuisance, stages, loss) and every test's scene
//     and measurement; all input errors before anything is written;
//  2. simulate every test with the starting law (NRMSE "before");
//  3. stage `curve`: least squares of the law's flow stress against every test's processed true
//     stress after equilibrium, at its true plastic strain, strain rate and temperature;
//  4. stage `signals`: least squares of simulated (dispersed as compare does) against measured
//     reflected and transmitted pulses of all tests at once, law and nuisance parameters (the
//     incident pulse is left out: it carries no information on the law, and with it the rise
//     time traded the incident's front against the others: LANL Cu transmitted 0.052 with it,
//     0.041 without);
//  5. write fit.json (a material file), summary.json, curves.csv, signals.csv.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "core/checked_write.hpp"
#include "core/csv_writer.hpp"
#include "core/error.hpp"
#include "core/json_value.hpp"
#include "core/median.hpp"
#include "core/number_format.hpp"
#include "core/output_folder.hpp"
#include "core/parallel_runner.hpp"
#include "fit/fit_case.hpp"
#include "fit/fit_spec.hpp"
#include "fit/law_parameters.hpp"
#include "fit/least_squares.hpp"
#include "model/calibration.hpp"
#include "version.hpp"

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
// (h²) far below the data scatter too. The signals stage uses FitArgs::relative_step.
constexpr double kCurveRelativeStep = 1e-4;
constexpr int kCurveIterations = 200;  // closed-form residuals: iterations are cheap

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}
// Processor time of the whole process (every thread), s: on a shared machine the wall time
// depends on the others' load, the processor time much less.
double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

struct Unknown {
  std::string name;     // "A", or "<test>:striker_velocity"
  std::size_t law = 0;  // index into spec.free if a law parameter
  int test = -1;        // the test of a nuisance parameter
  std::string nuisance;
  double lower = 0, upper = 0, start = 0;
  Dimension dimension = Dimension::kDimensionless;
};

struct StageReport {
  FitStage stage;
  LsResult result;
  std::vector<std::size_t> unknowns;  // indices into the unknown list
  double wall_time_s = 0, cpu_time_s = 0;
  long simulations = 0;
};

// A stage in summary.json (docs/outputs.md), without its parameter values (named by the writer).
void to_json(nlohmann::json& j, const StageReport& st) {
  j = {{"stage", to_string(st.stage)},
       {"cost_start", st.result.cost_start},
       {"cost", st.result.cost},
       {"residuals", st.result.residuals},
       {"iterations", st.result.iterations},
       {"evaluations", st.result.evaluations},
       {"simulations", st.simulations},
       {"wall_time_s", st.wall_time_s},
       {"cpu_time_s", st.cpu_time_s},
       {"converged", st.result.converged},
       {"termination", st.result.termination}};
  if (st.stage == FitStage::kSignals) {
    j["simulations_per_second"] = st.wall_time_s > 0 ? st.simulations / st.wall_time_s : 0.0;
    j["simulations_per_cpu_second"] = st.cpu_time_s > 0 ? st.simulations / st.cpu_time_s : 0.0;
  }
}

MaterialSpec law_with(const FitSpec& spec, const std::vector<double>& law_values) {
  MaterialSpec m = spec.material;
  for (std::size_t i = 0; i < spec.free.size(); ++i)
    set_law_parameter(m, spec.free[i].name, law_values[i]);
  return m;
}

double scale_of(const Unknown& u) {
  if (u.start != 0) return std::abs(u.start);
  return std::max(std::abs(u.lower), std::abs(u.upper));
}

}  // namespace

int run_fit(const FitArgs& args) {
  const auto t0 = Clock::now();
  const Campaign campaign = read_campaign(args.campaign);
  const FitSpec spec = read_fit_spec(campaign);
  std::vector<std::unique_ptr<FitCase>> cases;
  for (const auto& test : fit_tests(campaign))
    cases.push_back(std::make_unique<FitCase>(test, campaign, spec));
  auto say = [&](const std::string& line) {
    if (!args.quiet) std::fprintf(stderr, "fit: %s\n", line.c_str());
  };

  // The unknowns: the law's free parameters, then each test's nuisances.
  std::vector<Unknown> unknowns;
  for (std::size_t i = 0; i < spec.free.size(); ++i) {
    const auto& f = spec.free[i];
    unknowns.push_back(
        {f.name, i, -1, "", f.lower, f.upper, f.start, law_parameter_dimension(f.name)});
  }
  std::vector<std::string> warnings;
  for (std::size_t k = 0; k < cases.size(); ++k)
    for (const NuisanceSpec& n : spec.nuisance) {
      Unknown u;
      u.name = cases[k]->name() + ":" + n.name;
      u.test = static_cast<int>(k);
      u.nuisance = n.name;
      const Nuisance& s = cases[k]->start();
      u.start = n.name == "striker_velocity" ? s.striker_velocity_m_s
                : n.name == "rise_time"      ? s.rise_time_s
                                             : s.time_shift_s;
      u.dimension = n.name == "striker_velocity" ? Dimension::kVelocity : Dimension::kTime;
      if (n.relative) {
        u.lower = u.start * (1 - *n.relative), u.upper = u.start * (1 + *n.relative);
        if (!(u.upper > u.lower))
          throw input_error(campaign.display, n.json_path, "\"" + n.name + "\"",
                            "a relative range needs a nonzero start (test " + cases[k]->name() +
                                " starts at 0): give absolute bounds");
      } else {
        std::tie(u.lower, u.upper) = *n.bounds;
        const double clamped = std::clamp(u.start, u.lower, u.upper);
        if (clamped != u.start)
          warnings.push_back(u.name + ": the start " + JsonValue::format(u.start, u.dimension) +
                             " lies outside the bounds; started at " +
                             JsonValue::format(clamped, u.dimension));
        u.start = clamped;
      }
      unknowns.push_back(u);
    }
  for (const auto& c : cases)
    warnings.insert(warnings.end(), c->warnings().begin(), c->warnings().end());

  std::vector<std::filesystem::path> inputs = {campaign.file, spec.material_file};
  for (const auto& c : cases)
    for (const auto& f : scene_inputs(c->scene())) inputs.push_back(f);
  // Every input checked: from here on results are written (never into a folder that holds one).
  OutputFolder out(args.output, "fit", inputs);
  const int threads = resolve_threads(args.threads);
  say("campaign " + campaign.display + ": " + std::to_string(cases.size()) + " test(s), " +
      std::to_string(unknowns.size()) + " unknown(s), " + std::to_string(threads) + " thread(s)");

  // Current values of everything, updated by each stage.
  std::vector<double> current(unknowns.size());
  for (std::size_t i = 0; i < unknowns.size(); ++i) current[i] = unknowns[i].start;
  auto law_values = [&](const std::vector<double>& v) {
    return std::vector<double>(v.begin(), v.begin() + static_cast<long>(spec.free.size()));
  };
  auto nuisance_of = [&](std::size_t k, const std::vector<double>& v) {
    Nuisance n = cases[k]->start();
    for (std::size_t i = 0; i < unknowns.size(); ++i)
      if (unknowns[i].test == static_cast<int>(k)) {
        if (unknowns[i].nuisance == "striker_velocity") n.striker_velocity_m_s = v[i];
        if (unknowns[i].nuisance == "rise_time") n.rise_time_s = v[i];
        if (unknowns[i].nuisance == "time_shift") n.time_shift_s = v[i];
      }
    return n;
  };
  auto simulate_all = [&](const std::vector<double>& v) {
    std::vector<Overlay> o(cases.size());
    const MaterialSpec law = law_with(spec, law_values(v));
    run_parallel(cases.size(), threads,
                 [&](std::size_t k) { o[k] = cases[k]->simulate(law, nuisance_of(k, v)); });
    return o;
  };

  // Start: the windows and NRMSE before.
  const std::vector<Overlay> before = simulate_all(current);
  for (std::size_t k = 0; k < cases.size(); ++k) cases[k]->set_windows(before[k]);
  long simulations = static_cast<long>(cases.size());

  std::vector<StageReport> stages;
  std::vector<double> after_curve;  // law values after the curve stage
  const LsOptions base_options{
      threads, args.relative_step, args.max_iterations, spec.loss, 0.02, [&](const std::string& l) {
        say(l);
      }};
  for (FitStage stage : spec.stages) {
    const auto ts = Clock::now();
    const double cpu_start = cpu_seconds();
    StageReport report;
    report.stage = stage;
    std::vector<LsParameter> params;
    std::vector<LsGroup> groups;
    if (stage == FitStage::kCurve) {
      if (spec.free.empty() || !law_flow_stress(spec.material, 0.1, 1000, 293)) {
        warnings.push_back("stage curve skipped: " +
                           std::string(spec.free.empty() ? "no law parameter is free"
                                                         : "the law has no flow stress to fit"));
        continue;
      }
      for (std::size_t i = 0; i < spec.free.size(); ++i) report.unknowns.push_back(i);
      for (std::size_t k = 0; k < cases.size(); ++k) {
        const auto& pts = cases[k]->curve();
        if (pts.empty()) {
          warnings.push_back(
              cases[k]->name() +
              ": no processed sample after equilibrium; left out of the curve stage");
          continue;
        }
        double peak = 0;
        for (const auto& p : pts) peak = std::max(peak, std::abs(p.stress_Pa));
        const double c = std::sqrt(cases[k]->weight() / static_cast<double>(pts.size()));
        LsGroup g;
        for (std::size_t i = 0; i < spec.free.size(); ++i) g.parameters.push_back(i);
        g.loss_scale.assign(pts.size(), c);
        g.residuals = [&spec, &pts, c, peak](const std::vector<double>& theta) {
          const MaterialSpec law = law_with(spec, theta);
          std::vector<double> r;
          r.reserve(pts.size());
          for (const auto& p : pts)
            r.push_back(
                c *
                (*law_flow_stress(law, p.plastic_strain, p.strain_rate_1_s, p.temperature_K) -
                 p.stress_Pa) /
                peak);
          return r;
        };
        groups.push_back(std::move(g));
      }
      if (groups.empty()) {
        warnings.push_back("stage curve skipped: no test has processed samples after equilibrium");
        continue;
      }
    } else {
      for (std::size_t i = 0; i < unknowns.size(); ++i) report.unknowns.push_back(i);
      for (std::size_t k = 0; k < cases.size(); ++k) {
        LsGroup g;
        for (std::size_t i = 0; i < unknowns.size(); ++i)
          if (unknowns[i].test < 0 || unknowns[i].test == static_cast<int>(k))
            g.parameters.push_back(i);
        g.loss_scale = cases[k]->residual_scales();
        g.clock_sd_s = cases[k]->clock_sd_s();
        g.clock_sensitivity = [&, k](const std::vector<double>& theta) {
          return cases[k]->clock_sensitivity(
              cases[k]->simulate(law_with(spec, law_values(theta)), nuisance_of(k, theta)));
        };
        g.residuals = [&, k](const std::vector<double>& theta) {
          return cases[k]->residuals(
              cases[k]->simulate(law_with(spec, law_values(theta)), nuisance_of(k, theta)));
        };
        groups.push_back(std::move(g));
      }
    }
    if (stage == FitStage::kSignals && !after_curve.empty()) {
      // The curve stage only proposes a start: the signals stage starts from it or from the
      // material file's values, whichever reproduces the signals better.
      auto cost_at = [&](const std::vector<double>& v) {
        std::vector<double> cost(cases.size());
        const MaterialSpec law = law_with(spec, law_values(v));
        run_parallel(cases.size(), threads, [&](std::size_t k) {
          for (double r : cases[k]->residuals(cases[k]->simulate(law, nuisance_of(k, v))))
            cost[k] += 0.5 * r * r;
        });
        double sum = 0;
        for (double c : cost) sum += c;
        return sum;
      };
      std::vector<double> file_start = current;
      for (std::size_t i = 0; i < spec.free.size(); ++i) file_start[i] = unknowns[i].start;
      const double from_curve = cost_at(current), from_file = cost_at(file_start);
      simulations += 2 * static_cast<long>(cases.size());
      if (from_file < from_curve) {
        current = file_start;
        warnings.push_back(
            "stage signals started from the material file's values: they fit the "
            "signals better (cost " +
            format_number(from_file) +
            ") than the curve "
            "stage's (" +
            format_number(from_curve) + ")");
      }
      say("signals cost at the curve stage's values " + format_number(from_curve) +
          ", at the material file's " + format_number(from_file));
    }
    for (std::size_t i : report.unknowns) {
      const Unknown& u = unknowns[i];
      params.push_back({u.name, current[i], u.lower, u.upper, scale_of(u)});
    }
    say("stage " + to_string(stage) + ": " + std::to_string(params.size()) + " parameter(s)");
    LsOptions options = base_options;
    if (stage == FitStage::kCurve) {
      options.relative_step = kCurveRelativeStep;
      options.max_iterations = std::max(args.max_iterations, kCurveIterations);
    }
    report.result = solve_least_squares(params, groups, options);
    for (std::size_t j = 0; j < report.unknowns.size(); ++j)
      current[report.unknowns[j]] = report.result.value[j];
    report.wall_time_s = seconds_since(ts);
    report.cpu_time_s = cpu_seconds() - cpu_start;
    if (stage == FitStage::kSignals) report.simulations = report.result.evaluations;
    simulations += report.simulations;
    if (stage == FitStage::kCurve) after_curve = law_values(current);
    std::string line = "stage " + to_string(stage) + " done: cost " +
                       format_number(report.result.cost_start) + " -> " +
                       format_number(report.result.cost) + ", " +
                       std::to_string(report.result.evaluations) + " evaluations, " +
                       format_number(report.wall_time_s) + " s (processor " +
                       format_number(report.cpu_time_s) + " s);";
    for (std::size_t j = 0; j < params.size(); ++j)
      line += " " + params[j].name + " " +
              JsonValue::format(report.result.value[j], unknowns[report.unknowns[j]].dimension);
    say(line);
    for (const auto& w : report.result.warnings)
      warnings.push_back("stage " + to_string(stage) + ": " + w);
    stages.push_back(std::move(report));
  }

  const std::vector<Overlay> after = simulate_all(current);
  simulations += static_cast<long>(cases.size());

  // Identifiability, from the last stage run.
  const StageReport* last = stages.empty() ? nullptr : &stages.back();
  if (last) {
    const auto& r = last->result;
    const auto& idx = last->unknowns;
    for (std::size_t a = 0; a < idx.size(); ++a) {
      const Unknown& u = unknowns[idx[a]];
      if (!r.std_error.empty() && r.std_error[a] > std::abs(r.value[a]))
        warnings.push_back(u.name + " is not identifiable: its standard error " +
                           JsonValue::format(r.std_error[a], u.dimension) + " exceeds its value " +
                           JsonValue::format(r.value[a], u.dimension));
      for (std::size_t b = a + 1; b < idx.size(); ++b)
        if (!r.std_error.empty() &&
            std::abs(r.correlation(static_cast<long>(a), static_cast<long>(b))) > kCorrelationLimit)
          warnings.push_back(
              u.name + " and " + unknowns[idx[b]].name +
              " are not separately identifiable: correlation " +
              format_number(r.correlation(static_cast<long>(a), static_cast<long>(b))));
      const double span = u.upper - u.lower;
      if (std::abs(r.value[a] - u.lower) < 1e-6 * span ||
          std::abs(u.upper - r.value[a]) < 1e-6 * span)
        warnings.push_back(u.name + " ends at a bound (" +
                           JsonValue::format(r.value[a], u.dimension) +
                           "): widen the bounds or fix it");
      if (a < r.step_check.size() && r.step_check[a] > kStepCheckLimit)
        warnings.push_back(u.name + ": the Jacobian changes by " + format_number(r.step_check[a]) +
                           " of itself when the step is halved (round-off or a kink)");
    }
  }
  for (const auto& f : spec.free)
    if (f.name == "C") {
      double lo = 0, hi = 0;
      for (const auto& c : cases) {
        if (c->curve().empty()) continue;
        std::vector<double> rates;
        for (const auto& p : c->curve()) rates.push_back(p.strain_rate_1_s);
        const double rate = median(std::move(rates));
        lo = lo == 0 ? rate : std::min(lo, rate);
        hi = std::max(hi, rate);
      }
      if (!(lo > 0) || hi / lo < kRateRatioForC)
        warnings.push_back("C is not identifiable: the tests' strain rates span only " +
                           (lo > 0 ? format_number(hi / lo) + "x" : std::string("(none)")) + " (" +
                           std::to_string(cases.size()) +
                           " test(s)); the rate term needs at least two well-separated rates");
    }

  // fit.json: the starting material file with the fitted values.
  nlohmann::json material = spec.material_document;
  const auto final_law = law_values(current);
  for (std::size_t i = 0; i < spec.free.size(); ++i)
    set_law_parameter(material, spec.free[i].name, final_law[i]);
  std::string tests;
  for (const auto& c : cases) tests += (tests.empty() ? "" : ", ") + c->name();
  std::string stage_names;
  for (const auto& s : stages)
    stage_names += (stage_names.empty() ? "" : " then ") + to_string(s.stage);
  material["source"] = "shpb " + std::string(kVersion) + " fit of campaign " + campaign.display +
                       " (tests: " + tests + "; stages: " + stage_names + "), started from " +
                       spec.material_display +
                       (spec.material.source.empty() ? "" : " (" + spec.material.source + ")");
  if (material.contains("name"))
    material["name"] = material["name"].get<std::string>() + " (fitted)";
  write_text_file(out.file("fit.json"), material.dump(2) + "\n");

  // summary.json
  nlohmann::json s;
  s["campaign"] = campaign.display;
  s["material"] = spec.material_display;
  s["model"] = std::string(to_string(spec.material.model));
  s["loss"] = to_string(spec.loss);
  s["threads"] = threads;
  s["relative_step"] = args.relative_step;
  nlohmann::json parameters = nlohmann::json::object();
  std::vector<std::string> order;
  for (std::size_t i = 0; i < unknowns.size(); ++i) {
    const Unknown& u = unknowns[i];
    nlohmann::json p = {{"value", current[i]},
                        {"start", u.start},
                        {"bounds", {u.lower, u.upper}},
                        {"unit", std::string(si_unit(u.dimension))},
                        {"std_error", nullptr}};
    if (last)
      for (std::size_t j = 0; j < last->unknowns.size(); ++j)
        if (last->unknowns[j] == i && !last->result.std_error.empty())
          p["std_error"] = last->result.std_error[j];
    if (u.law < spec.free.size() && u.test < 0 && !after_curve.empty())
      p["after_curve"] = after_curve[u.law];
    parameters[u.name] = p;
  }
  s["parameters"] = parameters;
  nlohmann::json corr = nlohmann::json::array();
  if (last && !last->result.std_error.empty()) {
    for (std::size_t a = 0; a < last->unknowns.size(); ++a) {
      order.push_back(unknowns[last->unknowns[a]].name);
      nlohmann::json row = nlohmann::json::array();
      for (std::size_t b = 0; b < last->unknowns.size(); ++b)
        row.push_back(last->result.correlation(static_cast<long>(a), static_cast<long>(b)));
      corr.push_back(row);
    }
  }
  s["correlation"] = {{"parameters", order}, {"matrix", corr}};
  nlohmann::json stage_json = nlohmann::json::array();
  double signals_time = 0, signals_cpu = 0;
  long signal_simulations = 0;
  for (const auto& st : stages) {
    nlohmann::json j = st;
    nlohmann::json values = nlohmann::json::object(), check = nlohmann::json::object();
    for (std::size_t a = 0; a < st.unknowns.size(); ++a) {
      values[unknowns[st.unknowns[a]].name] = st.result.value[a];
      if (a < st.result.step_check.size())
        check[unknowns[st.unknowns[a]].name] = st.result.step_check[a];
    }
    j["values"] = values;
    j["jacobian_step_check"] = check;
    if (st.stage == FitStage::kSignals) {
      signals_time += st.wall_time_s, signals_cpu += st.cpu_time_s;
      signal_simulations += st.simulations;
    }
    stage_json.push_back(j);
  }
  s["stages"] = stage_json;
  nlohmann::json tests_json = nlohmann::json::array();
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const FitCase& c = *cases[k];
    nlohmann::json t = {{"name", c.name()},
                        {"scene", c.scene().file.string()},
                        {"calibration", calibration_summary(c.scene())},
                        {"weight", c.weight()},
                        {"temperature_K", c.temperature_K()},
                        {"striker_velocity_source", c.velocity_source()},
                        {"curve_points", c.curve().size()}};
    if (!c.curve().empty()) {
      std::vector<double> rates;
      for (const auto& p : c.curve()) rates.push_back(p.strain_rate_1_s);
      std::sort(rates.begin(), rates.end());
      t["strain_rate_1_s"] = rates[rates.size() / 2];
    }
    const auto cb = c.compare(before[k]), ca = c.compare(after[k]);
    for (std::size_t i = 0; i < cb.size(); ++i) {
      t["nrmse_" + cb[i].pulse + "_before"] = cb[i].nrmse;
      t["nrmse_" + cb[i].pulse + "_after"] = ca[i].nrmse;
    }
    tests_json.push_back(t);
  }
  s["tests"] = tests_json;
  s["evaluations"] = 0;
  long evaluations = 0;
  for (const auto& st : stages) evaluations += st.result.evaluations;
  s["evaluations"] = evaluations;
  s["simulations"] = simulations;
  s["simulations_per_second"] = signals_time > 0 ? signal_simulations / signals_time : 0.0;
  s["simulations_per_cpu_second"] = signals_cpu > 0 ? signal_simulations / signals_cpu : 0.0;
  s["wall_time_s"] = seconds_since(t0);
  s["cpu_time_s"] = cpu_seconds();
  s["warnings"] = warnings;
  s["version"] = kVersion;

  // curves.csv: the processed samples and the law at the start, after curve, at the end.
  {
    const MaterialSpec law0 = spec.material,
                       law1 = after_curve.empty() ? law0 : law_with(spec, after_curve),
                       law2 = law_with(spec, final_law);
    CsvWriter w(out.file("curves.csv"), {"test", "time_s", "true_strain", "true_plastic_strain",
                                         "strain_rate_1_s", "temperature_K", "stress_measured_Pa",
                                         "stress_start_Pa", "stress_curve_Pa", "stress_fitted_Pa"});
    auto flow = [](const MaterialSpec& m, const CurvePoint& p) {
      return law_flow_stress(m, p.plastic_strain, p.strain_rate_1_s, p.temperature_K).value_or(0.0);
    };
    for (const auto& c : cases)
      for (const auto& p : c->curve()) {
        const std::vector<double> v = {p.time_s,          p.true_strain,   p.plastic_strain,
                                       p.strain_rate_1_s, p.temperature_K, p.stress_Pa,
                                       flow(law0, p),     flow(law1, p),   flow(law2, p)};
        w.row(c->name(), 1, v);
      }
    w.close();
  }
  // signals.csv: measured, start and fitted strains in each compared window.
  {
    CsvWriter w(out.file("signals.csv"), {"test", "gauge", "pulse", "time_s", "measured_strain",
                                          "start_strain", "fitted_strain"});
    for (std::size_t k = 0; k < cases.size(); ++k) {
      const auto& m = cases[k]->measured();
      for (const auto& p : cases[k]->windows()) {
        const auto& meas = p.transmitted ? m.transmitted : m.incident;
        const auto& b = p.transmitted ? before[k].transmitted : before[k].incident;
        const auto& a = p.transmitted ? after[k].transmitted : after[k].incident;
        const std::string key = cases[k]->name() + "," + p.gauge + "," + p.name;
        for (std::size_t i = p.begin; i < p.end; ++i) {
          const std::vector<double> v = {m.time_s[i], meas[i], b[i], a[i]};
          w.row(key, 3, v);
        }
      }
    }
    w.close();
  }
  write_text_file(out.file("summary.json"), s.dump(2) + "\n");
  out.commit();

  if (!args.quiet) {
    for (const auto& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    for (std::size_t k = 0; k < cases.size(); ++k) {
      const auto cb = cases[k]->compare(before[k]), ca = cases[k]->compare(after[k]);
      for (std::size_t i = 0; i < cb.size(); ++i)
        std::fprintf(stderr, "%-16s %-12s NRMSE %.3f -> %.3f\n", cases[k]->name().c_str(),
                     cb[i].pulse.c_str(), cb[i].nrmse, ca[i].nrmse);
    }
    std::fprintf(stderr, "fit: %ld simulations, %.1f s (processor %.1f s); wrote %s\n", simulations,
                 seconds_since(t0), cpu_seconds(), out.final_path().string().c_str());
  }
  return 0;
}

}  // namespace shpb
