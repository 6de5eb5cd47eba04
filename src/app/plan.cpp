// shpb plan SCENE --rate R -o DIR: the set-up meeting a target rate (plan/plan_search.hpp).
#include <cstdio>
#include <memory>

#include "app/cli_options.hpp"
#include "app/progress.hpp"
#include "core/output_folder.hpp"
#include "plan/plan_outputs.hpp"

namespace shpb {

PlannedTest prepare_plan(const PlanArgs& args) {
  require_valid(args.targets);
  require_valid(args.options);
  return {args.scene, read_plan_input(args.scene), args.targets, args.options, {}};
}

void search_plan(PlannedTest& plan) {
  plan.result = plan_test(plan.input, plan.targets, plan.options);
  if (!plan.result.feasible) throw NumericalError(plan.file.string() + ": " + plan.result.binding);
}

std::vector<std::filesystem::path> plan_inputs(const PlanInput& input) {
  return scene_inputs(input.scene, false);
}

void write_plan(const PlannedTest& plan, OutputFolder& out) {
  write_plan_outputs(plan.result, plan.input, plan.targets, plan.options, plan.file.string(),
                     out.path(), out.final_path());
  out.commit();
}

int run_plan(const PlanArgs& args) {
  PlannedTest plan = prepare_plan(args);  // exit 2 before anything is written
  OutputFolder out(args.output, "plan", plan_inputs(plan.input));
  if (!args.quiet) plan.options.progress = ProgressPrinter("planning");
  search_plan(plan);
  write_plan(plan, out);
  for (const std::string& w : plan_warnings(plan.result, plan.targets))
    std::fprintf(stderr, "warning: %s\n", w.c_str());
  if (!args.quiet)
    std::fprintf(stderr, "planned %s in %.3g s (%ld runs): %d change(s); wrote %s\n",
                 plan.input.scene.name.c_str(), plan.result.wall_time_s, plan.result.simulations,
                 plan.result.changes, out.final_path().string().c_str());
  return 0;
}

Command add_plan_command(CLI::App& app) {
  struct Options {
    PlanArgs args;
    std::string rate, strain = "0.15", search = "3 %", tolerance = "0.5 %";
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("plan",
                                 "Find the striker, shaper and specimen within the scene's "
                                 "plan bounds that meet a target strain rate");
  cmd->add_option("scene", o->args.scene, "Scene JSON file with a plan block")->required();
  cmd->add_option("-o,--output", o->args.output, "Output folder (replaced atomically)")->required();
  cmd->add_option("--rate", o->rate, "Target specimen strain rate, e.g. \"2500 1/s\"")->required();
  cmd->add_option("--strain", o->strain, "Engineering strain the test must reach (default 0.15)");
  cmd->add_option("--search-tolerance", o->search, "Gauge error of the search's runs (\"3 %\")");
  cmd->add_option("--tolerance", o->tolerance, "Gauge error of the verification run (\"0.5 %\")");
  add_threads_option(cmd, o->args.options.threads, "Worker threads (0 = all cores)");
  cmd->add_flag("--quiet,-q", o->args.quiet, "No progress output on stderr");
  return {cmd, [o] {
            PlanArgs& a = o->args;
            a.targets.rate_1_s = quantity_option("--rate", o->rate, Dimension::kStrainRate);
            a.targets.strain = quantity_option("--strain", o->strain, Dimension::kDimensionless);
            a.options.search_tolerance = tolerance_option("--search-tolerance", o->search);
            a.options.verify_tolerance = tolerance_option("--tolerance", o->tolerance);
            return run_plan(a);
          }};
}

}  // namespace shpb
