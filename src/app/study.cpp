// shpb study SCENE.json -o DIR --sweep pareto|stability: accuracy against cost of every
// contact method × stepping × mesh resolution (pareto.csv), or the stability map of the contact
// methods over penalty stiffness, Courant number and mass ratio (stability.csv,
// stability_boundary.csv); summary.json says what was compared with what. Written atomically.
// The sweep is a plan of independent runs: run here on threads, or planned into a folder
// (--plan), run there shard by shard on other machines (--run DIR --shard K/N) and merged
// (--merge); one code path, so a merged study equals an in-process one apart from wall times.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/commands.hpp"
#include "app/progress.hpp"
#include "core/checked_write.hpp"
#include "core/csv_writer.hpp"
#include "core/error.hpp"
#include "core/file_digest.hpp"
#include "core/output_folder.hpp"
#include "core/parallel_runner.hpp"
#include "model/mesh_error_model.hpp"
#include "study/pareto_front.hpp"
#include "study/pareto_sweep.hpp"
#include "study/shards.hpp"
#include "study/stability_sweep.hpp"
#include "study/study_plan.hpp"
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

// "done/total runs" on stderr (app/progress.hpp).
std::function<void(std::size_t, std::size_t)> progress_printer(bool quiet, std::string what) {
  if (quiet) return {};
  return [print = ProgressPrinter("study " + what)](std::size_t done, std::size_t total) mutable {
    print(static_cast<double>(done) / static_cast<double>(total),
          std::to_string(done) + "/" + std::to_string(total) + " runs");
  };
}

// A CSV field: shortest round-trip double, empty for a non-finite value (undefined, e.g. the
// error of an unstable run).
std::string field(double v) { return std::isfinite(v) ? format_double(v) : std::string(); }

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

void write_pareto(const ParetoStudy& study, const Scene& scene, int threads, double wall_s,
                  const std::filesystem::path& dir) {
  std::vector<double> err, wall, updates;
  for (const ParetoRow& r : study.rows) {
    err.push_back(r.error);
    wall.push_back(r.wall_time_s);
    updates.push_back(static_cast<double>(r.node_updates));
  }
  // The one computation of the front: pareto.csv carries it for the report, summary.json lists it.
  const std::vector<bool> by_wall = pareto_front(err, wall),
                          by_updates = pareto_front(err, updates);
  {
    std::ostringstream csv;
    csv << "method,stepping,resolution,error,wall_time_s,node_updates,stable,"
           "pareto_front_wall_time,pareto_front_node_updates,recorded_error\n";
    for (std::size_t i = 0; i < study.rows.size(); ++i) {
      const ParetoRow& r = study.rows[i];
      csv << method_name(r.run) << ',' << to_string(r.run.stepping) << ','
          << format_double(r.run.resolution) << ',' << field(r.error) << ','
          << format_double(r.wall_time_s) << ',' << r.node_updates << ',' << (r.stable ? 1 : 0)
          << ',' << (by_wall[i] ? 1 : 0) << ',' << (by_updates[i] ? 1 : 0) << ','
          << field(r.recorded_error) << '\n';
    }
    write_text_file(dir / "pareto.csv", csv.str());
  }
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
  write_text_file(dir / "summary.json", j.dump(2) + "\n");
}

