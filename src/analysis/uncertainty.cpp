#include "analysis/uncertainty.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <optional>
#include <random>
#include <set>
#include <stdexcept>

#include "analysis/message_text.hpp"
#include "analysis/pulse_window.hpp"
#include "analysis/test_processing.hpp"
#include "analysis/uncertainty_inputs.hpp"
#include "core/csv_writer.hpp"  // format_double
#include "core/error.hpp"
#include "core/interrupt.hpp"
#include "core/options_check.hpp"
#include "core/parallel_runner.hpp"
#include "dispersion/real_fft.hpp"
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

// A gauge's record kept where it stands above its own noise (docs/methods.md §10): a record of n
// samples carrying white noise of σ has, in every bin of its (unnormalised) spectrum, a power
// |X|² of mean n·σ², exponentially distributed, so that of B bins the largest noise bin reaches
// about n·σ²·ln B. The bins whose power exceeds that are kept, the others (noise, or signal below
// it) removed: a hard Wiener-like mask read off the record itself, whatever its bar, its pulse or
// its sampling. The line through the first and last samples is taken out before the transform and
// put back after (no step where the padded record wraps round). The record as read for a record
// without noise (σ = 0) or of fewer than two samples.
std::vector<double> above_noise(const std::vector<double>& x, double sigma) {
  if (!(sigma > 0) || x.size() < 2) return x;
  const std::size_t n = x.size();
  const double slope = (x.back() - x.front()) / static_cast<double>(n - 1);
  RealFft fft(fast_fft_size(n));
  auto y = fft.samples();
  std::fill(y.begin(), y.end(), 0.0);
  for (std::size_t i = 0; i < n; ++i) y[i] = x[i] - x.front() - slope * static_cast<double>(i);
  fft.forward();
  auto spectrum = fft.spectrum();
  const double floor = static_cast<double>(n) * sigma * sigma;
  const double largest_noise = floor * std::log(static_cast<double>(spectrum.size()));
  for (auto& bin : spectrum)
    if (!(std::norm(bin) > largest_noise)) bin = 0;
  fft.inverse();
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = y[i] + x.front() + slope * static_cast<double>(i);
  return out;
}

// The σ of each gauge's rest (estimate_baseline, the rule of the signal checks: 1.4826 MAD of
// white Gaussian noise) for the gauges the reduction reads, 0 for the others: the noise floor of
// the record's estimate and, with measurement.uncertainty.record_noise, each draw's noise.
std::vector<double> rest_noise_sd(const GaugeSignals& signals, const KolskySetup& setup) {
  std::vector<double> sd(signals.gauges.size(), 0.0);
  for (std::size_t g = 0; g < signals.gauges.size(); ++g)
    if (signals.gauges[g] == setup.incident_gauge || signals.gauges[g] == setup.transmitted_gauge)
      sd[g] = estimate_baseline(signals.strain[g]).noise;
  return sd;
}

// The record the draws move (docs/methods.md §10): each gauge kept above its noise (above_noise,
// with the σ of its rest: rest_noise_sd; a gauge of σ 0 as read).
GaugeSignals record_estimate(const GaugeSignals& signals, const std::vector<double>& rest_sd) {
  GaugeSignals out = signals;
  for (std::size_t g = 0; g < signals.gauges.size(); ++g)
    out.strain[g] = above_noise(signals.strain[g], rest_sd[g]);
  return out;
}

// The input the record noise is listed as (its share: what the scalar inputs leave, figure_
// statistics): one σ of each gauge's own noise, the σs named.
std::optional<UncertainInput> record_noise_input(const GaugeSignals& signals,
                                                 const std::vector<double>& sd) {
  std::string name;
  for (std::size_t g = 0; g < sd.size(); ++g)
    if (sd[g] > 0)
      name += (name.empty() ? "" : ", ") + signals.gauges[g] + " σ " + fmt("%.2g", sd[g]);
  if (name.empty()) return std::nullopt;
  return UncertainInput{"record noise (white; " + name + ")",
                        "measurement.uncertainty.record_noise", 0.0, 1.0, ""};
}

// Draw d's noise generator: its own seed, mixed from the run's (splitmix64, Steele et al. 2014),
// so that a draw's noise depends neither on the thread nor on the other draws.
NormalDraws noise_draws(std::uint64_t seed, std::size_t d) {
  std::uint64_t x = seed + 0x9e3779b97f4a7c15ULL * (static_cast<std::uint64_t>(d) + 1);
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return NormalDraws(x ^ (x >> 31));
}

