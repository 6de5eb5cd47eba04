// shpb plan SCENE --rate R -o DIR: the set-up meeting a target rate (plan/plan_search.hpp).
#include <memory>

#include "app/cli_options.hpp"
#include "app/progress.hpp"
#include "core/output_folder.hpp"
#include "plan/plan_outputs.hpp"

namespace shpb {

Command add_plan_command(CLI::App& app) {
  struct Options {
    std::filesystem::path scene, output;
    std::string rate, strain = "0.15", search = "3 %", tolerance = "0.5 %";
    PlanOptions plan;
    bool quiet = false;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("plan",
                                 "Find the striker, shaper and specimen within the scene's "
                                 "plan bounds that meet a target strain rate");
  cmd->add_option("scene", o->scene, "Scene JSON file with a plan block")->required();
  cmd->add_option("-o,--output", o->output, "Output folder (replaced atomically)")->required();
  cmd->add_option("--rate", o->rate, "Target specimen strain rate, e.g. \"2500 1/s\"")->required();
  cmd->add_option("--strain", o->strain, "Engineering strain the test must reach (default 0.15)");
  cmd->add_option("--search-tolerance", o->search, "Gauge error of the search's runs (\"3 %\")");
  cmd->add_option("--tolerance", o->tolerance, "Gauge error of the verification run (\"0.5 %\")");
  add_threads_option(cmd, o->plan.threads, "Worker threads (0 = all cores)");
  cmd->add_flag("--quiet,-q", o->quiet, "No progress output on stderr");
  return {cmd, [o] {
            const PlanTargets targets{
                quantity_option("--rate", o->rate, Dimension::kStrainRate),
                quantity_option("--strain", o->strain, Dimension::kDimensionless)};
            require_valid(targets);
            o->plan.search_tolerance = tolerance_option("--search-tolerance", o->search);
            o->plan.verify_tolerance = tolerance_option("--tolerance", o->tolerance);
            const PlanInput input = read_plan_input(o->scene);  // exit 2 before anything is written
            OutputFolder out(o->output, "plan", scene_inputs(input.scene, false));
            if (!o->quiet) o->plan.progress = ProgressPrinter("planning");
            const PlanResult r = plan_test(input, targets, o->plan);
            if (!r.feasible) {  // nothing written
              std::fprintf(stderr, "error: %s: %s\n", o->scene.string().c_str(), r.binding.c_str());
              return 3;
            }
            write_plan_outputs(r, input, targets, o->plan, out.path(), out.final_path());
            out.commit();
            for (const std::string& w : plan_warnings(r, targets))
              std::fprintf(stderr, "warning: %s\n", w.c_str());
            if (!o->quiet)
              std::fprintf(stderr, "planned %s in %.3g s (%ld runs): %d change(s); wrote %s\n",
                           input.scene.name.c_str(), r.wall_time_s, r.simulations, r.changes,
                           out.final_path().string().c_str());
            return 0;
          }};
}

}  // namespace shpb
