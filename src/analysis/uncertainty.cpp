#include "analysis/uncertainty.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <stdexcept>

#include "analysis/test_processing.hpp"
#include "analysis/uncertainty_inputs.hpp"
#include "core/csv_writer.hpp"  // format_double
#include "core/error.hpp"
#include "core/interrupt.hpp"
#include "core/options_check.hpp"
#include "core/parallel_runner.hpp"
#include "output_schema.hpp"

namespace shpb {
namespace {

// Failed draws are reported by their first few distinct reasons.
constexpr std::size_t kFailureReasons = 3;

// What one draw gives: the curve at the nominal strains and the headline figures (NaN: none).
struct DrawResult {
  bool ok = false;
  std::string failure;
  std::vector<double> stress3, stress1, rate;
  std::vector<double> figures;
};

// The standard normal draws of every input, draw after draw, in one sequence: the result does
// not depend on the thread count.
std::vector<double> standard_normals(std::size_t count, std::uint64_t seed) {
  std::vector<double> z(count);
  NormalDraws normal(seed);
  for (double& v : z) v = normal();
  return z;
}

// Which channels make each gauge (the gauge's strain is their mean).
std::vector<std::vector<std::size_t>> channels_of_gauges(const MeasurementSpec& m,
                                                         const GaugeSignals& signals) {
  std::vector<std::vector<std::size_t>> channels_of(signals.gauges.size());
  for (std::size_t c = 0; c < m.channels.size(); ++c)
    for (std::size_t g = 0; g < signals.gauges.size(); ++g)
      if (m.channels[c].gauge == signals.gauges[g]) channels_of[g].push_back(c);
  return channels_of;
}

// What every draw shares: the nominal test, the inputs and their standard normal draws (z, k a
// draw), the nominal strains the curve is read at (first `rows`) and the headline figures.
struct DrawContext {
  const Scene& scene;
  const MeasurementSpec& m;
  const GaugeSignals& signals;
  const ProcessingOptions& options;
  const std::vector<Input>& inputs;
  const std::vector<double>& z;
  const std::vector<std::vector<std::size_t>>& channels_of;
  const std::vector<double>& nominal_strain;
  std::size_t rows;
  bool one_wave;
  const std::vector<FigureSpec>& figures;
};

// Draw d's perturbed test: its inputs applied in order, a drawn value ≤ 0 of a positive input
// failing the draw.
DrawState perturbed_state(const DrawContext& ctx, std::size_t d) {
  const std::size_t k = ctx.inputs.size();
  DrawState state{ctx.scene, ctx.options, std::vector<double>(ctx.m.channels.size(), 1.0)};
  for (std::size_t i = 0; i < k; ++i) {
    const Input& in = ctx.inputs[i];
    const double x = in.info.nominal + in.info.standard_uncertainty * ctx.z[d * k + i];
    if (in.positive && !(x > 0)) throw std::domain_error(in.info.name + " drawn <= 0");
    in.apply(x, state);
  }
  return state;
}

// Each gauge's strain scaled by the mean factor of its channels.
void scale_strains(const DrawContext& ctx, const DrawState& state, GaugeSignals& scaled) {
  const GaugeSignals& signals = ctx.signals;
  for (std::size_t g = 0; g < signals.gauges.size(); ++g) {
    const auto& channels = ctx.channels_of[g];
    double f = 0;
    for (std::size_t c : channels) f += state.channel_factor[c];
    f = channels.empty() ? 1.0 : f / static_cast<double>(channels.size());
    const auto& from = signals.strain[g];
    auto& to = scaled.strain[g];
    for (std::size_t i = 0; i < from.size(); ++i) to[i] = f * from[i];
  }
}

// Draw d reduced again; its curve read at the nominal strains (where each is first reached) and
// its figures. A failed reduction or a non-finite value fails the draw with the reason.
DrawResult reduce_draw(const DrawContext& ctx, std::size_t d, DispersionTableCache& tables,
                       FftPlans& plans, GaugeSignals& scaled) {
  DrawResult res;
  try {
    DrawState state = perturbed_state(ctx, d);
    state.options.tables = &tables;
    state.options.plans = &plans;
    scale_strains(ctx, state, scaled);
    const KolskySetup k_draw = resolve_setup(state.scene, ctx.signals.gauges);
    const ProcessedTest t = process_test(state.scene, scaled, k_draw, state.options);
    const ProcessingResult& r = t.result;
    CurveAtStrains at = curve_at_strains(r, ctx.one_wave, ctx.nominal_strain, ctx.rows);
    res.stress3 = std::move(at.stress3);
    res.stress1 = std::move(at.stress1);
    res.rate = std::move(at.rate);
    for (const FigureSpec& f : ctx.figures) res.figures.push_back(f.of(r));
    res.ok = true;
  } catch (const Interrupted&) {
    throw;  // a signal stops the draws: not a failed draw
  } catch (const std::exception& e) {
    res = DrawResult{};
    res.failure = e.what();
  }
  return res;
}

// Every draw, spread over the threads (draw d on worker d mod threads); the dispersion tables are
// shared by all, the FFT plans and the scaled signals by one worker's draws.
std::vector<DrawResult> run_draws(const DrawContext& ctx, std::size_t n_draws, int thread_option) {
  DispersionTableCache tables;
  std::vector<DrawResult> results(n_draws);
  const int threads =
      std::max(1, std::min<int>(resolve_threads(thread_option),
                                static_cast<int>(std::max<std::size_t>(1, n_draws))));
  run_parallel(static_cast<std::size_t>(threads), threads, [&](std::size_t worker) {
    FftPlans plans;
    GaugeSignals scaled = ctx.signals;
    for (std::size_t d = worker; d < n_draws; d += static_cast<std::size_t>(threads)) {
      throw_if_interrupted();  // Ctrl-C stops a long Monte Carlo within a draw (milliseconds)
      results[d] = reduce_draw(ctx, d, tables, plans, scaled);
    }
  });
  return results;
}

// The draws that succeeded; the failed ones counted in out with their first distinct reasons.
// Fewer than two good draws give no spread: a numerical error.
std::vector<std::size_t> good_draws(const std::vector<DrawResult>& results,
                                    UncertaintyResult& out) {
  std::vector<std::size_t> good;
  std::set<std::string> reasons;
  for (std::size_t d = 0; d < results.size(); ++d) {
    if (results[d].ok) {
      good.push_back(d);
    } else {
      ++out.failed;
      if (reasons.size() < kFailureReasons && reasons.insert(results[d].failure).second)
        out.failures.push_back(results[d].failure);
    }
  }
  if (good.size() < 2)
    throw NumericalError("process: " + std::to_string(out.failed) + " of " +
                         std::to_string(results.size()) +
                         " Monte Carlo draws of measurement.uncertainty failed" +
                         (out.failures.empty() ? std::string() : ": " + out.failures.front()));
  return good;
}

// The 2.5/50/97.5 % quantiles of the good draws' curves at each of the first `rows` strains.
void fill_bands(const std::vector<DrawResult>& results, const std::vector<std::size_t>& good,
                std::size_t rows, UncertaintyResult& out) {
  auto band = [&](std::vector<double> DrawResult::*field, std::vector<double>(&to)[3]) {
    std::vector<const std::vector<double>*> draws;
    for (std::size_t d : good) draws.push_back(&(results[d].*field));
    quantile_bands(draws, rows, to);
  };
  band(&DrawResult::stress3, out.stress_3wave);
  band(&DrawResult::stress1, out.stress_1wave);
  band(&DrawResult::rate, out.strain_rate);
}

}  // namespace

bool MonteCarloOptions::IsValid(std::string* error) const {
  if (!(draws >= kMinDraws && draws <= kMaxDraws)) {
    *error =
        input_error("--draws", "", std::to_string(draws),
                    "expected " + std::to_string(kMinDraws) + " to " + std::to_string(kMaxDraws))
            .what();
    return false;
  }
  *error = threads_problem(threads);
  return error->empty();
}

void check_uncertainty(const Scene& scene, const GaugeSignals& signals) {
  if (!scene.measurement || !scene.measurement->uncertainty || !scene.specimen) return;
  inputs_of(scene, *scene.measurement, signals, processing_options(scene),
            resolve_setup(scene, signals.gauges));
}

UncertaintyResult propagate_uncertainty(const Scene& scene, const MeasurementSpec& m,
                                        const GaugeSignals& signals,
                                        const ProcessingOptions& options,
                                        const ProcessingResult& nominal,
                                        const MonteCarloOptions& mc) {
  if (!scene.measurement || !scene.measurement->uncertainty || !scene.specimen)
    throw std::logic_error("propagate_uncertainty: the scene has no uncertainty block");
  const KolskySetup setup = resolve_setup(scene, signals.gauges);
  const std::vector<Input> inputs = inputs_of(scene, m, signals, options, setup);
  const std::vector<FigureSpec> figures =
      figure_specs(nominal, options.primary == PrimaryReduction::kOneWave, setup.pulse_shaper);
  UncertaintyResult out;
  out.draws = mc.draws;
  out.seed = mc.seed;
  for (const Input& i : inputs) out.inputs.push_back(i.info);

  const std::size_t k = inputs.size(), n_draws = mc.draws;
  const std::vector<double> z = standard_normals(n_draws * k, mc.seed);
  const bool one_wave = options.primary == PrimaryReduction::kOneWave;
  const Curve& nc = nominal.curve;
  const std::vector<std::vector<std::size_t>> channels_of = channels_of_gauges(m, signals);
  // Each draw reads its peak stress where the nominal did (processing.hpp).
  ProcessingOptions draw_options = options;
  draw_options.peak_in_equilibrium = nominal.peak_in_equilibrium;
  const DrawContext ctx{scene,
                        m,
                        signals,
                        draw_options,
                        inputs,
                        z,
                        channels_of,
                        one_wave ? nc.strain_1wave : nc.strain,
                        nominal.loading_end,
                        one_wave,
                        figures};
  const std::vector<DrawResult> results = run_draws(ctx, n_draws, mc.threads);

  const std::vector<std::size_t> good = good_draws(results, out);
  fill_bands(results, good, nominal.loading_end, out);
  std::vector<double> values(results.size());
  for (std::size_t f = 0; f < figures.size(); ++f) {
    for (std::size_t d : good) values[d] = results[d].figures[f];
    // A figure too few draws give (a strain 2.5 % of them do not reach) is left out, as its band.
    if (auto fu = figure_statistics(figures[f].name, figures[f].unit, figures[f].of(nominal),
                                    values, good, z, k))
      out.figures.push_back(std::move(*fu));
  }
  return out;
}

std::vector<std::pair<const char*, const std::vector<double>*>> uncertainty_band_columns(
    const UncertaintyResult& u) {
  namespace k = schema::curve;  // the column names (src/core/output_schema.json)
  return {{k::stress_3wave_p2_5_Pa, &u.stress_3wave[0]},
          {k::stress_3wave_p50_Pa, &u.stress_3wave[1]},
          {k::stress_3wave_p97_5_Pa, &u.stress_3wave[2]},
          {k::stress_1wave_p2_5_Pa, &u.stress_1wave[0]},
          {k::stress_1wave_p50_Pa, &u.stress_1wave[1]},
          {k::stress_1wave_p97_5_Pa, &u.stress_1wave[2]},
          {k::strain_rate_p2_5_1_s, &u.strain_rate[0]},
          {k::strain_rate_p50_1_s, &u.strain_rate[1]},
          {k::strain_rate_p97_5_1_s, &u.strain_rate[2]}};
}

nlohmann::json uncertainty_summary(const UncertaintyResult& u) {
  nlohmann::json inputs = nlohmann::json::array();
  for (const UncertainInput& i : u.inputs)
    inputs.push_back({{"name", i.name},
                      {"key", i.key},
                      {"nominal", i.nominal},
                      {"standard_uncertainty", i.standard_uncertainty},
                      {"unit", i.unit}});
  nlohmann::json figures = nlohmann::json::object();
  for (const FigureUncertainty& f : u.figures) {
    nlohmann::json shares = nlohmann::json::array();
    for (const auto& [i, share] : f.shares)
      shares.push_back({{"input", u.inputs[i].name}, {"share", share}});
    figures[f.name] = {{"nominal", f.nominal},
                       {"median", f.median},
                       {"standard_uncertainty", f.standard_uncertainty},
                       {"interval_95", {f.low95, f.high95}},
                       {"unit", f.unit},
                       {"draws", f.draws},
                       {"contributions", shares}};
  }
  return {{"method",
           "Monte Carlo propagation (GUM Supplement 1, JCGM 101:2008): every input of "
           "measurement.uncertainty drawn from a normal distribution with its standard "
           "uncertainty, the test reduced again per draw; standard uncertainty = standard "
           "deviation of the draws, interval_95 = their 2.5 and 97.5 % quantiles; contributions: "
           "each input's share of the variance (squared correlation of the figure with the "
           "input's draws), largest first; curve.csv's band columns: quantiles at each strain"},
          {"draws", u.draws},
          {"seed", u.seed},
          {"failed_draws", u.failed},
          {"failures", u.failures},
          {"inputs", inputs},
          {"figures", figures}};
}

std::string uncertainty_headline(const UncertaintyResult& u) {
  const FigureUncertainty* f = nullptr;
  for (const auto& x : u.figures)
    if (x.name == "flow_stress_Pa_at_strain_0.1") f = &x;
  for (const auto& x : u.figures)
    if (!f && x.name == "peak_stress_Pa") f = &x;
  if (!f) return "";
  char line[400];
  std::snprintf(line, sizeof line,
                "process: uncertainty (%zu draws%s): %s %.4g MPa, 95 %% interval %.4g to %.4g MPa "
                "(standard uncertainty %.3g MPa); largest contributors:",
                u.draws, u.failed ? (", " + std::to_string(u.failed) + " failed").c_str() : "",
                f->name == "peak_stress_Pa" ? "peak stress" : "flow stress at strain 0.1",
                f->nominal / 1e6, f->low95 / 1e6, f->high95 / 1e6, f->standard_uncertainty / 1e6);
  std::string text = line;
  for (std::size_t i = 0; i < std::min<std::size_t>(3, f->shares.size()); ++i) {
    std::snprintf(line, sizeof line, "%s %s %.0f %%", i ? "," : "",
                  u.inputs[f->shares[i].first].name.c_str(), 100 * f->shares[i].second);
    text += line;
  }
  return text;
}

}  // namespace shpb
