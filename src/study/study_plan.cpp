#include "study/study_plan.hpp"

#include <cmath>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

#include "core/error.hpp"
#include "core/json_document.hpp"
#include "core/json_numbers.hpp"
#include "core/json_value.hpp"
#include "version.hpp"

namespace shpb {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

Json series_json(const TimeSeries& s) {
  Json values = Json::array();
  for (const auto& column : s.values) {
    Json c = Json::array();
    for (double v : column) c.push_back(number(v));
    values.push_back(c);
  }
  return Json{{"columns", s.columns}, {"time_s", s.time_s}, {"values", values}};
}

// A gauge record, checked to be a table: one value column per name, each as long as the times.
TimeSeries series_from(const nlohmann::json& j) {
  TimeSeries s;
  s.columns = j.at("columns").get<std::vector<std::string>>();
  s.time_s = j.at("time_s").get<std::vector<double>>();
  for (const auto& column : j.at("values")) {
    std::vector<double> c;
    c.reserve(column.size());
    for (const auto& v : column) c.push_back(number(v));
    if (c.size() != s.time_s.size())
      throw std::invalid_argument("gauges.values[" + std::to_string(s.values.size()) + "] has " +
                                  std::to_string(c.size()) + " values for " +
                                  std::to_string(s.time_s.size()) + " times");
    s.values.push_back(std::move(c));
  }
  if (s.values.size() != s.columns.size())
    throw std::invalid_argument("gauges: " + std::to_string(s.values.size()) +
                                " value columns for " + std::to_string(s.columns.size()) +
                                " column names");
  return s;
}

// The keys of plan.json and of its options (plan_text writes them).
const std::vector<std::string> kPlanKeys = {"version",    "command", "plan_id", "sweep", "scene",
                                            "scene_text", "inputs",  "options", "runs"};
const std::vector<std::string> kOptionKeys = {"contact", "stepping",      "courant",
                                              "refine",  "distributions", "seed"};

// A whole number 0 … 2^64 − 1 (a seed: JsonValue::integer stops at 2^63 − 1).
std::uint64_t unsigned_integer(const JsonValue& v) {
  if (!v.json().is_number_unsigned()) throw v.error("expected a whole number 0 to 2^64 - 1");
  return v.json().get<std::uint64_t>();
}

double real(const JsonValue& v) { return v.quantity(Dimension::kDimensionless); }

// One of the plan's runs, of a kind its sweep has, appended to the plan.
void read_run(const JsonValue& v, StudyPlan& plan) {
  static const std::vector<std::string> kPareto = {
      "run", "kind", "row", "method", "stepping", "resolution", "finite_links"};
  static const std::vector<std::string> kStability = {
      "run", "kind", "method", "stiffness_factor", "mass_ratio", "courant", "tied", "step_ratio"};
  static const std::vector<std::string> kMonteCarlo = {"run", "kind", "values"};
  const JsonValue kind_value =
      v.object({"run", "kind", "row", "method", "stepping", "resolution", "finite_links",
                "stiffness_factor", "mass_ratio", "courant", "tied", "step_ratio", "values"})
          .require("kind", "the run's kind");
  const std::string kind = kind_value.string();
  const auto run_index = static_cast<std::int64_t>(plan.runs());
  auto number = [](const JsonObject& o, const char* key) { return real(o.require(key, key)); };
  if (plan.sweep == Sweep::kPareto && (kind == "case" || kind == "reference")) {
    const JsonObject o = v.object(kPareto);
    o.require("run", "the run's index").integer(run_index, run_index);
    ParetoJob p;
    p.reference = kind == "reference";
    if (!p.reference)
      p.row = static_cast<std::size_t>(o.require("row", "the case's row").integer(0, 1 << 30));
    p.run = {
        enum_from(o.require("method", "the contact method"), kContactMethodNames),
        enum_from(o.require("stepping", "the stepping"), kSteppingNames),
        o.require("resolution", "the mesh factor").positive_quantity(Dimension::kDimensionless),
        o.require("finite_links", "true or false").boolean()};
    plan.pareto.push_back(p);
  } else if (plan.sweep == Sweep::kStability && (kind == "boundary" || kind == "point")) {
    const JsonObject o = v.object(kStability);
    o.require("run", "the run's index").integer(run_index, run_index);
    StabilityJob s;
    s.boundary = kind == "boundary";
    s.point = {enum_from(o.require("method", "the contact method"), kContactMethodNames),
               number(o, "stiffness_factor"),
               number(o, "mass_ratio"),
               number(o, "courant"),
               o.require("tied", "true or false").boolean(),
               number(o, "step_ratio")};
    plan.stability.push_back(s);
  } else if (plan.sweep == Sweep::kMonteCarlo && (kind == "nominal" || kind == "draw")) {
    const JsonObject o = v.object(kMonteCarlo);
    o.require("run", "the run's index").integer(run_index, run_index);
    MonteCarloJob m;
    m.nominal = kind == "nominal";
    if (!m.nominal) {
      const JsonValue values = o.require("values", "one drawn value per distribution");
      for (const JsonValue& x : values.array()) m.values.push_back(real(x));
      if (m.values.size() != plan.distributions.size())
        throw values.error_with_value(
            std::to_string(m.values.size()) + " values",
            "expected one per distribution, " + std::to_string(plan.distributions.size()));
    }
    plan.monte_carlo.push_back(m);
  } else {
    throw kind_value.error("not a run of a " + to_string(plan.sweep) + " plan");
  }
}

InputError damaged(const fs::path& file, const std::string& what) {
  return input_error(
      file.string(), "", "",
      "not a file written by shpb study --plan/--run (" + what + "): plan and run again");
}

}  // namespace

