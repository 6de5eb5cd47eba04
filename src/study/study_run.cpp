#include "study/study_run.hpp"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/clock.hpp"
#include "core/error.hpp"
#include "core/file_digest.hpp"
#include "core/output_folder.hpp"
#include "core/parallel_runner.hpp"
#include "core/shards.hpp"
#include "model/run_overrides.hpp"
#include "model/scene_inputs.hpp"
#include "study/pareto_sweep.hpp"
#include "study/stability_sweep.hpp"
#include "study/study_report.hpp"

namespace shpb {
namespace {

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

}  // namespace

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The plan of the sweep the options ask for (ids and the scene's text filled in by the caller).
StudyPlan make_study_plan(const StudyOptions& args, const Scene& scene) {
  StudyPlan plan;
  plan.sweep = args.sweep;
  plan.contact = args.contact;
  plan.stepping = args.stepping;
  plan.courant = args.courant;
  plan.refine = args.refine;
  std::vector<ContactMethod> methods;
  std::vector<Stepping> steppings;
  if (plan.contact) methods.push_back(*plan.contact);
  if (plan.stepping) steppings.push_back(*plan.stepping);
  if (plan.sweep == Sweep::kMonteCarlo) {
    plan.distributions = read_distributions(args.distributions, scene);
    plan.seed = args.seed;
    plan.monte_carlo = monte_carlo_jobs(plan.distributions, args.draws, args.seed);
  } else if (plan.sweep == Sweep::kStability)
    plan.stability = stability_jobs(stability_grid(methods, plan.refine));
  else
    plan.pareto = pareto_jobs(scene, pareto_cases(methods, steppings));
  return plan;
}

RunOverrides study_overrides(RunOverrides o) {
  o.default_tolerance = false;
  return o;
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
  apply_overrides(study_overrides(o), scene);
  return scene;
}

// Runs `runs` of the plan on `threads` workers, each result into its slot.
void run_plan(const StudyPlan& plan, const Scene& scene, const std::vector<std::size_t>& runs,
              int threads, const std::function<void(std::size_t, std::size_t)>& progress,
              StudyResults& results) {
  const auto cancel = [] { return interrupted(); };
  results.pareto.resize(plan.pareto.size());
  results.stability.resize(plan.stability.size());
  results.monte_carlo.resize(plan.monte_carlo.size());
  if (plan.sweep == Sweep::kMonteCarlo) {
    run_parallel(
        runs.size(), threads,
        [&](std::size_t i) {
          results.monte_carlo[runs[i]] =
              run_monte_carlo_job(scene, plan.distributions, plan.monte_carlo[runs[i]], cancel);
        },
        progress);
  } else if (plan.sweep == Sweep::kStability) {
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

std::vector<std::size_t> all_runs(std::size_t n) {
  std::vector<std::size_t> runs(n);
  for (std::size_t i = 0; i < n; ++i) runs[i] = i;
  return runs;
}

MergedParts merge_parts(const StudyPlan& plan, const Scene& scene,
                        const std::filesystem::path& dir) {
  MergedParts m;
  m.parts = find_parts(dir / "parts", ".json");
  check_parts_cover(dir / "parts", plan.runs(), m.parts);
  StudyResults& results = m.results;
  results.pareto.resize(plan.pareto.size());
  results.stability.resize(plan.stability.size());
  results.monte_carlo.resize(plan.monte_carlo.size());
  // Threads and wall time of a merged study: the most threads a shard used, the shards' sum.
  int& threads = m.threads;
  double& wall = m.wall_s;
  for (const Part& p : m.parts) {
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
  check_gauge_columns(plan, scene, m.parts, results);
  return m;
}

void require_new_plan_folder(const std::filesystem::path& dir) {
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_empty(dir, ec))
    throw input_error(dir.string(), "", "", "exists and is not empty: plan into a new folder");
}

StudyPlan write_study_plan(const std::filesystem::path& scene_file, const Scene& scene,
                           const StudyOptions& options, const std::filesystem::path& dir) {
  require_new_plan_folder(dir);
  StudyPlan plan = make_study_plan(options, scene);
  plan.id = new_plan_id();
  plan.scene = std::filesystem::absolute(scene_file).lexically_normal();
  plan.scene_text = read_text(scene_file);
  const std::vector<std::filesystem::path> inputs = scene_inputs(scene, false);
  plan.inputs = input_digests(inputs);
  OutputFolder out(dir, "study", inputs);
  std::filesystem::create_directory(out.path() / "parts");
  write_file_atomically(out.file("plan.json"), plan_text(plan));
  out.commit();
  return plan;
}

ShardRun run_study_shard(const StudyPlan& plan, const std::filesystem::path& dir,
                         const std::string& shard_text, int threads,
                         const std::function<void(std::size_t, std::size_t)>& progress) {
  const Shard shard = parse_shard("--shard", shard_text);
  ShardRun r;
  r.part = dir / "parts" / (part_name(shard) + ".json");
  if (std::filesystem::exists(r.part)) {
    r.skipped = true;
    return r;
  }
  const Scene scene = plan_scene(plan, dir / "plan.json");
  const auto start = std::chrono::steady_clock::now();
  const std::vector<std::size_t> runs = shard_runs(plan.runs(), shard);
  StudyResults results;
  run_plan(plan, scene, runs, threads, progress, results);
  if (interrupted()) throw Interrupted();
  nlohmann::ordered_json j = part_json(plan, results, runs);
  j["shard"] = shard_text;
  j["threads"] = threads;
  r.wall_s = seconds_since(start);
  j["wall_time_s"] = r.wall_s;
  std::filesystem::create_directories(r.part.parent_path());
  write_file_atomically(r.part, j.dump() + "\n");
  r.runs = runs.size();
  return r;
}

MergedStudy merge_study_parts(const StudyPlan& plan, const std::filesystem::path& dir,
                              const std::filesystem::path& output) {
  const std::filesystem::path plan_file = dir / "plan.json";
  const Scene scene = plan_scene(plan, plan_file);  // an input changed: said first
  std::vector<std::filesystem::path> inputs = {plan_file, dir / "parts"};
  for (const auto& f : scene_inputs(scene, false)) inputs.push_back(f);
  const MergedParts merged = merge_parts(plan, scene, dir);
  OutputFolder out(output, "study", inputs);
  std::vector<std::string> warnings =
      write_study(plan, scene, merged.results, merged.threads, merged.wall_s, out.path());
  out.commit();
  return {out.final_path(), merged.parts.size(), scene.name, std::move(warnings)};
}

}  // namespace shpb