// What every draw shares: the nominal test, the inputs and their standard normal draws (z, k a
// draw), the record's estimate the draws move (above_noise), the residual every draw adds back
// (the nominal reduction's curve and figures less the estimate's: the record's noise where the
// nominal reading put it), each gauge's record noise σ and the noise seed, the nominal strains the
// curve is read at (first `rows`) and the headline figures.
struct DrawContext {
  const Scene& scene;
  const MeasurementSpec& m;
  const GaugeSignals& estimate;
  const ProcessingOptions& options;
  const std::vector<Input>& inputs;
  const std::vector<double>& z;
  const std::vector<std::vector<std::size_t>>& channels_of;
  const std::vector<double>& noise_sd;
  std::uint64_t seed;
  const std::vector<double>& nominal_strain;
  std::size_t rows;
  bool one_wave;
  bool noisy;  // a record noise drawn
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

// Each gauge's estimate (above_noise) with draw d's noise, scaled by the mean factor of its
// channels (the noise is the recorded signal's, in the channel's volts).
void scale_strains(const DrawContext& ctx, std::size_t d, const DrawState& state,
                   GaugeSignals& scaled) {
  const GaugeSignals& signals = ctx.estimate;
  NormalDraws noise = noise_draws(ctx.seed, d);
  for (std::size_t g = 0; g < signals.gauges.size(); ++g) {
    const auto& channels = ctx.channels_of[g];
    double f = 0;
    for (std::size_t c : channels) f += state.channel_factor[c];
    f = channels.empty() ? 1.0 : f / static_cast<double>(channels.size());
    const auto& from = signals.strain[g];
    auto& to = scaled.strain[g];
    const double sd = ctx.noise_sd[g];
    if (sd > 0)
      for (std::size_t i = 0; i < from.size(); ++i) to[i] = f * (from[i] + sd * noise());
    else
      for (std::size_t i = 0; i < from.size(); ++i) to[i] = f * from[i];
  }
}

// A reduction's curve read at the nominal strains (where each is first reached) and its figures.
// With the record noise drawn, at the sample nearest each strain (curve_at_strains).
DrawResult read_reduction(const ProcessingResult& r, bool one_wave, bool noisy,
                          const std::vector<double>& nominal_strain, std::size_t rows,
                          const std::vector<FigureSpec>& figures) {
  DrawResult res;
  CurveAtStrains at = curve_at_strains(r, one_wave, nominal_strain, rows, noisy);
  res.stress3 = std::move(at.stress3);
  res.stress1 = std::move(at.stress1);
  res.rate = std::move(at.rate);
  for (const FigureSpec& f : figures) res.figures.push_back(f.of(r));
  res.ok = true;
  return res;
}

// to += add, element by element, where add is finite (the residual where the estimate's reduction
// read a value; elsewhere none is added).
void add_finite(std::vector<double>& to, const std::vector<double>& add) {
  for (std::size_t i = 0; i < std::min(to.size(), add.size()); ++i)
    if (std::isfinite(add[i])) to[i] += add[i];
}

// Draw d reduced again, the residual added back; its curve read at the nominal strains and its
// figures. A failed reduction or a non-finite value fails the draw with the reason.
DrawResult reduce_draw(const DrawContext& ctx, const DrawResult& residual, std::size_t d,
                       DispersionTableCache& tables, FftPlans& plans, GaugeSignals& scaled) {
  DrawResult res;
  try {
    DrawState state = perturbed_state(ctx, d);
    state.options.tables = &tables;
    state.options.plans = &plans;
    scale_strains(ctx, d, state, scaled);
    const KolskySetup k_draw = resolve_setup(state.scene, ctx.estimate.gauges);
    res = read_reduction(process_test(state.scene, scaled, k_draw, state.options).result,
                         ctx.one_wave, ctx.noisy, ctx.nominal_strain, ctx.rows, ctx.figures);
    add_finite(res.stress3, residual.stress3);
    add_finite(res.stress1, residual.stress1);
    add_finite(res.rate, residual.rate);
    add_finite(res.figures, residual.figures);
  } catch (const Interrupted&) {
    throw;  // a signal stops the draws: not a failed draw
  } catch (const std::exception& e) {
    res = DrawResult{};
    res.failure = e.what();
  }
  return res;
}

// The record split for the draws (docs/methods.md §10): its estimate (above_noise), which the draws
// move, and the residual each adds back unmoved, the nominal reading less the estimate's read
// alike (the nominal's own noise where the nominal reading put it). When the estimate's
// reduction fails, the record as read and no residual (the draws then move its noise too).
struct RecordSplit {
  GaugeSignals estimate;
  DrawResult residual;
};
RecordSplit split_record(const Scene& scene, const GaugeSignals& signals, const KolskySetup& setup,
                         const std::vector<double>& rest_sd, const ProcessingOptions& options,
                         const ProcessingResult& nominal, const std::vector<double>& nominal_strain,
                         bool one_wave, bool noisy, const std::vector<FigureSpec>& figures) {
  RecordSplit split{record_estimate(signals, rest_sd), {}};
  const std::size_t rows = nominal.loading_end;
  try {
    const DrawResult smooth =
        read_reduction(process_test(scene, split.estimate, setup, options).result, one_wave, noisy,
                       nominal_strain, rows, figures);
    split.residual = read_reduction(nominal, one_wave, noisy, nominal_strain, rows, figures);
    auto less = [](std::vector<double>& to, const std::vector<double>& from) {
      for (std::size_t i = 0; i < to.size(); ++i) to[i] -= from[i];
    };
    less(split.residual.stress3, smooth.stress3);
    less(split.residual.stress1, smooth.stress1);
    less(split.residual.rate, smooth.rate);
    less(split.residual.figures, smooth.figures);
  } catch (const Interrupted&) {
    throw;
  } catch (const std::exception&) {
    split = {signals, {}};
  }
  return split;
}

// Every draw, spread over the threads (draw d on worker d mod threads); the dispersion tables are
// shared by all, the FFT plans and the scaled signals by one worker's draws.
std::vector<DrawResult> run_draws(const DrawContext& ctx, const DrawResult& residual,
                                  std::size_t n_draws, int thread_option) {
  DispersionTableCache tables;
  std::vector<DrawResult> results(n_draws);
  const int threads =
      std::max(1, std::min<int>(resolve_threads(thread_option),
                                static_cast<int>(std::max<std::size_t>(1, n_draws))));
  run_parallel(static_cast<std::size_t>(threads), threads, [&](std::size_t worker) {
    FftPlans plans;
    GaugeSignals scaled = ctx.estimate;
    for (std::size_t d = worker; d < n_draws; d += static_cast<std::size_t>(threads)) {
      throw_if_interrupted();  // Ctrl-C stops a long Monte Carlo within a draw (milliseconds)
      results[d] = reduce_draw(ctx, residual, d, tables, plans, scaled);
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
  const std::vector<double> rest_sd = rest_noise_sd(signals, setup);
  const std::vector<double> noise_sd = scene.measurement->uncertainty->record_noise
                                           ? rest_sd
                                           : std::vector<double>(rest_sd.size(), 0.0);
  const std::optional<UncertainInput> noise_input = record_noise_input(signals, noise_sd);
  if (noise_input) out.inputs.push_back(*noise_input);

  const std::size_t k = inputs.size(), n_draws = mc.draws;
  const std::vector<double> z = standard_normals(n_draws * k, mc.seed);
  const bool one_wave = options.primary == PrimaryReduction::kOneWave;
  const Curve& nc = nominal.curve;
  const std::vector<double>& nominal_strain = one_wave ? nc.strain_1wave : nc.strain;
  const std::vector<std::vector<std::size_t>> channels_of = channels_of_gauges(m, signals);
  // Each draw reads its peak stress where the nominal did (processing.hpp).
  ProcessingOptions draw_options = options;
  draw_options.peak_in_equilibrium = nominal.peak_in_equilibrium;
  const RecordSplit split =
      split_record(scene, signals, setup, rest_sd, draw_options, nominal, nominal_strain, one_wave,
                   noise_input.has_value(), figures);
  const DrawContext ctx{scene,
                        m,
                        split.estimate,
                        draw_options,
                        inputs,
                        z,
                        channels_of,
                        noise_sd,
                        mc.seed,
                        nominal_strain,
                        nominal.loading_end,
                        one_wave,
                        noise_input.has_value(),
                        figures};
  const std::vector<DrawResult> results = run_draws(ctx, split.residual, n_draws, mc.threads);

  const std::vector<std::size_t> good = good_draws(results, out);
  fill_bands(results, good, nominal.loading_end, out);
  std::vector<double> values(results.size());
  for (std::size_t f = 0; f < figures.size(); ++f) {
    for (std::size_t d : good) values[d] = results[d].figures[f];
    // A figure too few draws give (a strain 2.5 % of them do not reach) is left out, as its band.
    if (auto fu = figure_statistics(figures[f].name, figures[f].unit, figures[f].of(nominal),
                                    values, good, z, k, noise_input.has_value()))
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
           "uncertainty, and (measurement.uncertainty.record_noise) each gauge record's own "
           "noise, white with the standard deviation of its rest, drawn anew; each draw reduces "
           "the record's spectrum where it stands above that noise and adds back the nominal "
           "reduction's residual unmoved; standard uncertainty = standard "
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
