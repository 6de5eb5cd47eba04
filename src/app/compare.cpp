// shpb compare SCENE.json -o DIR: simulate the scene and lay it over its measurement, pulse by
// pulse (analysis/compare_run.hpp: the plan, the comparison and its files). Writes
// comparison.csv, signals.csv (measured, simulated, simulated without dispersion, on the measured
// clock), summary.json, and the simulation's own files in simulation/.
#include <cstdio>
#include <filesystem>
#include <memory>

#include "analysis/compare_run.hpp"
#include "app/cli_options.hpp"
#include "app/commands.hpp"
#include "core/output_folder.hpp"
#include "solver/simulation.hpp"

namespace shpb {
namespace {

void print_outcome(bool dispersion, const ComparePlan& plan, const CompareOutcome& c,
                   const OutputFolder& out) {
  std::fprintf(stderr, "striker %.4g m/s (%s); dispersion %s\n", plan.velocity_m_s,
               plan.velocity_source.c_str(), dispersion ? "applied" : "off");
  for (const auto& r : c.results)
    std::fprintf(
        stderr,
        "%-12s %-12s shift %+7.2f us  peak ratio %.3f  plateau ratio %.3f  duration ratio %.3f  "
        "NRMSE %.3f  r %.3f\n",
        r.gauge.c_str(), r.pulse.c_str(), r.arrival_shift_s * 1e6, r.peak_ratio, r.plateau_ratio,
        r.duration_ratio, r.nrmse, r.correlation);
  std::fprintf(stderr, "wrote %s\n", out.final_path().string().c_str());
}

}  // namespace

int run_compare(const CompareArgs& args) {
  Scene scene = read_scene(args.scene);  // InputError → exit 2, nothing written
  apply_overrides(args.overrides, scene);
  const ComparePlan plan = plan_comparison(std::move(scene), args.striker_velocity);
  // Every input checked: from here on results are written.
  OutputFolder out(args.output, "compare", scene_inputs(plan.scene));
  SimulationOptions options;
  options.cancel = [] { return interrupted(); };
  const SimulationResult sim = simulate(plan.scene, options);
  std::filesystem::create_directories(out.path() / "simulation");
  write_simulation_outputs(sim, plan.scene, out.path() / "simulation");
  const SimulationFacts facts{sim.stable, sim.wall_time_s, sim.energy_error, sim.warnings};
  // The bars disperse as the measurement says (as `fit` lays the pulses over): a correction
  // "none" (signals of 1D bars, a simulated record) compares the 1D pulses, as --no-dispersion.
  const bool dispersion = args.dispersion && plan.scene.measurement->dispersion.correction;
  const CompareOutcome c = compare_simulation(plan, sim.gauges, dispersion, facts);
  write_comparison(plan, c, sim.gauges, dispersion, facts, out.path());
  out.commit();
  // What is implausible is said even with --quiet (which silences progress only).
  if (args.overrides.warnings_on_stderr)
    for (const auto& w : c.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  if (!sim.stable) {
    std::fprintf(stderr, "error: %s: %s (outputs up to then written to %s)\n",
                 plan.scene.file.string().c_str(), sim.failure.c_str(),
                 out.final_path().string().c_str());
    return 3;
  }
  if (!args.overrides.quiet) print_outcome(dispersion, plan, c, out);
  return 0;
}

Command add_compare_command(CLI::App& app) {
  struct Options {
    CompareArgs args;
    RunOptionText run;
    std::string striker_velocity;
    bool no_dispersion = false;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand(
      "compare",
      "Simulate the scene and compare its gauge signals with the measured ones, pulse "
      "by pulse; write comparison.csv, signals.csv, summary.json and the simulation's files in "
      "simulation/");
  cmd->add_option("scene", o->args.scene, "Scene JSON file with a measurement")->required();
  cmd->add_option("-o,--output", o->args.output, "Output folder (replaced atomically)")->required();
  cmd->add_flag("--no-dispersion", o->no_dispersion,
                "Do not propagate simulated pulses through Pochhammer–Chree dispersion");
  cmd->add_option("--striker-velocity", o->striker_velocity,
                  "Striker velocity, e.g. \"22 m/s\" (default: the scene's "
                  "measurement.striker_velocity, else inferred from the measured incident "
                  "plateau; summary.json says which)");
  add_run_options(cmd, o->args.overrides, o->run);
  return {cmd, [o] {
            resolve_run_options(o->args.overrides, o->run);
            o->args.dispersion = !o->no_dispersion;
            if (!o->striker_velocity.empty())
              o->args.striker_velocity =
                  quantity_option("--striker-velocity", o->striker_velocity, Dimension::kVelocity);
            return run_compare(o->args);
          }};
}

}  // namespace shpb
