// shpb study SCENE.json -o DIR --sweep pareto|stability: accuracy against cost of every
// contact method × stepping × mesh resolution (pareto.csv), or the stability map of the contact
// methods over penalty stiffness, Courant number and mass ratio (stability.csv,
// stability_boundary.csv); summary.json says what was compared with what. Written atomically.
// The sweep is a plan of independent runs: run here on threads, or planned into a folder
// (--plan), run there shard by shard on other machines (--run DIR --shard K/N) and merged
// (--merge); one code path, so a merged study equals an in-process one apart from wall times.
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>

#include "app/cli_options.hpp"
#include "app/commands.hpp"
#include "app/progress.hpp"
#include "core/clock.hpp"
#include "core/error.hpp"
#include "core/output_folder.hpp"
#include "core/parallel_runner.hpp"
#include "core/shards.hpp"
#include "study/study_report.hpp"
#include "study/study_run.hpp"

namespace shpb {
namespace {

// "done/total runs" on stderr (app/progress.hpp).
std::function<void(std::size_t, std::size_t)> progress_printer(bool quiet, std::string what) {
  if (quiet) return {};
  return [print = ProgressPrinter("study " + what)](std::size_t done, std::size_t total) mutable {
    print(static_cast<double>(done) / static_cast<double>(total),
          std::to_string(done) + "/" + std::to_string(total) + " runs");
  };
}

StudyOptions study_options(const StudyArgs& args) {
  StudyOptions o{args.chosen_sweep(), args.overrides.contact, args.overrides.stepping,
                 args.overrides.courant, args.refine};
  o.distributions = args.distributions;
  if (args.draws) o.draws = *args.draws;
  if (args.seed) o.seed = *args.seed;
  return o;
}

// shpb study SCENE --plan DIR: DIR/plan.json, nothing run.
int plan_study(const StudyArgs& args) {
  require_new_plan_folder(*args.plan);
  if (args.overrides.tolerance)  // the plan re-applies only the scene's own tolerance
    throw input_error("--tolerance", "", "",
                      "not with --plan: give simulation.tolerance in the scene");
  Scene scene = read_scene(args.scene);
  apply_overrides(study_overrides(args.overrides), scene);
  const StudyPlan plan = write_study_plan(args.scene, scene, study_options(args), *args.plan);
  const std::string dir = args.plan->string();
  if (!args.overrides.quiet)
    std::fprintf(stderr,
                 "study %s of %s: %zu runs planned in %s; next: shpb study --run %s --shard K/N, "
                 "then shpb study --merge %s\n",
                 to_string(plan.sweep).c_str(), scene.name.c_str(), plan.runs(), dir.c_str(),
                 dir.c_str(), dir.c_str());
  return 0;
}

// shpb study --run DIR --shard K/N: DIR/parts/K-of-N.json.
int run_study_shard(const StudyArgs& args) {
  if (args.shard.empty()) throw input_error("--shard", "", "", "K/N is needed with --run DIR");
  parse_shard("--shard", args.shard);  // a bad K/N is said before the plan is read
  const StudyPlan plan = read_study_plan(*args.run / "plan.json");
  const int threads = resolve_threads(args.overrides.threads);
  const ShardRun r = run_study_shard(plan, *args.run, args.shard, threads,
                                     progress_printer(args.overrides.quiet, to_string(plan.sweep)));
  if (args.overrides.quiet) return 0;
  if (r.skipped)
    std::fprintf(stderr, "study: %s exists, shard skipped\n", r.part.string().c_str());
  else
    std::fprintf(stderr, "study %s shard %s: %zu runs in %.3g s on %d threads; wrote %s\n",
                 to_string(plan.sweep).c_str(), args.shard.c_str(), r.runs, r.wall_s, threads,
                 r.part.string().c_str());
  return 0;
}

// shpb study --merge DIR [-o OUT]: the whole study from DIR's parts.
int merge_study(const StudyArgs& args) {
  const StudyPlan plan = read_study_plan(*args.merge / "plan.json");
  const MergedStudy m = merge_study_parts(
      plan, *args.merge, args.output.empty() ? *args.merge / "result" : args.output);
  if (args.overrides.warnings_on_stderr)  // else returned (the Python module's result.warnings)
    for (const auto& w : m.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  if (!args.overrides.quiet)
    std::fprintf(stderr, "study %s of %s: merged %zu parts (%zu runs); wrote %s\n",
                 to_string(plan.sweep).c_str(), m.scene_name.c_str(), m.parts, plan.runs(),
                 m.folder.string().c_str());
  return 0;
}

}  // namespace

std::vector<std::filesystem::path> study_inputs(const Scene& scene,
                                                const std::filesystem::path& distributions) {
  std::vector<std::filesystem::path> inputs = scene_inputs(scene, false);  // measured files unread
  if (!distributions.empty()) inputs.push_back(distributions);
  return inputs;
}

int run_study(const StudyArgs& args) {
  require_valid(args);
  if (args.run) return run_study_shard(args);
  if (args.merge) return merge_study(args);
  if (args.plan) return plan_study(args);

  Scene scene = read_scene(args.scene);  // InputError → exit 2, nothing written
  apply_overrides(study_overrides(args.overrides), scene);
  const auto start = std::chrono::steady_clock::now();
  const StudyPlan plan =
      make_study_plan(study_options(args), scene);  // a bad file: nothing written
  OutputFolder out(args.output, "study", study_inputs(scene, args.distributions));
  const int threads = resolve_threads(args.overrides.threads);
  StudyResults results;
  run_plan(plan, scene, all_runs(plan.runs()), threads,
           progress_printer(args.overrides.quiet, to_string(plan.sweep)), results);
  const std::vector<std::string> warnings =
      write_study(plan, scene, results, threads, seconds_since(start), out.path());
  const double wall = seconds_since(start);
  out.commit();
  if (args.overrides.warnings_on_stderr)
    for (const auto& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  if (!args.overrides.quiet)
    std::fprintf(stderr, "study %s of %s in %.3g s on %d threads; wrote %s\n",
                 to_string(args.chosen_sweep()).c_str(), scene.name.c_str(), wall, threads,
                 out.final_path().string().c_str());
  return 0;
}

Command add_study_command(CLI::App& app) {
  struct Options {
    StudyArgs args;
    RunOptionText run;
    std::string sweep;
    std::uint64_t seed = 0;
  };
  auto o = std::make_shared<Options>();
  StudyArgs& study = o->args;
  auto* cmd = app.add_subcommand(
      "study",
      "Sweep contact methods, steppings, resolutions and penalty parameters: accuracy "
      "against cost (pareto.csv) and stability maps (stability.csv); or the Monte Carlo of a "
      "planned test over uncertain scene values (bands on the gauges and the curve)");
  cmd->add_option("scene", study.scene, "Scene JSON file (not with --run/--merge)");
  cmd->add_option("-o,--output", study.output,
                  "Output folder (replaced atomically); with --merge default DIR/result");
  const std::vector<std::string> sweeps = enum_names(kSweepNames);
  cmd->add_option(
      "--sweep", o->sweep,
      alternatives(sweeps) + " (default " + to_string(StudyArgs{}.chosen_sweep()) + ")");
  // Its choices (check_choice) and the ranges of --refine and --draws (StudyArgs::IsValid) are
  // checked as the Python module checks them: one message.
  cmd->add_option("--refine", study.refine,
                  "Stability map: refine-1 more points between neighbours on the stiffness "
                  "and Courant axes (2: about 4 x the points; default 1)");
  cmd->add_option("--distributions", study.distributions,
                  "Monte Carlo: JSON file of the scene values to draw and their distributions");
  cmd->add_option(
         "--draws", study.draws,
         "Monte Carlo: number of draws (default " + std::to_string(kDefaultMonteCarloDraws) + ")")
      ->check(unsigned_text_check());
  auto* seed = add_seed_option(
      cmd, o->seed, "Monte Carlo: seed of the draws (default 1: the same draws every run)");
  cmd->add_option("--plan", study.plan,
                  "Write the sweep's independent runs into DIR/plan.json instead of running "
                  "them (then --run DIR --shard K/N, then --merge DIR)");
  cmd->add_option("--run", study.run,
                  "Run shard --shard K/N of DIR's plan; writes DIR/parts/K-of-N.json "
                  "atomically (an existing part is skipped)");
  cmd->add_option("--shard", study.shard, "K/N: every N-th run of the plan from K (K from 0)");
  cmd->add_option("--merge", study.merge,
                  "Check DIR's parts (each run exactly once) and write the outputs of the "
                  "whole sweep into -o (default DIR/result)");
  add_run_options(cmd, study.overrides, o->run);
  return {cmd, [o, seed] {
            if (!o->sweep.empty()) {
              check_choice("--sweep", o->sweep, enum_names(kSweepNames));
              o->args.sweep = *enum_value(kSweepNames, o->sweep);
            }
            resolve_run_options(o->args.overrides, o->run);
            if (seed->count() > 0) o->args.seed = o->seed;
            return run_study(o->args);
          }};
}

}  // namespace shpb
