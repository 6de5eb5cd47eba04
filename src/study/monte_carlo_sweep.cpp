#include "study/monte_carlo_sweep.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "analysis/monte_carlo.hpp"
#include "analysis/process_scene.hpp"
#include "analysis/test_processing.hpp"
#include "core/closest_match.hpp"
#include "core/error.hpp"
#include "core/json_document.hpp"
#include "core/json_numbers.hpp"
#include "core/json_value.hpp"
#include "model/input_keys.hpp"
#include "model/law_parameters.hpp"
#include "model/scene_validation.hpp"
#include "model/uncertainty_reader.hpp"
#include "solver/simulation.hpp"

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

std::vector<Distribution> read_distributions_objects(const std::filesystem::path& file,
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

}  // namespace

// A key refused in one object of the file names the other it belongs to.
std::vector<Distribution> read_distributions(const std::filesystem::path& file,
                                             const Scene& scene) {
  return read_placing_keys(file.string(), input_keys::kDistributionsPlaces,
                           [&] { return read_distributions_objects(file, scene); });
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

Distribution distribution_from(const JsonValue& v) {
  const JsonObject o = v.object({"key", "distribution", "unit", "nominal", "mean",
                                 "standard_deviation", "range", "path", "dimension"});
  auto real = [&](const char* key) {
    return o.require(key, key).quantity(Dimension::kDimensionless);
  };
  static constexpr EnumName<DistributionKind> kKinds[] = {{"normal", DistributionKind::kNormal},
                                                          {"uniform", DistributionKind::kUniform}};
  Distribution d;
  d.key = o.require("key", "the scene value drawn").string();
  d.path = o.require("path", "its path in the distributions file").string();
  d.kind = enum_from(o.require("distribution", "normal or uniform"), kKinds);
  d.nominal = real("nominal");
  d.mean = real("mean");
  d.standard_deviation = real("standard_deviation");
  if (auto u = o.get("unit")) u->string();
  if (d.kind == DistributionKind::kUniform) {
    const JsonValue range = o.require("range", "[low, high]");
    const std::vector<JsonValue> ends = range.array();
    if (ends.size() != 2) throw range.error("expected [low, high]");
    d.low = ends[0].quantity(Dimension::kDimensionless);
    d.high = ends[1].quantity(Dimension::kDimensionless);
  }
  const JsonValue dim = o.require("dimension", "the value's dimension");
  const std::string name = dim.string();
  bool found = false;
  for (int k = 0; k <= static_cast<int>(Dimension::kStiffness); ++k)
    if (to_string(static_cast<Dimension>(k)) == name) {
      d.dimension = static_cast<Dimension>(k);
      found = true;
    }
  if (!found) throw dim.error("not a dimension shpb writes");
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

}  // namespace shpb
