#include "study/study_plan.hpp"

#include <cmath>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

#include "core/error.hpp"
#include "core/json_numbers.hpp"
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

ContactMethod method_from(const nlohmann::json& j) {
  const auto m = contact_method_from_string(j.get<std::string>());
  if (!m) throw std::invalid_argument("unknown contact method " + j.dump());
  return *m;
}

Stepping stepping_from(const nlohmann::json& j) {
  const auto s = stepping_from_string(j.get<std::string>());
  if (!s) throw std::invalid_argument("unknown stepping " + j.dump());
  return *s;
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
  std::ifstream in(plan_file);
  if (!in)
    throw input_error(plan_file.string(), "", "",
                      "cannot be read (make the plan first: shpb study SCENE --plan DIR)");
  StudyPlan plan;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    if (j.at("command") != "study") throw std::invalid_argument("not a study plan");
    plan.id = j.at("plan_id").get<std::string>();
    const auto sweep = enum_value(kSweepNames, j.at("sweep").get<std::string>());
    if (!sweep) throw std::invalid_argument("unknown sweep " + j.at("sweep").dump());
    plan.sweep = *sweep;
    plan.scene = j.at("scene").get<std::string>();
    plan.scene_text = j.at("scene_text").get<std::string>();
    plan.inputs = j.at("inputs");
    if (!plan.inputs.is_array()) throw std::invalid_argument("inputs is not a list");
    const auto& o = j.at("options");
    if (o.contains("contact")) plan.contact = method_from(o.at("contact"));
    if (o.contains("stepping")) plan.stepping = stepping_from(o.at("stepping"));
    if (o.contains("courant")) plan.courant = o.at("courant").get<double>();
    if (o.contains("refine")) plan.refine = o.at("refine").get<int>();
    if (plan.sweep == Sweep::kMonteCarlo) {
      for (const auto& d : o.at("distributions"))
        plan.distributions.push_back(distribution_from(d));
      plan.seed = o.at("seed").get<std::uint64_t>();
    }
    for (const auto& r : j.at("runs")) {
      const std::string kind = r.at("kind").get<std::string>();
      if (plan.sweep == Sweep::kPareto && (kind == "case" || kind == "reference")) {
        ParetoJob p;
        p.reference = kind == "reference";
        if (!p.reference) p.row = r.at("row").get<std::size_t>();
        p.run = {method_from(r.at("method")), stepping_from(r.at("stepping")),
                 r.at("resolution").get<double>(), r.at("finite_links").get<bool>()};
        plan.pareto.push_back(p);
      } else if (plan.sweep == Sweep::kStability && (kind == "boundary" || kind == "point")) {
        StabilityJob s;
        s.boundary = kind == "boundary";
        s.point = {method_from(r.at("method")),      r.at("stiffness_factor").get<double>(),
                   r.at("mass_ratio").get<double>(), r.at("courant").get<double>(),
                   r.at("tied").get<bool>(),         r.at("step_ratio").get<double>()};
        plan.stability.push_back(s);
      } else if (plan.sweep == Sweep::kMonteCarlo && (kind == "nominal" || kind == "draw")) {
        MonteCarloJob m;
        m.nominal = kind == "nominal";
        if (!m.nominal) m.values = r.at("values").get<std::vector<double>>();
        if (m.values.size() != (m.nominal ? 0 : plan.distributions.size()))
          throw std::invalid_argument("run " + r.at("run").dump() + " has " +
                                      std::to_string(m.values.size()) + " values for " +
                                      std::to_string(plan.distributions.size()) + " distributions");
        plan.monte_carlo.push_back(m);
      } else {
        throw std::invalid_argument("run of kind \"" + kind + "\" in a " + to_string(plan.sweep) +
                                    " plan");
      }
    }
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw damaged(plan_file, e.what());
  }
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
