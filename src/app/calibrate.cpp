// `shpb calibrate SCENE... -o DIR` (docs/commands.md): the bars' wave speeds, Poisson ratios,
// gauge positions and channel gains and delays fitted to calibration shots (fit/calibration.hpp);
// the files are written by fit/calibration_report.hpp.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "app/cli_options.hpp"
#include "app/commands.hpp"
#include "core/error.hpp"
#include "fit/calibration.hpp"
#include "fit/calibration_report.hpp"

namespace shpb {
namespace {

// The shots of `scenes`, and the files they read appended to `inputs`.
std::vector<CalibrationShot> read_shots(const std::vector<std::filesystem::path>& scenes,
                                        std::vector<std::filesystem::path>& inputs) {
  std::vector<CalibrationShot> shots;
  for (const auto& file : scenes) {
    shots.push_back({read_scene(file), file.string()});
    for (const auto& f : scene_inputs(shots.back().scene)) inputs.push_back(f);
  }
  return shots;
}

}  // namespace

std::vector<std::filesystem::path> calibrate_inputs(
    const std::vector<std::filesystem::path>& scenes) {
  std::vector<std::filesystem::path> inputs;
  read_shots(scenes, inputs);
  return inputs;
}

int run_calibrate(const CalibrateArgs& args) {
  require_valid(args);
  std::vector<std::filesystem::path> inputs;
  const std::vector<CalibrationShot> shots = read_shots(args.scenes, inputs);
  CalibrateOptions options;
  options.threads = args.threads;
  if (!args.quiet)
    options.progress = [](const std::string& line) {
      std::fprintf(stderr, "calibrate: %s\n", line.c_str());
    };
  CalibrationFit fit = calibrate_bars(shots, options);
  write_calibration_outputs(fit, args.output, inputs);
  if (args.warnings_on_stderr) {
    for (const auto& w : fit.undetermined) std::fprintf(stderr, "warning: %s\n", w.c_str());
    for (const auto& w : fit.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  }
  if (!args.quiet) {
    for (const auto& p : fit.parameters)
      std::fprintf(stderr, "calibrate: %-40s %.6g -> %.6g +- %s\n", p.name.c_str(), p.nominal,
                   p.value, p.sd ? std::to_string(*p.sd).c_str() : "(undetermined)");
    std::fprintf(stderr, "calibrate: -> %s\n", args.output.string().c_str());
  }
  return 0;
}

bool CalibrateArgs::IsValid(std::string* error) const {
  // No shot is nothing to fit (the solver aborted the process on it: a notebook's kernel died);
  // checked here, not by the option parser, so that the command and the module say one line.
  *error = scenes.empty()
               ? input_error("calibrate", "", "", "a scene file is needed (one a calibration shot)")
                     .what()
               : threads_problem(threads);
  return error->empty();
}

Command add_calibrate_command(CLI::App& app) {
  auto args = std::make_shared<CalibrateArgs>();
  auto* cmd = app.add_subcommand(
      "calibrate",
      "Fit the bars (wave speed, Poisson ratio), gauge positions and channel gains and delays to "
      "calibration shots (bars apart, bars together); write calibration.json, summary.json and "
      "shot-K.csv");
  cmd->add_option("scene", args->scenes,
                  "Scenes of calibration shots (no specimen; a measurement each)");
  cmd->add_option("-o,--output", args->output, "Output folder (replaced atomically)")->required();
  add_threads_option(cmd, args->threads, "Evaluations in parallel (0 = all cores)");
  cmd->add_flag("--quiet,-q", args->quiet, "No progress output on stderr");
  return {cmd, [args] { return run_calibrate(*args); }};
}

}  // namespace shpb