std::string new_plan_id() {
  std::random_device rd;
  std::ostringstream s;
  s << std::hex << rd() << rd();
  return s.str();
}

std::string plan_text(const StudyPlan& plan) {
  Json runs = Json::array();
  for (std::size_t j = 0; j < plan.pareto.size(); ++j) {
    const ParetoJob& p = plan.pareto[j];
    Json r{{"run", j}, {"kind", p.reference ? "reference" : "case"}};
    if (!p.reference) r["row"] = p.row;
    r["method"] = to_string(p.run.method);
    r["stepping"] = to_string(p.run.stepping);
    r["resolution"] = p.run.resolution;
    r["finite_links"] = p.run.finite_links;
    runs.push_back(r);
  }
  for (std::size_t j = 0; j < plan.stability.size(); ++j) {
    const StabilityJob& s = plan.stability[j];
    runs.push_back(Json{{"run", j},
                        {"kind", s.boundary ? "boundary" : "point"},
                        {"method", to_string(s.point.method)},
                        {"stiffness_factor", s.point.stiffness_factor},
                        {"mass_ratio", s.point.mass_ratio},
                        {"courant", s.point.courant},
                        {"tied", s.point.tied},
                        {"step_ratio", s.point.step_ratio}});
  }
  for (std::size_t j = 0; j < plan.monte_carlo.size(); ++j) {
    const MonteCarloJob& m = plan.monte_carlo[j];
    Json r{{"run", j}, {"kind", m.nominal ? "nominal" : "draw"}};
    if (!m.nominal) r["values"] = m.values;
    runs.push_back(r);
  }
  Json j;
  j["version"] = kVersion;
  j["command"] = "study";
  j["plan_id"] = plan.id;
  j["sweep"] = to_string(plan.sweep);
  j["scene"] = plan.scene.string();
  j["scene_text"] = plan.scene_text;
  j["inputs"] = plan.inputs;
  Json options = Json::object();
  if (plan.contact) options["contact"] = to_string(*plan.contact);
  if (plan.stepping) options["stepping"] = to_string(*plan.stepping);
  if (plan.courant) options["courant"] = *plan.courant;
  if (plan.refine != 1) options["refine"] = plan.refine;
  if (plan.sweep == Sweep::kMonteCarlo) {
    Json d = Json::array();
    for (const Distribution& x : plan.distributions) d.push_back(distribution_json(x));
    options["distributions"] = d;
    options["seed"] = plan.seed;
  }
  j["options"] = options;
  j["runs"] = runs;
  return j.dump(1) + "\n";
}

StudyPlan read_study_plan(const fs::path& plan_file) {
  if (!std::ifstream(plan_file))
    throw input_error(plan_file.string(), "", "",
                      "cannot be read (make the plan first: shpb study SCENE --plan DIR)");
  // The project's reader and schema checks (core/json_document.hpp, core/json_value.hpp): a
  // damaged or hand-edited plan is refused with its file, JSON path, value and what is expected.
  const std::string display = plan_file.string();
  const nlohmann::json document = read_json_object_file(plan_file, display);
  const JsonObject o = JsonValue(document, display, "").object(kPlanKeys);
  StudyPlan plan;
  if (const auto command = o.require("command", "\"study\""); command.string() != "study")
    throw command.error("expected \"study\": a plan written by shpb study --plan");
  if (auto v = o.get("version")) v->string();
  plan.id = o.require("plan_id", "the plan's id").string();
  plan.sweep = enum_from(o.require("sweep", "the sweep"), kSweepNames);
  plan.scene = o.require("scene", "the scene's absolute path").string();
  plan.scene_text = o.require("scene_text", "the scene file's text").string();
  const JsonValue inputs = o.require("inputs", "the input files with their digests");
  inputs.array();  // each entry is checked against its file (check_input_digests)
  plan.inputs = inputs.json();
  const JsonObject options = o.require("options", "the sweep's options").object(kOptionKeys);
  if (auto v = options.get("contact")) plan.contact = enum_from(*v, kContactMethodNames);
  if (auto v = options.get("stepping")) plan.stepping = enum_from(*v, kSteppingNames);
  if (auto v = options.get("courant"))
    plan.courant = v->positive_quantity(Dimension::kDimensionless);
  if (auto v = options.get("refine")) plan.refine = static_cast<int>(v->integer(1, kMaxRefine));
  if (plan.sweep == Sweep::kMonteCarlo) {
    for (const JsonValue& d : options.require("distributions", "the values drawn").array())
      plan.distributions.push_back(distribution_from(d));
    plan.seed = unsigned_integer(options.require("seed", "the draws' seed"));
  }
  for (const JsonValue& r : o.require("runs", "the plan's runs").array()) read_run(r, plan);
  return plan;
}

