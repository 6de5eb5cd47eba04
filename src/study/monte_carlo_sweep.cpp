#include "study/monte_carlo_sweep.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "analysis/monte_carlo.hpp"
#include "analysis/process_scene.hpp"
#include "analysis/test_processing.hpp"
#include "analysis/uncertainty.hpp"
#include "core/checked_write.hpp"
#include "core/closest_match.hpp"
#include "core/csv_writer.hpp"
#include "core/error.hpp"
#include "core/json_document.hpp"
#include "core/json_value.hpp"
#include "model/input_keys.hpp"
#include "model/law_parameters.hpp"
#include "model/scene_validation.hpp"
#include "model/uncertainty_reader.hpp"
#include "output_schema.hpp"
#include "solver/simulation.hpp"
#include "study/json_numbers.hpp"
#include "version.hpp"

namespace shpb {
namespace {

using Json = nlohmann::ordered_json;
constexpr const char* kFriction = "contact.friction";

// A scene value a distribution may set: its nominal value, dimension and setter.
struct Target {
  Dimension dimension = Dimension::kDimensionless;
  std::function<double(const Scene&)> get;
  std::function<void(Scene&, double)> set;
};

// The bar quantities of every bar (geometry, velocity; the material's density, Poisson's ratio
// and law parameters when it has one), and the friction of every interface.
std::vector<std::pair<std::string, Target>> targets(const Scene& scene) {
  std::vector<std::pair<std::string, Target>> t;
  t.push_back({kFriction,
               {Dimension::kDimensionless, [](const Scene& s) { return s.contact.friction; },
                [](Scene& s, double x) {
                  s.contact.friction = x;  // every interface: the overrides too
                  for (auto& o : s.contact.interfaces)
                    if (o.friction) o.friction = x;
                }}});
  for (std::size_t i = 0; i < scene.bars.size(); ++i) {
    const BarSpec& bar = scene.bars[i];
    const std::string p = bar.name + ".";
    t.push_back({p + "velocity",
                 {Dimension::kVelocity, [i](const Scene& s) { return s.bars[i].velocity_m_s; },
                  [i](Scene& s, double x) { s.bars[i].velocity_m_s = x; }}});
    t.push_back({p + "length",
                 {Dimension::kLength, [i](const Scene& s) { return s.bars[i].length_m; },
                  [i](Scene& s, double x) { s.bars[i].length_m = x; }}});
    t.push_back({p + "diameter",
                 {Dimension::kLength, [i](const Scene& s) { return s.bars[i].diameter_m; },
                  [i](Scene& s, double x) { set_bar_diameter(s.bars[i], x); }}});
    if (!bar.has_material) continue;
    t.push_back(
        {p + "density",
         {Dimension::kDensity, [i](const Scene& s) { return s.bars[i].material.density_kg_m3; },
          [i](Scene& s, double x) { s.bars[i].material.density_kg_m3 = x; }}});
    t.push_back({p + "poisson_ratio",
                 {Dimension::kDimensionless,
                  [i](const Scene& s) { return s.bars[i].material.poisson_ratio; },
                  [i](Scene& s, double x) { s.bars[i].material.poisson_ratio = x; }}});
    for (const std::string& name : law_parameter_names(bar.material))
      t.push_back(
          {p + name,
           {law_parameter_dimension(name),
            [i, name](const Scene& s) { return law_parameter(s.bars[i].material, name); },
            [i, name](Scene& s, double x) { set_law_parameter(s.bars[i].material, name, x); }}});
  }
  return t;
}

const Target* find_target(const std::vector<std::pair<std::string, Target>>& all,
                          const std::string& key) {
  for (const auto& [k, t] : all)
    if (k == key) return &t;
  return nullptr;
}

// A drawn value the scene cannot take: of the other sign than its nominal value (a length, a
// modulus, a law parameter), a negative friction, a Poisson's ratio or friction of 0.5 or 1 and
// above. Empty when it can.
std::string drawn_value_problem(const Distribution& d, double x) {
  if (!std::isfinite(x)) return "not finite";
  if (d.nominal > 0 && !(x > 0)) return "not positive";
  if (d.nominal < 0 && !(x < 0)) return "not negative";
  if (d.nominal == 0 && x < 0) return "negative";
  if (d.key.ends_with(".poisson_ratio") && x >= 0.5) return "a Poisson's ratio of 0.5 or more";
  if (d.key == kFriction && x >= 1) return "a friction coefficient of 1 or more";
  return "";
}

std::string column_name(const Distribution& d) {
  std::string unit(si_unit(d.dimension));
  std::replace(unit.begin(), unit.end(), '/', '_');
  return unit.empty() ? d.key : d.key + "_" + unit;
}

Json doubles(const std::vector<double>& v) {
  Json a = Json::array();
  for (double x : v) a.push_back(number(x));
  return a;
}
std::vector<double> doubles_from(const nlohmann::json& j) {
  std::vector<double> v;
  for (const auto& x : j) v.push_back(number(x));
  return v;
}

}  // namespace

std::vector<Distribution> read_distributions(const std::filesystem::path& file,
                                             const Scene& scene) {
  // The scene's reader: a folder, a device or a FIFO (which would block), duplicate keys, depth
  // and size beyond the limits are refused naming the file (core/json_document.hpp).
  const nlohmann::json doc = read_json_object_file(file, file.string());
  const JsonValue root(doc, file.string(), "");
  const auto o = root.object(input_keys::kDistributions);
  if (auto v = o.get("notes")) v->string();
  const JsonValue values = o.require("values", "{\"<bar>.<quantity>\": {\"normal\": ...}, ...}");
  if (!values.is_object() || values.json().empty())
    throw values.error(
        "expected a non-empty object {\"<bar>.<quantity>\": {\"normal\": \"2 %\"}, ...}");
  const auto all = targets(scene);
  std::vector<std::string> keys;
  for (const auto& [k, t] : all) keys.push_back(k);
  std::vector<Distribution> out;
  for (const auto& [key, item] : values.json().items()) {
    const JsonValue v(item, file.string(), json_child_path(values.path(), key));
    const Target* t = find_target(all, key);
    if (!t)
      throw v.error_with_value(json_quoted(key),
                               "no such scene value; " + suggestion_text(key, keys));
    Distribution d;
    d.key = key;
    d.path = v.path();
    d.dimension = t->dimension;
    d.nominal = d.mean = t->get(scene);
    if (!v.is_object() || v.json().size() != 1)
      throw v.error(
          "expected {\"normal\": standard deviation} or {\"uniform\": half-width or "
          "[low, high]}");
    const auto dist = v.object(input_keys::kDistribution);
    // A spread in the value's unit or "%" of the scene's value; > 0.
    auto spread = [&](const JsonValue& s) {
      const StandardUncertainty u = read_standard_uncertainty(s, d.dimension, d.nominal != 0);
      const double x = u.relative ? u.value * std::abs(d.nominal) : u.value;
      if (!(x > 0)) throw s.error("must be > 0 (a spread)");
      return x;
    };
    // A value of one sign keeps it in every draw (drawn_value_problem): a distribution that
    // crosses zero is refused here rather than failing its draws.
    if (auto n = dist.get("normal")) {
      d.kind = DistributionKind::kNormal;
      d.standard_deviation = spread(*n);
      if (d.nominal != 0)
        if (const std::string what =
                sign_keeping_problem(d.nominal, d.standard_deviation, d.dimension);
            !what.empty())
          throw n->error(what);
    } else if (auto u = dist.get("uniform")) {
      d.kind = DistributionKind::kUniform;
      if (u->json().is_array()) {
        const auto range = u->array();
        if (range.size() != 2) throw u->error("expected [low, high] or a half-width");
        d.low = range[0].quantity(d.dimension);
        d.high = range[1].quantity(d.dimension);
        if (!(d.low < d.high)) throw u->error("expected low < high");
        d.mean = (d.low + d.high) / 2;
      } else {
        const double h = spread(*u);
        d.low = d.nominal - h, d.high = d.nominal + h;
      }
      d.standard_deviation = (d.high - d.low) / std::sqrt(12.0);
      if ((d.nominal > 0 && d.low < 0) || (d.nominal < 0 && d.high > 0))
        throw u->error("reaches " + JsonValue::format(d.nominal > 0 ? d.low : d.high, d.dimension) +
                       ": the scene's value " + JsonValue::format(d.nominal, d.dimension) +
                       " must keep its sign in every draw");
    }
    out.push_back(d);
  }
  return out;
}

std::vector<MonteCarloJob> monte_carlo_jobs(const std::vector<Distribution>& distributions,
                                            std::size_t draws, std::uint64_t seed) {
  std::vector<MonteCarloJob> jobs = {{true, {}}};
  NormalDraws random(seed);
  for (std::size_t k = 0; k < draws; ++k) {
    MonteCarloJob j;
    for (const Distribution& d : distributions)
      j.values.push_back(d.kind == DistributionKind::kNormal
                             ? d.mean + d.standard_deviation * random()
                             : d.low + (d.high - d.low) * random.uniform());
    jobs.push_back(j);
  }
  return jobs;
}

MonteCarloJobResult run_monte_carlo_job(const Scene& nominal,
                                        const std::vector<Distribution>& distributions,
                                        const MonteCarloJob& job,
                                        const std::function<bool()>& cancel) {
  MonteCarloJobResult out;
  const auto start = std::chrono::steady_clock::now();
  try {
    Scene scene = nominal;
    if (!job.nominal) {
      const auto all = targets(nominal);
      for (std::size_t i = 0; i < distributions.size(); ++i) {
        const Distribution& d = distributions[i];
        if (const std::string p = drawn_value_problem(d, job.values[i]); !p.empty())
          throw std::domain_error(d.key + " drawn " +
                                  JsonValue::format(job.values[i], d.dimension) + ": " + p);
        find_target(all, d.key)->set(scene, job.values[i]);
      }
      (void)validate_scene(scene);
    }
    SimulationOptions options;
    options.record_field = false;
    options.cancel = cancel;
    SimulationResult r = simulate(scene, options);
    if (!r.stable) throw std::domain_error("unstable: " + r.failure);
    out.gauges = std::move(r.gauges);
    out.ok = true;
    if (scene.specimen) {
      try {
        const KolskySetup setup = resolve_setup(scene, out.gauges.columns);
        const GaugeSignals signals =
            simulated_signals(out.gauges, {setup.incident_gauge, setup.transmitted_gauge});
        ProcessingOptions po = processing_options(scene);
        use_simulated_signals(po);
        const ProcessingResult p = process_test(scene, signals, setup, po).result;
        if (const std::string f = reduction_failure(p); !f.empty()) throw std::domain_error(f);
        const bool one_wave = po.primary == PrimaryReduction::kOneWave;
        const Curve& c = p.curve;
        const std::size_t n = p.loading_end;
        const auto& x = one_wave ? c.strain_1wave : c.strain;
        const auto& rate = one_wave ? c.strain_rate_1wave_1_s : c.strain_rate_1_s;
        out.strain.assign(x.begin(), x.begin() + static_cast<long>(n));
        out.stress3.assign(c.stress_3wave_Pa.begin(),
                           c.stress_3wave_Pa.begin() + static_cast<long>(n));
        out.stress1.assign(c.stress_1wave_Pa.begin(),
                           c.stress_1wave_Pa.begin() + static_cast<long>(n));
        out.rate.assign(rate.begin(), rate.begin() + static_cast<long>(n));
        for (const FigureSpec& f : figure_specs(p, one_wave, setup.pulse_shaper))
          out.figures.emplace_back(f.name, f.of(p));
        out.reduced = n > 0;
        if (!out.reduced) out.reduction_failure = "no loading in the reduced curve";
      } catch (const Interrupted&) {
        throw;
      } catch (const std::exception& e) {
        out.reduction_failure = e.what();
      }
    }
  } catch (const Interrupted&) {
    throw;
  } catch (const std::exception& e) {
    out = MonteCarloJobResult{};
    out.failure = e.what();
  }
  out.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

nlohmann::ordered_json distribution_json(const Distribution& d) {
  Json j{{"key", d.key},
         {"distribution", d.kind == DistributionKind::kNormal ? "normal" : "uniform"},
         {"unit", std::string(si_unit(d.dimension))},
         {"nominal", d.nominal},
         {"mean", d.mean},
         {"standard_deviation", d.standard_deviation}};
  if (d.kind == DistributionKind::kUniform) j["range"] = {d.low, d.high};
  j["path"] = d.path;
  j["dimension"] = std::string(to_string(d.dimension));
  return j;
}

Distribution distribution_from(const nlohmann::json& j) {
  Distribution d;
  d.key = j.at("key").get<std::string>();
  d.path = j.at("path").get<std::string>();
  const std::string kind = j.at("distribution").get<std::string>();
  if (kind != "normal" && kind != "uniform")
    throw std::invalid_argument("unknown distribution " + kind);
  d.kind = kind == "normal" ? DistributionKind::kNormal : DistributionKind::kUniform;
  d.nominal = j.at("nominal").get<double>();
  d.mean = j.at("mean").get<double>();
  d.standard_deviation = j.at("standard_deviation").get<double>();
  if (d.kind == DistributionKind::kUniform) {
    d.low = j.at("range").at(0).get<double>();
    d.high = j.at("range").at(1).get<double>();
  }
  const std::string dim = j.at("dimension").get<std::string>();
  bool found = false;
  for (int k = 0; k <= static_cast<int>(Dimension::kStiffness); ++k)
    if (to_string(static_cast<Dimension>(k)) == dim) {
      d.dimension = static_cast<Dimension>(k);
      found = true;
    }
  if (!found) throw std::invalid_argument("unknown dimension " + dim);
  return d;
}

nlohmann::ordered_json job_result_json(const MonteCarloJobResult& r) {
  Json j{{"ok", r.ok}, {"failure", r.failure}, {"wall_time_s", r.wall_time_s}};
  if (!r.ok) return j;
  Json values = Json::array();
  for (const auto& column : r.gauges.values) values.push_back(doubles(column));
  j["gauges"] = {{"columns", r.gauges.columns}, {"time_s", r.gauges.time_s}, {"values", values}};
  j["reduced"] = r.reduced;
  j["reduction_failure"] = r.reduction_failure;
  if (!r.reduced) return j;
  j["strain"] = doubles(r.strain);
  j["stress_3wave_Pa"] = doubles(r.stress3);
  j["stress_1wave_Pa"] = doubles(r.stress1);
  j["strain_rate_1_s"] = doubles(r.rate);
  Json figures = Json::array();
  for (const auto& [name, v] : r.figures) figures.push_back({name, number(v)});
  j["figures"] = figures;
  return j;
}

MonteCarloJobResult job_result_from(const nlohmann::json& j) {
  MonteCarloJobResult r;
  r.ok = j.at("ok").get<bool>();
  r.failure = j.at("failure").get<std::string>();
  r.wall_time_s = j.at("wall_time_s").get<double>();
  if (!r.ok) return r;
  const auto& g = j.at("gauges");
  r.gauges.columns = g.at("columns").get<std::vector<std::string>>();
  r.gauges.time_s = g.at("time_s").get<std::vector<double>>();
  for (const auto& column : g.at("values")) {
    r.gauges.values.push_back(doubles_from(column));
    if (r.gauges.values.back().size() != r.gauges.time_s.size())
      throw std::invalid_argument("gauge values and times differ in size");
  }
  if (r.gauges.values.size() != r.gauges.columns.size())
    throw std::invalid_argument("gauge columns and names differ in number");
  r.reduced = j.at("reduced").get<bool>();
  r.reduction_failure = j.at("reduction_failure").get<std::string>();
  if (!r.reduced) return r;
  r.strain = doubles_from(j.at("strain"));
  r.stress3 = doubles_from(j.at("stress_3wave_Pa"));
  r.stress1 = doubles_from(j.at("stress_1wave_Pa"));
  r.rate = doubles_from(j.at("strain_rate_1_s"));
  const std::size_t n = r.strain.size();
  if (n == 0 || r.stress3.size() != n || r.stress1.size() != n || r.rate.size() != n)
    throw std::invalid_argument("curve columns differ in size");
  for (const auto& f : j.at("figures"))
    r.figures.emplace_back(f.at(0).get<std::string>(), number(f.at(1)));
  return r;
}

namespace {

// The quantities of summary.json: each gauge's peak |strain|, then the reduction's figures (those
// of the nominal run); values[q][d] for draw d (NaN where a draw gives none).
struct Quantities {
  std::vector<std::string> names, units;
  std::vector<double> nominal;
  std::vector<std::vector<double>> values;
};

double peak_strain(const TimeSeries& g, std::size_t column) {
  double peak = 0;
  for (double v : g.values[column]) peak = std::max(peak, std::abs(v));
  return peak;
}

Quantities quantities(const std::vector<MonteCarloJobResult>& results) {
  Quantities q;
  const MonteCarloJobResult& n = results[0];
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t g = 0; g < n.gauges.columns.size(); ++g) {
    q.names.push_back(n.gauges.columns[g] + "_peak_strain");
    q.units.push_back("");
    q.nominal.push_back(peak_strain(n.gauges, g));
    std::vector<double> v(results.size() - 1, nan);
    for (std::size_t d = 1; d < results.size(); ++d)
      if (results[d].ok) v[d - 1] = peak_strain(results[d].gauges, g);
    q.values.push_back(v);
  }
  if (!n.reduced) return q;
  for (const auto& [name, value] : n.figures) {
    q.names.push_back(name);
    q.units.push_back(name.ends_with("_Pa")    ? "Pa"
                      : name.ends_with("_1_s") ? "1/s"
                      : name.ends_with("_m_s") ? "m/s"
                                               : "");
    q.nominal.push_back(value);
    std::vector<double> v(results.size() - 1, nan);
    for (std::size_t d = 1; d < results.size(); ++d)
      if (results[d].reduced)
        for (const auto& [dn, dv] : results[d].figures)
          if (dn == name) v[d - 1] = dv;
    q.values.push_back(v);
  }
  return q;
}

void write_draws(const std::vector<Distribution>& distributions,
                 const std::vector<MonteCarloJob>& jobs,
                 const std::vector<MonteCarloJobResult>& results,
                 const std::filesystem::path& file) {
  namespace k = schema::draws;  // the column names (src/core/output_schema.json)
  std::vector<std::string> header = {k::draw};
  for (const Distribution& d : distributions) header.push_back(column_name(d));
  header.insert(header.end(), {k::simulated, k::reduced, k::failure});
  CsvWriter csv(file, header);
  for (std::size_t r = 1; r < jobs.size(); ++r) {
    std::vector<std::string> cells = {std::to_string(r)};
    for (double v : jobs[r].values) cells.push_back(format_double(v));
    const MonteCarloJobResult& x = results[r];
    cells.push_back(x.ok ? "1" : "0");
    cells.push_back(x.reduced ? "1" : "0");
    cells.push_back(x.ok ? x.reduction_failure : x.failure);
    csv.row(cells);
  }
  csv.close();
}

// The gauges' bands at the nominal run's times (up to the shortest run's record).
void write_gauge_bands(const std::vector<MonteCarloJobResult>& results,
                       const std::vector<std::size_t>& good, const std::filesystem::path& file) {
  const TimeSeries& n = results[0].gauges;
  std::size_t rows = n.samples();
  for (std::size_t d : good) rows = std::min(rows, results[d].gauges.samples());
  std::vector<std::string> header = {schema::gauge_bands::time_s};
  std::vector<std::vector<double>> columns;
  for (std::size_t g = 0; g < n.columns.size(); ++g) {
    std::vector<const std::vector<double>*> draws;
    for (std::size_t d : good) draws.push_back(&results[d].gauges.values[g]);
    std::vector<double> band[3];
    quantile_bands(draws, rows, band);
    const std::string& c = n.columns[g];
    header.insert(header.end(), {c, c + "_p2.5", c + "_p50", c + "_p97.5"});
    columns.push_back(n.values[g]);
    for (auto& b : band) columns.push_back(std::move(b));
  }
  CsvWriter csv(file, header);
  for (std::size_t i = 0; i < rows; ++i) {
    std::vector<std::string> cells = {format_double(n.time_s[i])};
    for (const auto& c : columns) cells.push_back(format_double(c[i]));
    csv.row(cells);
  }
  csv.close();
}

// The processed curve's bands at the nominal curve's strains (process's band columns).
void write_curve_bands(const std::vector<MonteCarloJobResult>& results,
                       const std::vector<std::size_t>& reduced, const std::filesystem::path& file) {
  const MonteCarloJobResult& n = results[0];
  const std::size_t rows = n.strain.size();
  std::vector<CurveAtStrains> at;
  for (std::size_t d : reduced)
    at.push_back(curve_at_strains(results[d].strain, results[d].stress3, results[d].stress1,
                                  results[d].rate, results[d].strain.size(), n.strain, rows));
  UncertaintyResult u;
  auto band = [&](std::vector<double> CurveAtStrains::*field, std::vector<double>(&to)[3]) {
    std::vector<const std::vector<double>*> draws;
    for (const auto& a : at) draws.push_back(&(a.*field));
    quantile_bands(draws, rows, to);
  };
  band(&CurveAtStrains::stress3, u.stress_3wave);
  band(&CurveAtStrains::stress1, u.stress_1wave);
  band(&CurveAtStrains::rate, u.strain_rate);
  const auto bands = uncertainty_band_columns(u);
  namespace k = schema::curve_bands;  // the nominal columns, then the bands (as curve.csv's)
  std::vector<std::string> header = {k::strain, k::stress_3wave_Pa, k::stress_1wave_Pa,
                                     k::strain_rate_1_s};
  for (const auto& [name, column] : bands) header.push_back(name);
  CsvWriter csv(file, header);
  for (std::size_t i = 0; i < rows; ++i) {
    std::vector<std::string> cells = {format_double(n.strain[i]), format_double(n.stress3[i]),
                                      format_double(n.stress1[i]), format_double(n.rate[i])};
    for (const auto& [name, column] : bands) cells.push_back(format_field((*column)[i]));
    csv.row(cells);
  }
  csv.close();
}

}  // namespace

std::vector<std::string> write_monte_carlo(
    const Scene& scene, const std::vector<Distribution>& distributions, std::uint64_t seed,
    const std::vector<MonteCarloJob>& jobs, const std::vector<MonteCarloJobResult>& results,
    int threads, double wall_s, const std::filesystem::path& dir) {
  const MonteCarloJobResult& nominal = results.at(0);
  if (!nominal.ok)
    throw NumericalError("study monte-carlo: the nominal scene does not run: " + nominal.failure);
  std::vector<std::size_t> good, reduced;
  std::vector<std::string> failures;
  std::size_t failed = 0;
  std::string first_failure, first_unreduced;  // the first cause of each kind, in draw order
  for (std::size_t d = 1; d < results.size(); ++d) {
    if (results[d].ok) good.push_back(d);
    if (results[d].ok && results[d].reduced && nominal.reduced) reduced.push_back(d);
    const std::string& why = results[d].ok ? results[d].reduction_failure : results[d].failure;
    if (!results[d].ok) ++failed;
    std::string& first = results[d].ok ? first_unreduced : first_failure;
    if (first.empty()) first = why;
    if (!why.empty() && failures.size() < 3 &&
        std::find(failures.begin(), failures.end(), why) == failures.end())
      failures.push_back(why);
  }
  const std::string draws = std::to_string(results.size() - 1);
  // Fewer than two good draws have no spread: the study failed (exit 3), nothing written.
  if (good.size() < 2)
    throw NumericalError("study monte-carlo: " + std::to_string(failed) + " of " + draws +
                         " draws failed" +
                         (first_failure.empty() ? std::string() : ": " + first_failure));
  // Some failed: the bands are over the others, said on stderr as in summary.json.
  std::vector<std::string> warnings;
  if (failed > 0)
    warnings.push_back("study monte-carlo: " + std::to_string(failed) + " of " + draws +
                       " draws failed (summary.json failed_draws), the bands are over the " +
                       std::to_string(good.size()) + " others; the first: " + first_failure);
  if (const std::size_t unreduced = good.size() - reduced.size(); nominal.reduced && unreduced > 0)
    warnings.push_back("study monte-carlo: " + std::to_string(unreduced) + " of " + draws +
                       " draws ran but were not reduced (summary.json unreduced_draws)" +
                       (reduced.size() < 2 ? ", so no curve_bands.csv" : "") +
                       "; the first: " + first_unreduced);
  write_draws(distributions, jobs, results, dir / schema::draws::kFile);
  write_gauge_bands(results, good, dir / schema::gauge_bands::kFile);
  if (reduced.size() >= 2) write_curve_bands(results, reduced, dir / schema::curve_bands::kFile);

  // Each quantity over the draws, with each drawn value's share of its variance.
  const std::size_t k = distributions.size();
  std::vector<double> inputs((results.size() - 1) * k);
  for (std::size_t d = 1; d < jobs.size(); ++d)
    for (std::size_t i = 0; i < k; ++i) inputs[(d - 1) * k + i] = jobs[d].values[i];
  std::vector<std::size_t> from;
  for (std::size_t d : good) from.push_back(d - 1);
  const Quantities q = quantities(results);
  Json figures = Json::object();
  for (std::size_t f = 0; f < q.names.size(); ++f) {
    const FigureUncertainty u =
        figure_statistics(q.names[f], q.units[f], q.nominal[f], q.values[f], from, inputs, k);
    Json shares = Json::array();
    for (const auto& [i, share] : u.shares)
      shares.push_back({{"value", distributions[i].key}, {"share", share}});
    figures[u.name] = {{"nominal", number(u.nominal)},
                       {"median", u.median},
                       {"standard_deviation", u.standard_uncertainty},
                       {"interval_95", {u.low95, u.high95}},
                       {"unit", u.unit},
                       {"draws", u.draws},
                       {"contributions", shares}};
  }
  Json dist = Json::array();
  for (const Distribution& d : distributions) dist.push_back(distribution_json(d));
  Json j;
  j["version"] = kVersion;
  j["scene"] = scene.name;
  j["sweep"] = "monte-carlo";
  j["method"] =
      "Monte Carlo (GUM Supplement 1, JCGM 101:2008): each draw sets the scene's values from "
      "their distributions, is simulated and reduced as process --signals reduces a simulated "
      "test; bands: 2.5/50/97.5 % quantiles over the draws at each time (gauge_bands.csv) and at "
      "each strain of the nominal curve (curve_bands.csv); quantities: standard deviation and "
      "2.5/97.5 % quantiles over the draws; contributions: each drawn value's share of the "
      "variance (squared correlation), largest first";
  j["draws"] = results.size() - 1;
  j["seed"] = seed;
  j["failed_draws"] = failed;
  j["unreduced_draws"] = good.size() - reduced.size();
  j["failures"] = failures;
  j["distributions"] = dist;
  j["curve_bands"] = reduced.size() >= 2;
  if (!nominal.reduced && scene.specimen)
    j["curve_bands_missing_because"] = nominal.reduction_failure;
  j["quantities"] = figures;
  j["threads"] = threads;
  j["wall_time_s"] = wall_s;
  write_text_file(dir / "summary.json", j.dump(2) + "\n");
  return warnings;
}

}  // namespace shpb