void write_stability(const StabilityStudy& study, const Scene& scene, int refine, int threads,
                     double wall_s, const std::filesystem::path& dir) {
  {
    std::ostringstream csv;
    csv << "method,stiffness_factor,mass_ratio,courant,energy_growth,stable,step_ratio,"
           "closings_after_release\n";
    for (const StabilityRow& r : study.rows)
      csv << to_string(r.point.method) << ',' << format_double(r.point.stiffness_factor) << ','
          << (r.point.method == ContactMethod::kPenalty ? "" : format_double(r.point.mass_ratio))
          << ',' << format_double(r.point.courant) << ',' << field(r.verdict.energy_growth) << ','
          << (r.verdict.stable ? 1 : 0) << ',' << format_double(r.point.step_ratio) << ','
          << r.verdict.closings_after_release << '\n';
    write_text_file(dir / "stability.csv", csv.str());
  }
  {
    std::ostringstream csv;
    csv << "method,link,stiffness_factor,mass_ratio,critical_courant,closed_form_courant,"
           "step_ratio\n";
    for (const StabilityBoundary& b : study.boundaries)
      csv << to_string(b.line.method) << ',' << (b.line.tied ? "tied" : "unilateral") << ','
          << format_double(b.line.stiffness_factor) << ','
          << (b.line.method == ContactMethod::kPenalty ? "" : format_double(b.line.mass_ratio))
          << ','
          << (b.critical_courant <= kBoundaryCourantMin ? "" : format_double(b.critical_courant))
          << ',' << format_double(b.closed_form_courant) << ',' << format_double(b.line.step_ratio)
          << '\n';
    write_text_file(dir / "stability_boundary.csv", csv.str());
  }
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
  write_text_file(dir / "summary.json", j.dump(2) + "\n");
}

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The plan of the sweep the options ask for (ids and the scene's text filled in by the caller).
StudyPlan make_plan(const StudyArgs& args, const Scene& scene) {
  StudyPlan plan;
  plan.sweep = args.sweep;
  plan.contact = args.overrides.contact;
  plan.stepping = args.overrides.stepping;
  plan.courant = args.overrides.courant;
  plan.refine = args.refine;
  std::vector<ContactMethod> methods;
  std::vector<Stepping> steppings;
  if (plan.contact) methods.push_back(*plan.contact);
  if (plan.stepping) steppings.push_back(*plan.stepping);
  if (plan.sweep == Sweep::kStability)
    plan.stability = stability_jobs(stability_grid(methods, plan.refine));
  else
    plan.pareto = pareto_jobs(scene, pareto_cases(methods, steppings));
  return plan;
}

// The scene of a plan read from its folder: the same files (scene, materials), unchanged, with the
// same options.
Scene plan_scene(const StudyPlan& plan, const std::filesystem::path& plan_file) {
  check_input_digests(plan.inputs, plan_file, "inputs", "the plan was made", "plan again");
  Scene scene = read_scene(plan.scene);
  RunOverrides o;
  o.contact = plan.contact;
  o.stepping = plan.stepping;
  o.courant = plan.courant;
  apply_overrides(o, scene);
  return scene;
}

// Runs `runs` of the plan on `threads` workers, each result into its slot.
void run_plan(const StudyPlan& plan, const Scene& scene, const std::vector<std::size_t>& runs,
              int threads, bool quiet, StudyResults& results) {
  const auto cancel = [] { return interrupted(); };
  results.pareto.resize(plan.pareto.size());
  results.stability.resize(plan.stability.size());
  const auto progress = progress_printer(quiet, to_string(plan.sweep));
  if (plan.sweep == Sweep::kStability) {
    const Scene probe = stability_probe_scene(scene);
    run_parallel(
        runs.size(), threads,
        [&](std::size_t i) {
          if (cancel()) throw Interrupted();
          results.stability[runs[i]] = run_stability_job(probe, plan.stability[runs[i]]);
        },
        progress);
  } else {
    run_parallel(
        runs.size(), threads,
        [&](std::size_t i) {
          results.pareto[runs[i]] = run_pareto_job(scene, plan.pareto[runs[i]], cancel);
        },
        progress);
  }
}

// The study's files from every run's result.
void write_study(const StudyPlan& plan, const Scene& scene, const StudyResults& results,
                 int threads, double wall_s, const std::filesystem::path& dir) {
  if (plan.sweep == Sweep::kStability)
    write_stability(
        assemble_stability(stability_probe_scene(scene), plan.stability, results.stability), scene,
        plan.refine, threads, wall_s, dir);
  else
    write_pareto(assemble_pareto(scene, plan.pareto, results.pareto), scene, threads, wall_s, dir);
}

std::vector<std::size_t> all_runs(std::size_t n) {
  std::vector<std::size_t> runs(n);
  for (std::size_t i = 0; i < n; ++i) runs[i] = i;
  return runs;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// shpb study SCENE --plan DIR: DIR/plan.json, nothing run.
int plan_study(const StudyArgs& args) {
  const std::filesystem::path dir = *args.plan;
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_empty(dir, ec))
    throw input_error(dir.string(), "", "", "exists and is not empty: plan into a new folder");
  if (args.overrides.tolerance)  // the plan re-applies only the scene's own tolerance
    throw input_error("--tolerance", "", "",
                      "not with --plan: give simulation.tolerance in the scene");
  Scene scene = read_scene(args.scene);
  apply_overrides(args.overrides, scene);
  StudyPlan plan = make_plan(args, scene);
  plan.id = new_plan_id();
  plan.scene = std::filesystem::absolute(args.scene).lexically_normal();
  plan.scene_text = read_text(args.scene);
  const std::vector<std::filesystem::path> inputs = scene_inputs(scene, false);
  plan.inputs = input_digests(inputs);
  OutputFolder out(dir, "study", inputs);
  std::filesystem::create_directory(out.path() / "parts");
  write_file_atomically(out.file("plan.json"), plan_text(plan));
  out.commit();
  if (!args.overrides.quiet)
    std::fprintf(stderr,
                 "study %s of %s: %zu runs planned in %s; next: shpb study --run %s --shard K/N, "
                 "then shpb study --merge %s\n",
                 to_string(plan.sweep).c_str(), scene.name.c_str(), plan.runs(),
                 dir.string().c_str(), dir.string().c_str(), dir.string().c_str());
  return 0;
}

// shpb study --run DIR --shard K/N: DIR/parts/K-of-N.json.
int run_study_shard(const StudyArgs& args) {
  const std::filesystem::path dir = *args.run, plan_file = dir / "plan.json";
  if (args.shard.empty()) throw input_error("--shard", "", "", "K/N is needed with --run DIR");
  const Shard shard = parse_shard("--shard", args.shard);
  const StudyPlan plan = read_study_plan(plan_file);
  const std::filesystem::path part = dir / "parts" / (part_name(shard) + ".json");
  if (std::filesystem::exists(part)) {
    if (!args.overrides.quiet)
      std::fprintf(stderr, "study: %s exists, shard skipped\n", part.string().c_str());
    return 0;
  }
  const Scene scene = plan_scene(plan, plan_file);
  const int threads = resolve_threads(args.overrides.threads);
  const auto start = std::chrono::steady_clock::now();
  const std::vector<std::size_t> runs = shard_runs(plan.runs(), shard);
  StudyResults results;
  run_plan(plan, scene, runs, threads, args.overrides.quiet, results);
  if (interrupted()) throw Interrupted();
  nlohmann::ordered_json j = part_json(plan, results, runs);
  j["shard"] = args.shard;
  j["threads"] = threads;
  j["wall_time_s"] = seconds_since(start);
  std::filesystem::create_directories(part.parent_path());
  write_file_atomically(part, j.dump() + "\n");
  if (!args.overrides.quiet)
    std::fprintf(stderr, "study %s shard %s: %zu runs in %.3g s on %d threads; wrote %s\n",
                 to_string(plan.sweep).c_str(), args.shard.c_str(), runs.size(),
                 seconds_since(start), threads, part.string().c_str());
  return 0;
}

// Every gauge record of the parts names the scene's gauges in its order: the error compares column
// by column with the reference.
void check_gauge_columns(const StudyPlan& plan, const Scene& scene, const std::vector<Part>& parts,
                         const StudyResults& results) {
  std::vector<std::string> gauges;
  for (const BarSpec& b : scene.bars)
    for (const GaugeSpec& g : b.gauges) gauges.push_back(g.name);
  for (const Part& p : parts)
    for (std::size_t r : shard_runs(plan.runs(), p.shard))
      if (r < results.pareto.size() && results.pareto[r].gauges.samples() > 0 &&
          results.pareto[r].gauges.columns != gauges)
        throw input_error(p.path.string(), "results (run " + std::to_string(r) + ")", "",
                          "gauge columns other than the scene's gauges: remove the part and run "
                          "its shard again");
}

// shpb study --merge DIR [-o OUT]: the whole study from DIR's parts.
int merge_study(const StudyArgs& args) {
  const std::filesystem::path dir = *args.merge, plan_file = dir / "plan.json";
  const StudyPlan plan = read_study_plan(plan_file);
  const Scene scene = plan_scene(plan, plan_file);  // an input changed: said first
  const std::vector<Part> parts = find_parts(dir / "parts", ".json");
  check_parts_cover(dir / "parts", plan.runs(), parts);
  // The plan, its parts and the files they were computed from are this run's inputs.
  std::vector<std::filesystem::path> inputs = {plan_file, dir / "parts"};
  for (const auto& f : scene_inputs(scene, false)) inputs.push_back(f);
  OutputFolder out(args.output.empty() ? dir / "result" : args.output, "study", inputs);
  StudyResults results;
  results.pareto.resize(plan.pareto.size());
  results.stability.resize(plan.stability.size());
  // Threads and wall time of a merged study: the most threads a shard used, the shards' sum.
  int threads = 0;
  double wall = 0;
  for (const Part& p : parts) {
    std::ifstream in(p.path);
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(in);
      threads = std::max(threads, j.at("threads").get<int>());
      wall += j.at("wall_time_s").get<double>();
    } catch (const std::exception& e) {
      throw input_error(p.path.string(), "", "",
                        std::string("damaged part (") + e.what() +
                            "): remove it and run its "
                            "shard again");
    }
    read_part(j, p.path, plan, shard_runs(plan.runs(), p.shard), results);
  }
  check_gauge_columns(plan, scene, parts, results);
  write_study(plan, scene, results, threads, wall, out.path());
  out.commit();
  if (!args.overrides.quiet)
    std::fprintf(stderr, "study %s of %s: merged %zu parts (%zu runs); wrote %s\n",
                 to_string(plan.sweep).c_str(), scene.name.c_str(), parts.size(), plan.runs(),
                 out.final_path().string().c_str());
  return 0;
}

}  // namespace