nlohmann::ordered_json part_json(const StudyPlan& plan, const StudyResults& results,
                                 const std::vector<std::size_t>& runs) {
  Json out = Json::array();
  for (std::size_t r : runs) {
    Json j{{"run", r}};
    if (plan.sweep == Sweep::kMonteCarlo) {
      j["result"] = job_result_json(results.monte_carlo[r]);
    } else if (plan.sweep == Sweep::kPareto) {
      const ParetoJobResult& p = results.pareto[r];
      j["stable"] = p.stable;
      j["failure"] = p.failure;
      j["wall_time_s"] = p.wall_time_s;
      j["node_updates"] = p.node_updates;
      j["gauges"] = series_json(p.gauges);
    } else {
      const StabilityJobResult& s = results.stability[r];
      if (plan.stability[r].boundary) {
        j["critical_courant"] = number(s.critical_courant);
      } else {
        j["energy_growth"] = number(s.verdict.energy_growth);
        j["stable"] = s.verdict.stable;
        j["closings_after_release"] = s.verdict.closings_after_release;
        j["meetings_after_unloading"] = s.verdict.meetings_after_unloading;
        j["force_after_unloading_share"] = number(s.verdict.force_after_unloading_share);
      }
    }
    out.push_back(j);
  }
  return Json{{"plan_id", plan.id}, {"inputs", plan.inputs}, {"results", out}};
}

void read_part(const nlohmann::json& part, const fs::path& file, const StudyPlan& plan,
               const std::vector<std::size_t>& expected, StudyResults& results) {
  try {
    if (part.at("plan_id").get<std::string>() != plan.id)
      throw input_error(file.string(), "plan_id", part.at("plan_id").dump(),
                        "a part of another plan (the folder was planned again): run this shard "
                        "again");
    if (part.at("inputs") != plan.inputs)
      throw input_error(file.string(), "inputs", "",
                        "run on other input files than the plan lists now (a scene or material "
                        "file changed between shards): remove the part and run its shard again");
    const auto& list = part.at("results");
    if (list.size() != expected.size()) throw std::invalid_argument("wrong number of runs");
    for (std::size_t i = 0; i < expected.size(); ++i) {
      const auto& j = list[i];
      const std::size_t r = j.at("run").get<std::size_t>();
      if (r != expected[i]) throw std::invalid_argument("unexpected run " + std::to_string(r));
      if (plan.sweep == Sweep::kMonteCarlo) {
        results.monte_carlo.at(r) = job_result_from(j.at("result"));
      } else if (plan.sweep == Sweep::kPareto) {
        ParetoJobResult& p = results.pareto.at(r);
        p.stable = j.at("stable").get<bool>();
        p.failure = j.at("failure").get<std::string>();
        p.wall_time_s = j.at("wall_time_s").get<double>();
        p.node_updates = j.at("node_updates").get<long long>();
        p.gauges = series_from(j.at("gauges"));
        if (plan.pareto.at(r).reference && p.gauges.samples() == 0)
          throw std::invalid_argument("the reference run (run " + std::to_string(r) +
                                      ") has no gauge record");
      } else {
        StabilityJobResult& s = results.stability.at(r);
        if (plan.stability.at(r).boundary) {
          s.critical_courant = number(j.at("critical_courant"));
        } else {
          s.verdict.energy_growth = number(j.at("energy_growth"));
          s.verdict.stable = j.at("stable").get<bool>();
          s.verdict.closings_after_release = j.at("closings_after_release").get<long>();
          s.verdict.meetings_after_unloading = j.at("meetings_after_unloading").get<long>();
          s.verdict.force_after_unloading_share = number(j.at("force_after_unloading_share"));
        }
      }
    }
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw damaged(file, e.what());
  }
}

}  // namespace shpb
