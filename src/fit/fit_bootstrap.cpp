#include "fit/fit_bootstrap.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>

#include "core/error.hpp"
#include "core/json_value.hpp"
#include "core/number_format.hpp"
#include "core/parallel_runner.hpp"

namespace shpb {
namespace {

// Fewer finished refits than this give no bootstrap interval: the spread of 10 draws is itself
// uncertain by ±23 % (1/√(2(N−1))).
constexpr std::size_t kMinRefits = 10;
// Sampling standard deviations of the refits' spread within which it agrees with the linearised
// standard error (about 95 % of bootstraps of a right one agree).
constexpr double kSpreadSamplingSigmas = 2.0;
// Weak identification (docs/methods.md §9, "Intervals"). Not the refits' spread against the
// linearised standard error: correlated (coloured) record noise widens the spread of a parameter
// the data fix well.
//  - the 95 % interval is wider than ±25 % of the value: the data fix the parameter's order of
//    magnitude only (a law table quotes its constants to a few per cent);
constexpr double kWeakRelativeHalfWidth = 0.25;
//  - a tenth of the refits end at a bound: the bounds, not the data, hold the parameter.
constexpr double kAtBoundFraction = 0.1;

// The residuals measured − fitted of one gauge over the test's fitted windows, centred.
std::vector<double> gauge_residuals(const FitCase& c, const Overlay& o, bool transmitted) {
  const MeasuredPulses& m = c.measured();
  std::vector<double> r;
  for (const OverlaidPulse& p : c.fitted_windows()) {
    if (p.transmitted != transmitted) continue;
    const auto& meas = transmitted ? m.transmitted : m.incident;
    const auto& sim = transmitted ? o.transmitted : o.incident;
    // A clipped sample's difference is the cut-off pulse, not noise.
    const ClippedSamples* clipped = clipped_channel(m, transmitted);
    for (std::size_t i = p.begin; i < p.end; ++i)
      if (!clipped || !clipped->at[i]) r.push_back(meas[i] - sim[i]);
  }
  double mean = 0;
  for (double v : r) mean += v / static_cast<double>(r.size());
  for (double& v : r) v -= mean;
  return r;
}

// A test's record as the fitted model makes it, plus a noise draw per gauge.
GaugeSignals synthetic_record(const FitCase& c, const Overlay& fitted,
                              const NoiseModel& incident_noise, const NoiseModel& transmitted_noise,
                              std::mt19937_64& rng) {
  GaugeSignals g = c.signals();
  g.warnings.clear();
  const KolskySetup& setup = c.measured().setup;
  for (std::size_t k = 0; k < g.gauges.size(); ++k) {
    const bool incident = g.gauges[k] == setup.incident_gauge;
    if (!incident && g.gauges[k] != setup.transmitted_gauge) continue;
    const std::vector<double>& sim = incident ? fitted.incident : fitted.transmitted;
    const NoiseModel& noise_model = incident ? incident_noise : transmitted_noise;
    if (sim.size() != g.strain[k].size() || noise_model.innovations.empty())
      throw NumericalError("bootstrap: test " + c.name() + ": no fitted record of gauge " +
                           g.gauges[k]);
    const std::vector<double> noise = draw_noise(noise_model, sim.size(), rng);
    for (std::size_t i = 0; i < sim.size(); ++i) g.strain[k][i] = sim[i] + noise[i];
    // The record's channel clipped as the measured one was, at the same level.
    const ClippedSamples* clipped = clipped_channel(c.measured(), !incident);
    if (clipped)
      for (double& x : g.strain[k]) x = clipped->clip(x);
  }
  return g;
}

}  // namespace

NoiseModel fit_noise_model(const std::vector<double>& r) {
  NoiseModel m;
  const std::size_t n = r.size();
  if (n == 0) return m;
  const std::size_t max_order = std::min(kMaxNoiseOrder, n / 10);
  std::vector<double> gamma(max_order + 1, 0.0);  // biased autocovariances: a stationary fit
  for (std::size_t k = 0; k <= max_order; ++k) {
    for (std::size_t i = k; i < n; ++i) gamma[k] += r[i] * r[i - k];
    gamma[k] /= static_cast<double>(n);
  }
  // Levinson–Durbin: the order-k coefficients from the order k−1 ones.
  std::vector<double> a, best;
  double e = gamma[0];
  double best_aic = e > 0 ? static_cast<double>(n) * std::log(e) : 0.0;
  for (std::size_t k = 1; k <= max_order && e > 0; ++k) {
    double acc = gamma[k];
    for (std::size_t j = 1; j < k; ++j) acc -= a[j - 1] * gamma[k - j];
    const double lambda = acc / e;
    std::vector<double> next(k);
    for (std::size_t j = 1; j < k; ++j) next[j - 1] = a[j - 1] - lambda * a[k - j - 1];
    next[k - 1] = lambda;
    a = std::move(next);
    e *= 1 - lambda * lambda;
    if (!(e > 0)) break;
    const double aic = static_cast<double>(n) * std::log(e) + 2.0 * static_cast<double>(k);
    if (aic < best_aic) best_aic = aic, best = a;
  }
  m.ar = best;
  const std::size_t p = m.ar.size();
  for (std::size_t t = p; t < n; ++t) {
    double v = r[t];
    for (std::size_t j = 1; j <= p; ++j) v -= m.ar[j - 1] * r[t - j];
    m.innovations.push_back(v);
  }
  double mean = 0;
  for (double v : m.innovations) mean += v / static_cast<double>(m.innovations.size());
  for (double& v : m.innovations) v -= mean;
  return m;
}

std::vector<double> draw_noise(const NoiseModel& m, std::size_t n, std::mt19937_64& rng) {
  std::vector<double> x(n, 0.0);
  if (m.innovations.empty()) return x;
  const std::size_t p = m.ar.size(), burn = m.innovations.size() + p;
  std::uniform_int_distribution<std::size_t> pick(0, m.innovations.size() - 1);
  std::vector<double> all(burn + n, 0.0);
  for (std::size_t t = 0; t < all.size(); ++t) {
    double v = m.innovations[pick(rng)];
    for (std::size_t j = 1; j <= std::min(p, t); ++j) v += m.ar[j - 1] * all[t - j];
    all[t] = v;
  }
  std::copy(all.begin() + static_cast<long>(burn), all.end(), x.begin());
  return x;
}

double student_t95(double dof) {
  const double z = kNormalZ95, z2 = z * z, v = dof;
  const double g1 = (z2 + 1) * z / 4;
  const double g2 = ((5 * z2 + 16) * z2 + 3) * z / 96;
  const double g3 = (((3 * z2 + 19) * z2 + 17) * z2 - 15) * z / 384;
  const double g4 = ((((79 * z2 + 776) * z2 + 1482) * z2 - 1920) * z2 - 945) * z / 92160;
  return z + g1 / v + g2 / (v * v) + g3 / (v * v * v) + g4 / (v * v * v * v);
}

void run_bootstrap(FitRun& run, const FitOptions& options) {
  if (run.stages.empty() || options.bootstrap <= 0) return;
  const auto started = std::chrono::steady_clock::now();
  const std::size_t tests = run.cases.size(), draws = static_cast<std::size_t>(options.bootstrap);
  std::vector<NoiseModel> incident(tests), transmitted(tests);
  for (std::size_t k = 0; k < tests; ++k) {
    std::vector<double> in = gauge_residuals(*run.cases[k], run.after[k], false);
    std::vector<double> tr = gauge_residuals(*run.cases[k], run.after[k], true);
    // A gauge without a fitted window borrows the other gauge's residuals.
    if (in.empty()) in = tr;
    if (tr.empty()) tr = in;
    incident[k] = fit_noise_model(in);
    transmitted[k] = fit_noise_model(tr);
  }
  const std::vector<std::size_t>& fitted = run.stages.back().unknowns;
  std::vector<std::vector<double>> estimates(draws);
  std::vector<char> done(draws, 0);
  std::vector<long> simulations(draws, 0);
  FitOptions refit = options;
  refit.threads = 1;
  refit.bootstrap = 0;
  refit.progress = {};
  std::mutex m;
  int finished = 0;
  run_parallel(
      draws, run.threads,
      [&](std::size_t b) {
        std::mt19937_64 rng(options.seed + b);  // draw b's noise: the same on any thread count
        std::vector<GaugeSignals> records;
        try {
          for (std::size_t k = 0; k < tests; ++k)
            records.push_back(
                synthetic_record(*run.cases[k], run.after[k], incident[k], transmitted[k], rng));
          FitRun d = prepare_fit(run, records);
          run_fit(d, refit);
          simulations[b] = d.simulations;
          if (d.stages.empty() || d.stages.back().unknowns != fitted) return;
          for (std::size_t i : fitted) estimates[b].push_back(d.current[i]);
          done[b] = 1;
        } catch (const NumericalError&) {
        } catch (const InputError&) {
        }
      },
      [&](std::size_t n, std::size_t count) {
        const std::lock_guard lock(m);
        finished = static_cast<int>(n);
        if (options.progress && (n % 10 == 0 || n == count))
          options.progress("bootstrap: " + std::to_string(n) + " of " + std::to_string(count) +
                           " refits");
      });
  (void)finished;
  FitBootstrapSummary& s = run.bootstrap;
  s = {};
  s.draws = options.bootstrap;
  s.seed = options.seed;
  for (std::size_t b = 0; b < draws; ++b) {
    s.simulations += simulations[b];
    if (done[b])
      s.estimates.push_back(estimates[b]);
    else
      ++s.failed;
  }
  run.simulations += s.simulations;
  s.wall_time_s = seconds_since(started);
  if (s.failed > 0)
    run.warnings.push_back("bootstrap: " + std::to_string(s.failed) + " of " +
                           std::to_string(s.draws) + " refits failed and are left out");
}

void set_intervals(FitRun& run) {
  run.intervals.assign(run.unknowns.size(), {});
  if (run.stages.empty()) return;
  const FitStageReport& last = run.stages.back();
  const std::vector<std::vector<double>>& est = run.bootstrap.estimates;
  const bool bootstrap = est.size() >= kMinRefits;
  if (run.bootstrap.draws > 0 && !bootstrap)
    run.warnings.push_back("bootstrap: " + std::to_string(est.size()) +
                           " refits finished, fewer than " + std::to_string(kMinRefits) +
                           ": the intervals are the linearised ones");
  for (std::size_t a = 0; a < last.unknowns.size(); ++a) {
    const std::size_t i = last.unknowns[a];
    const FitUnknown& u = run.unknowns[i];
    const double value = run.current[i];
    ParameterInterval& p = run.intervals[i];
    double se = 0;
    if (!last.result.std_error.empty()) {
      se = last.result.std_error[a];
      p.has_linear = true;
      p.linear_lower = value - kNormalZ95 * se, p.linear_upper = value + kNormalZ95 * se;
    }
    if (bootstrap) {
      const auto n = static_cast<double>(est.size());
      double mean = 0, var = 0, at_bound = 0;
      for (const auto& e : est) mean += e[a] / n;
      for (const auto& e : est) {
        var += (e[a] - mean) * (e[a] - mean) / (n - 1);
        at_bound += (shpb::at_bound(e[a], u.lower, u.upper) ? 1.0 : 0.0) / n;
      }
      p.has_bootstrap = true;
      p.bootstrap_sd = std::sqrt(var);
      p.bootstrap_bias = mean - value;
      p.at_bound = at_bound;
      const double half = student_t95(n - 1) * p.bootstrap_sd;
      p.bootstrap_lower = value - p.bootstrap_bias - half;
      p.bootstrap_upper = value - p.bootstrap_bias + half;
    }
    p.known = p.has_linear || p.has_bootstrap;
    if (p.has_linear && p.has_bootstrap) {
      // The linearised error holds when the refits' root-mean-square distance from the value
      // (spread and bias) exceeds it by no more than two sampling standard deviations of a spread
      // estimated from N refits (1/√(2(N−1)) of it each).
      const double n = static_cast<double>(est.size());
      const double rms = std::hypot(p.bootstrap_sd, p.bootstrap_bias);
      const bool holds = rms <= se * (1 + kSpreadSamplingSigmas / std::sqrt(2 * (n - 1)));
      p.method = holds ? "linearised" : "bootstrap";
      p.lower = holds ? p.linear_lower : std::min(p.linear_lower, p.bootstrap_lower);
      p.upper = holds ? p.linear_upper : std::max(p.linear_upper, p.bootstrap_upper);
    } else if (p.known) {
      p.method = p.has_linear ? "linearised" : "bootstrap";
      p.lower = p.has_linear ? p.linear_lower : p.bootstrap_lower;
      p.upper = p.has_linear ? p.linear_upper : p.bootstrap_upper;
    }
    // Within the bounds: the fit looks nowhere else.
    p.lower = std::max(p.lower, u.lower), p.upper = std::min(p.upper, u.upper);
    std::string why;
    if (!p.known)
      why = "no interval (no covariance and no bootstrap)";
    else if (p.at_bound >= kAtBoundFraction)
      why = format_number(100 * p.at_bound) + " % of the bootstrap's refits end at a bound";
    else if (std::max(value - p.lower, p.upper - value) > kWeakRelativeHalfWidth * std::abs(value))
      why = "its 95 % interval [" + JsonValue::format(p.lower, u.dimension) + ", " +
            JsonValue::format(p.upper, u.dimension) + "] reaches beyond ±" +
            format_number(100 * kWeakRelativeHalfWidth) + " % of its value";
    if (!why.empty()) {
      p.weak = true;
      p.weak_reason = why;
      run.warnings.push_back(u.name + " is weakly identified: " + why);
    }
  }
}

}  // namespace shpb