int run_study(const StudyArgs& args) {
  const int modes = (args.plan ? 1 : 0) + (args.run ? 1 : 0) + (args.merge ? 1 : 0);
  if (modes > 1)
    throw input_error("study", "", "", "--plan, --run and --merge are separate steps: give one");
  if (args.refine != 1 && args.sweep != Sweep::kStability)
    throw input_error("--refine", "", std::to_string(args.refine), "only with --sweep stability");
  if (!args.shard.empty() && !args.run)
    throw input_error("--shard", "", "\"" + args.shard + "\"", "only with --run DIR");
  if ((args.run || args.plan) && !args.output.empty())
    throw input_error("-o", "", "\"" + args.output.string() + "\"",
                      "not with --plan or --run: they write into DIR (the plan, DIR/parts)");
  if ((args.run || args.merge) && !args.scene.empty())
    throw input_error(args.scene.string(), "", "",
                      "--run and --merge take the scene from DIR/plan.json: give no scene");
  if (args.run) return run_study_shard(args);
  if (args.merge) return merge_study(args);
  if (args.scene.empty()) throw input_error("study", "", "", "a scene file is required");
  if (args.plan) return plan_study(args);
  if (args.output.empty()) throw input_error("-o", "", "", "an output folder is required");

  Scene scene = read_scene(args.scene);  // InputError → exit 2, nothing written
  apply_overrides(args.overrides, scene);
  OutputFolder out(args.output, "study", scene_inputs(scene, false));  // measured files unread
  const int threads = resolve_threads(args.overrides.threads);
  const auto start = std::chrono::steady_clock::now();
  const StudyPlan plan = make_plan(args, scene);
  StudyResults results;
  run_plan(plan, scene, all_runs(plan.runs()), threads, args.overrides.quiet, results);
  write_study(plan, scene, results, threads, seconds_since(start), out.path());
  const double wall = seconds_since(start);
  out.commit();
  if (!args.overrides.quiet)
    std::fprintf(stderr, "study %s of %s in %.3g s on %d threads; wrote %s\n",
                 to_string(args.sweep).c_str(), scene.name.c_str(), wall, threads,
                 out.final_path().string().c_str());
  return 0;
}

}  // namespace shpb
