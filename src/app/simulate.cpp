// shpb simulate SCENE.json -o DIR: read and validate the scene (exit 2 before anything is
// written), run it, write the files of docs/outputs.md atomically. An instability is exit 3 with
// what was computed until then and a summary saying where and when (still written atomically).
#include <cstdio>
#include <memory>
#include <new>

#include "app/cli_options.hpp"
#include "app/commands.hpp"
#include "app/progress.hpp"
#include "core/error.hpp"
#include "core/output_folder.hpp"
#include "model/discretization.hpp"
#include "solver/simulation.hpp"

namespace shpb {

int run_simulate(const SimulateArgs& args) {
  Scene scene = read_scene(args.scene);  // InputError → exit 2, nothing written
  apply_overrides(args.overrides, scene);
  OutputFolder out(args.output, "simulate", scene_inputs(scene, false));  // measured files unread
  SimulationOptions options;
  options.full_model = args.full_model;
  if (!args.overrides.quiet) {
    options.progress = ProgressPrinter("simulating");
    options.repeating = [](const std::string& why) {
      std::fprintf(stderr, "simulating: %s\n", why.c_str());
    };
  }
  options.cancel = [] { return interrupted(); };
  SimulationResult result;
  try {
    result = simulate(scene, options);
    write_simulation_outputs(result, scene, out.path());
  } catch (const std::bad_alloc&) {  // the estimate fitted the limits, the machine did not
    char mb[32];
    std::snprintf(mb, sizeof mb, "%.3g MB", discretize(scene).memory_estimate_bytes / 1e6);
    throw NumericalError("out of memory: " + args.scene.string() + ": the run needs about " + mb +
                         " (estimate) and this machine could not give it");
  }
  out.commit();
  for (const auto& w : result.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  if (!result.stable) {
    std::fprintf(stderr, "error: %s: %s (outputs up to then written to %s)\n",
                 args.scene.string().c_str(), result.failure.c_str(),
                 out.final_path().string().c_str());
    return 3;
  }
  if (!args.overrides.quiet)
    std::fprintf(stderr,
                 "simulated %s in %.3g s (%lld node updates, energy error %.3g); wrote %s\n",
                 scene.name.c_str(), result.wall_time_s, result.node_updates, result.energy_error,
                 out.final_path().string().c_str());
  return 0;
}

Command add_simulate_command(CLI::App& app) {
  struct Options {
    SimulateArgs args;
    RunOptionText run;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("simulate",
                                 "Run a scene; write gauges.csv, interfaces.csv, "
                                 "specimen.csv, energy.csv, field.csv, summary.json");
  cmd->add_option("scene", o->args.scene, "Scene JSON file")->required();
  cmd->add_option("-o,--output", o->args.output, "Output folder (replaced atomically)")->required();
  cmd->add_flag("--full-model", o->args.full_model,
                "Update every node of every bar from the start (no causal economy)");
  add_run_options(cmd, o->args.overrides, o->run);
  return {cmd, [o] {
            resolve_run_options(o->args.overrides, o->run);
            return run_simulate(o->args);
          }};
}

}  // namespace shpb
