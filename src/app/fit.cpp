// shpb fit CAMPAIGN.json -o DIR: calibrate a specimen law from measured tests (docs/methods.md §9):
// the campaign read and checked (fit/fit_run.hpp prepare_fit: all input errors before anything is
// written), the stages run (run_fit), the files written (fit/fit_report.hpp).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>

#include "app/cli_options.hpp"
#include "app/commands.hpp"
#include "core/output_folder.hpp"
#include "fit/fit_report.hpp"
#include "fit/fit_run.hpp"

namespace shpb {
namespace {

FitOptions fit_options(const FitArgs& args) {
  FitOptions o = args.options;
  if (!args.quiet)
    o.progress = [](const std::string& l) { std::fprintf(stderr, "fit: %s\n", l.c_str()); };
  return o;
}

void print_outcome(const FitRun& run, const OutputFolder& out) {
  for (const auto& w : run.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  for (std::size_t k = 0; k < run.cases.size(); ++k) {
    const auto cb = run.cases[k]->compare(run.before[k]), ca = run.cases[k]->compare(run.after[k]);
    for (std::size_t i = 0; i < cb.size(); ++i)
      std::fprintf(stderr, "%-16s %-12s NRMSE %.3f -> %.3f\n", run.cases[k]->name().c_str(),
                   cb[i].pulse.c_str(), cb[i].nrmse, ca[i].nrmse);
  }
  std::fprintf(stderr, "fit: %ld simulations, %.1f s (processor %.1f s); wrote %s\n",
               run.simulations, seconds_since(run.started), cpu_seconds(),
               out.final_path().string().c_str());
}

}  // namespace

int run_fit(const FitArgs& args) {
  require_valid(args);
  const FitOptions options = fit_options(args);
  FitRun run = prepare_fit(args.campaign, options);
  // Every input checked: from here on results are written (never into a folder that holds one).
  OutputFolder out(args.output, "fit", fit_inputs(run));
  if (options.progress)
    options.progress("campaign " + run.campaign.display + ": " + std::to_string(run.cases.size()) +
                     " test(s), " + std::to_string(run.unknowns.size()) + " unknown(s), " +
                     std::to_string(run.threads) + " thread(s)");
  run_fit(run, options);
  write_fit_outputs(run, out.path());
  out.commit();
  if (!args.quiet) print_outcome(run, out);
  return 0;
}

Command add_fit_command(CLI::App& app) {
  auto args = std::make_shared<FitArgs>();
  auto* cmd = app.add_subcommand(
      "fit",
      "Calibrate a specimen law from measured tests (a campaign file): fit the processed "
      "curves, then the simulated gauge signals; write fit.json (a material file), "
      "summary.json, curves.csv, signals.csv");
  cmd->add_option("campaign", args->campaign, "Campaign JSON file (tests, material, free, ...)")
      ->required();
  cmd->add_option("-o,--output", args->output, "Output folder (replaced atomically)")->required();
  add_threads_option(cmd, args->options.threads, "Simulations in parallel (0 = all cores)");
  cmd->add_option(
      "--max-iterations", args->options.max_iterations,
      "Solver iterations per stage (default " + std::to_string(FitOptions{}.max_iterations) + ")");
  cmd->add_option("--relative-step", args->options.relative_step,
                  "Central-difference step of the signals stage, relative to each parameter "
                  "(default 0.05: above the simulator's noise; the curve stage uses 1e-4)");
  cmd->add_option("--bootstrap", args->options.bootstrap,
                  "Refits of the parametric bootstrap that checks each parameter's interval "
                  "(default " +
                      std::to_string(FitOptions{}.bootstrap) + "; 0: linearised intervals only)");
  // The ranges: FitOptions::IsValid (run_fit, before anything), the Python module's check too.
  add_seed_option(cmd, args->options.seed, "Seed of the bootstrap's noise draws (default 1)");
  cmd->add_flag("--quiet,-q", args->quiet, "No progress output on stderr");
  return {cmd, [args] { return run_fit(*args); }};
}

}  // namespace shpb
