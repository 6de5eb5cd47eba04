#include "study/study_report.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "core/checked_write.hpp"
#include "core/csv_writer.hpp"
#include "model/mesh_error_model.hpp"
#include "output_schema.hpp"
#include "study/monte_carlo_outputs.hpp"
#include "study/pareto_front.hpp"
#include "study/pareto_sweep.hpp"
#include "study/stability_sweep.hpp"
#include "version.hpp"

namespace shpb {

// One run of a Pareto sweep as summary.json lists it (docs/outputs.md).
void to_json(nlohmann::ordered_json& j, const ParetoCase& c) {
  j = {{"method", method_name(c)},
       {"stepping", to_string(c.stepping)},
       {"resolution", c.resolution}};
}

namespace {

using Json = nlohmann::ordered_json;

// A CSV field: empty for a non-finite value (undefined, e.g. the error of an unstable run).
std::string field(double v) { return format_field(v); }

// A CSV flag: 1 or 0.
std::string flag(bool b) { return b ? "1" : "0"; }

// Speed of localized-bipenalty asynchronous against localized-bipenalty global at equal error:
// the global runs' wall time (and node updates) interpolated at each asynchronous run's error.
Json speed_ratios(const ParetoStudy& study) {
  std::vector<double> err, wall, updates;
  for (const ParetoRow& r : study.rows)
    if (r.run.method == ContactMethod::kLocalizedBipenalty && r.run.stepping == Stepping::kGlobal &&
        !r.run.finite_links && std::isfinite(r.error)) {
      err.push_back(r.error);
      wall.push_back(r.wall_time_s);
      updates.push_back(static_cast<double>(r.node_updates));
    }
  Json out = Json::array();
  for (const ParetoRow& r : study.rows) {
    if (r.run.method != ContactMethod::kLocalizedBipenalty || r.run.finite_links ||
        r.run.stepping != Stepping::kAsynchronous || !std::isfinite(r.error))
      continue;
    Json j{{"resolution", r.run.resolution}, {"error", r.error}, {"wall_time_s", r.wall_time_s}};
    const auto w = cost_at_error(err, wall, r.error);
    const auto u = cost_at_error(err, updates, r.error);
    j["global_wall_time_s_at_equal_error"] = w ? Json(*w) : Json(nullptr);
    j["wall_time_ratio_global_to_asynchronous"] = w ? Json(*w / r.wall_time_s) : Json(nullptr);
    j["node_update_ratio_global_to_asynchronous"] =
        u ? Json(*u / static_cast<double>(r.node_updates)) : Json(nullptr);
    out.push_back(j);
  }
  return out;
}

// Returns the warnings to print: a scene whose every interface is bonded compares no contact
// method (a glued joint stays bonded in every run, src/study/sweep.cpp scene_for): its methods'
// rows are one run each, told apart by wall-time noise only.
std::vector<std::string> write_pareto(const ParetoStudy& study, const Scene& scene, int threads,
                                      double wall_s, const std::filesystem::path& dir) {
  bool all_bonded = true;
  for (std::size_t k = 0; k + 1 < scene.bars.size(); ++k)
    all_bonded = all_bonded && interface_method(scene.contact, k) == ContactMethod::kBonded;
  std::vector<std::string> warnings;
  if (all_bonded)
    warnings.push_back(
        "study pareto: every interface of the scene is bonded, and a bonded interface stays "
        "bonded in every run: the contact methods of pareto.csv are the same run, only the "
        "stepping and the mesh differ");
  std::vector<double> err, wall, updates;
  for (const ParetoRow& r : study.rows) {
    err.push_back(r.error);
    wall.push_back(r.wall_time_s);
    updates.push_back(static_cast<double>(r.node_updates));
  }
  // The one computation of the front: pareto.csv carries it for the report, summary.json lists it.
  const std::vector<bool> by_wall = pareto_front(err, wall),
                          by_updates = pareto_front(err, updates);
  namespace k = schema::pareto;  // the column names (src/core/output_schema.json)
  CsvWriter csv(dir / k::kFile, {k::method, k::stepping, k::resolution, k::error, k::wall_time_s,
                                 k::node_updates, k::stable, k::pareto_front_wall_time,
                                 k::pareto_front_node_updates, k::recorded_error});
  for (std::size_t i = 0; i < study.rows.size(); ++i) {
    const ParetoRow& r = study.rows[i];
    const std::string cells[] = {method_name(r.run),
                                 std::string(to_string(r.run.stepping)),
                                 format_double(r.run.resolution),
                                 field(r.error),
                                 format_double(r.wall_time_s),
                                 std::to_string(r.node_updates),
                                 flag(r.stable),
                                 flag(by_wall[i]),
                                 flag(by_updates[i]),
                                 field(r.recorded_error)};
    csv.row(cells);
  }
  csv.close();
  Json front_wall = Json::array(), front_updates = Json::array(), unstable = Json::array();
  for (std::size_t i = 0; i < study.rows.size(); ++i) {
    if (by_wall[i]) front_wall.push_back(Json(study.rows[i].run));
    if (by_updates[i]) front_updates.push_back(Json(study.rows[i].run));
    if (!study.rows[i].stable) {
      Json j = study.rows[i].run;
      j["failure"] = study.rows[i].failure;
      unstable.push_back(j);
    }
  }
  Json j;
  j["version"] = kVersion;
  j["scene"] = scene.name;
  j["sweep"] = to_string(Sweep::kPareto);
  j["error"] = "relative L2 norm of the gauge strains against the reference, all gauges";
  j["reference"] = study.reference;
  j["reference_exact"] = study.reference_exact;
  if (!study.reference_exact) j["reference_wall_time_s"] = study.reference_wall_time_s;
  j["runs"] = study.rows.size();
  j["threads"] = threads;
  j["wall_time_s"] = wall_s;
  j["pareto_front_wall_time"] = front_wall;
  j["pareto_front_node_updates"] = front_updates;
  j["localized_bipenalty_asynchronous_against_global"] = speed_ratios(study);
  j["unstable"] = unstable;
  if (const auto t = scene.simulation.tolerance) {  // resolution 1 is the tolerance's meshes
    j["tolerance"] = *t;
    j["predicted_gauge_error"] = predict_gauge_error(scene, discretize(scene)).total;
  }
  j["warnings"] = warnings;
  write_text_file(dir / "summary.json", j.dump(2) + "\n");
  return warnings;
}

void write_stability(const StabilityStudy& study, const Scene& scene, int refine, int threads,
                     double wall_s, const std::filesystem::path& dir) {
  namespace k = schema::stability;  // the column names (src/core/output_schema.json)
  CsvWriter points(dir / k::kFile,
                   {k::method, k::stiffness_factor, k::mass_ratio, k::courant, k::energy_growth,
                    k::stable, k::step_ratio, k::closings_after_release,
                    k::meetings_after_unloading, k::force_after_unloading_share});
  for (const StabilityRow& r : study.rows) {
    const bool penalty = r.point.method == ContactMethod::kPenalty;
    const std::string cells[] = {std::string(to_string(r.point.method)),
                                 format_double(r.point.stiffness_factor),
                                 penalty ? "" : format_double(r.point.mass_ratio),
                                 format_double(r.point.courant),
                                 field(r.verdict.energy_growth),
                                 flag(r.verdict.stable),
                                 format_double(r.point.step_ratio),
                                 std::to_string(r.verdict.closings_after_release),
                                 std::to_string(r.verdict.meetings_after_unloading),
                                 field(r.verdict.force_after_unloading_share)};
    points.row(cells);
  }
  points.close();
  namespace kb = schema::stability_boundary;
  CsvWriter lines(dir / kb::kFile, {kb::method, kb::link, kb::stiffness_factor, kb::mass_ratio,
                                    kb::critical_courant, kb::closed_form_courant, kb::step_ratio});
  for (const StabilityBoundary& b : study.boundaries) {
    const bool penalty = b.line.method == ContactMethod::kPenalty;
    const std::string cells[] = {
        std::string(to_string(b.line.method)),
        b.line.tied ? "tied" : "unilateral",
        format_double(b.line.stiffness_factor),
        penalty ? "" : format_double(b.line.mass_ratio),
        b.critical_courant <= kBoundaryCourantMin ? "" : format_double(b.critical_courant),
        format_double(b.closed_form_courant),
        format_double(b.line.step_ratio)};
    lines.row(cells);
  }
  lines.close();
  Json j;
  j["version"] = kVersion;
  j["scene"] = scene.name;
  j["sweep"] = to_string(Sweep::kStability);
  j["probe"] = study.probe;
  j["unstable_when"] = "total energy above " + format_double(kUnstableEnergyGrowth) +
                       " x its initial value, or a non-finite value";
  j["stiffness_factor"] = "penalty stiffness / (EA/h) of the stiffer neighbour";
  j["mass_ratio"] = "R / R_crit, R = stiffness / mass penalty, R_crit = (2 c/h)^2";
  j["closed_form_courant"] =
      "penalty: sqrt(2/(1+sqrt(1+4 s^2))), exact limit of two lumped bars joined by the penalty "
      "spring; bipenalty: 1 for R <= R_crit, sqrt(R_crit/R) (the 2/sqrt(R) step) above";
  j["boundary_range"] = {kBoundaryCourantMin, kBoundaryCourantMax};
  j["critical_courant"] =
      "largest stable Courant number by bisection in boundary_range; empty: unstable at its lower "
      "end, its upper end: stable throughout; link tied: penalty or node-to-node bipenalty acting "
      "in "
      "tension too (the linear system of the closed forms), unilateral: as used";
  if (refine != 1) j["refine"] = refine;
  j["points"] = study.rows.size();
  j["threads"] = threads;
  j["wall_time_s"] = wall_s;
  j["warnings"] = Json::array();  // none: every summary.json has the key
  write_text_file(dir / "summary.json", j.dump(2) + "\n");
}

}  // namespace

std::vector<std::string> write_study(const StudyPlan& plan, const Scene& scene,
                                     const StudyResults& results, int threads, double wall_s,
                                     const std::filesystem::path& dir) {
  if (plan.sweep == Sweep::kMonteCarlo)
    return write_monte_carlo(scene, plan.distributions, plan.seed, plan.monte_carlo,
                             results.monte_carlo, threads, wall_s, dir);
  if (plan.sweep == Sweep::kStability)
    write_stability(
        assemble_stability(stability_probe_scene(scene), plan.stability, results.stability), scene,
        plan.refine, threads, wall_s, dir);
  else
    return write_pareto(assemble_pareto(scene, plan.pareto, results.pareto), scene, threads, wall_s,
                        dir);
  return {};
}

}  // namespace shpb
