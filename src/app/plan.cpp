// shpb plan SCENE --rate R [--strain E] -o DIR: the set-up that meets a target strain rate and
// strain within the scene's `plan` bounds (plan/plan_search.hpp); exit 3 naming what binds.
#include <cstdio>
#include <memory>

#include "app/cli_options.hpp"
#include "app/progress.hpp"
#include "core/error.hpp"
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
                                 "Search the striker, pulse shaper and specimen length within the "
                                 "scene's plan bounds for a target strain rate; write the planned "
                                 "scene, summary.json (scope settings), path.csv, simulation/");
  cmd->add_option("scene", o->scene, "Scene JSON file with a plan block")->required();
  cmd->add_option("-o,--output", o->output, "Output folder (replaced atomically)")->required();
  cmd->add_option("--rate", o->rate, "Target specimen strain rate, e.g. \"2500 1/s\"")->required();
  cmd->add_option("--strain", o->strain, "Engineering strain the test must reach (default 0.15)");
  cmd->add_option("--search-tolerance", o->search,
                  "Gauge error of the search's runs (default \"3 %\": coarse meshes)");
  cmd->add_option("--tolerance", o->tolerance,
                  "Gauge error of the chosen set-up's verification run (default \"0.5 %\")");
  cmd->add_option("--threads", o->plan.threads, "Worker threads (0 = all cores)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--quiet,-q", o->quiet, "No progress output on stderr");
  return {
      cmd, [o] {
        PlanTargets targets;
        targets.rate_1_s = quantity_option("--rate", o->rate, Dimension::kStrainRate);
        targets.strain = quantity_option("--strain", o->strain, Dimension::kDimensionless);
        if (!(targets.rate_1_s > 0)) throw input_error("--rate", "", o->rate, "must be > 0");
        if (!(targets.strain > 0 && targets.strain < 1))
          throw input_error("--strain", "", o->strain, "expected an engineering strain in (0, 1)");
        o->plan.search_tolerance = tolerance_option("--search-tolerance", o->search);
        o->plan.verify_tolerance = tolerance_option("--tolerance", o->tolerance);
        const PlanInput input = read_plan_input(o->scene);  // exit 2 before anything is written
        OutputFolder out(o->output, "plan", scene_inputs(input.scene, false));
        if (!o->quiet) o->plan.progress = ProgressPrinter("planning");
        const PlanResult r = plan_test(input, targets, o->plan);
        if (!r.feasible) {
          std::fprintf(stderr, "error: %s: no set-up within the plan's bounds meets %.4g 1/s: %s\n",
                       o->scene.string().c_str(), targets.rate_1_s, r.binding.c_str());
          return 3;  // nothing written: the output folder is dropped
        }
        write_plan_outputs(r, input, targets, o->plan, out.path(), out.final_path());
        out.commit();
        if (!o->quiet)
          std::fprintf(stderr,
                       "planned %s: striker %.4g m at %.4g m/s, %d change(s), %ld runs in %.3g s; "
                       "wrote %s\n",
                       input.scene.name.c_str(), r.chosen.striker_length_m,
                       r.chosen.striker_velocity_m_s, r.changes, r.simulations, r.wall_time_s,
                       out.final_path().string().c_str());
        return 0;
      }};
}

}  // namespace shpb
