// shpb — a virtual Split-Hopkinson pressure bar laboratory. This file is only the command line:
// CLI11 subcommands (docs/commands.md) that call one function each in app/.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "core/csv_writer.hpp"
#include "core/enum_names.hpp"
#include "core/error.hpp"
#include "core/output_folder.hpp"
#include "core/units.hpp"
#include "model/discretization.hpp"
#include "model/scene.hpp"
#include "version.hpp"

namespace {

using namespace shpb;

// "a | b | c" of an option's choices.
std::string alternatives(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& n : names) text += (text.empty() ? "" : " | ") + n;
  return text;
}

// --contact/--stepping/--courant/--tolerance/--threads/--quiet for simulate, compare, study and
// validate. The choices are the enums' own name tables (core/enum_names.hpp); `bonded` is a scene
// key only.
void add_run_options(CLI::App* cmd, RunOverrides& o, std::string& contact, std::string& stepping,
                     std::string& tolerance) {
  std::vector<std::string> methods = enum_names(kContactMethodNames);
  std::erase(methods, std::string(to_string(ContactMethod::kBonded)));
  const std::vector<std::string> steppings = enum_names(kSteppingNames);
  cmd->add_option("--contact", contact,
                  "Contact method at every interface: " + alternatives(methods) +
                      " (default: the scene's, else " +
                      std::string(to_string(ContactSpec{}.method)) + ")")
      ->check(CLI::IsMember(methods));
  cmd->add_option("--stepping", stepping,
                  alternatives(steppings) +
                      ": every bar its own time step, or all bars at the smallest step (default: "
                      "the scene's, else " +
                      std::string(to_string(SimulationSpec{}.stepping)) + ")")
      ->check(CLI::IsMember(steppings));
  // Its range, (0, 1] as in the scene, is checked with the scene (model/scene_validation.hpp).
  cmd->add_option("--courant", o.courant,
                  "Courant number of every bar, c·Δt/h, in (0, 1] (default: the scene's, else " +
                      format_double(kDefaultCourant) + ")");
  // Its range, (0 %, 100 %) as in the scene, is checked with the scene
  // (model/scene_validation.hpp).
  cmd->add_option("--tolerance", tolerance,
                  "Gauge error accepted, e.g. \"1 %\": every bar meshed as coarsely as the error "
                  "model predicts meets it (default: the scene's simulation.tolerance, else the "
                  "automatic meshes)");
  cmd->add_option("--threads", o.threads, "Worker threads (0 = all cores)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--quiet,-q", o.quiet, "No progress output on stderr");
}

void resolve_run_options(RunOverrides& o, const std::string& contact, const std::string& stepping,
                         const std::string& tolerance) {
  if (!contact.empty()) o.contact = contact_method_from_string(contact);
  if (!stepping.empty()) o.stepping = stepping_from_string(stepping);
  if (!tolerance.empty()) try {
      o.tolerance = parse_quantity(tolerance, Dimension::kDimensionless);
    } catch (const std::invalid_argument&) {
      throw input_error("--tolerance", "", "\"" + tolerance + "\"",
                        "expected a gauge error such as \"1 %\"");
    }
}

double quantity_option(const std::string& option, const std::string& text, Dimension d) {
  try {
    return parse_quantity(text, d);
  } catch (const std::invalid_argument& e) {
    throw input_error(option, "", "\"" + text + "\"", e.what());
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "shpb — virtual Split-Hopkinson pressure bar laboratory: simulate a Kolsky bar test from one "
      "JSON scene, record strain gauges, correct Pochhammer–Chree dispersion and reduce gauge "
      "signals (simulated or measured) to specimen stress–strain curves."};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("shpb ") + kVersion);
  std::string contact, stepping, tolerance;

  SimulateArgs sim;
  auto* simulate = app.add_subcommand("simulate",
                                      "Run a scene; write gauges.csv, interfaces.csv, "
                                      "specimen.csv, energy.csv, field.csv, summary.json");
  simulate->add_option("scene", sim.scene, "Scene JSON file")->required();
  simulate->add_option("-o,--output", sim.output, "Output folder (replaced atomically)")
      ->required();
  simulate->add_flag("--full-model", sim.full_model,
                     "Update every node of every bar from the start (no causal economy)");
  add_run_options(simulate, sim.overrides, contact, stepping, tolerance);

  ProcessArgs proc;
  std::string signals;
  auto* process = app.add_subcommand(
      "process",
      "Reduce gauge signals (the scene's measurement, or --signals) to aligned pulses "
      "and 1/2/3-wave stress–strain curves; write pulses.csv, curve.csv, summary.json");
  CampaignArgs campaign;
  std::vector<std::string> process_scenes;
  std::string campaign_file;
  process->add_option("scene", process_scenes,
                      "Scene JSON file (bars, gauges, specimen, measurement); several: a "
                      "campaign, one folder per test and campaign.csv");
  process->add_option("--campaign", campaign_file,
                      "Campaign file (tests[]: {scene, name}) instead of scenes: one folder per "
                      "test and campaign.csv");
  process
      ->add_option("--flow-stress-at", campaign.flow_strains,
                   "Campaigns: engineering strains at which campaign.csv gives the flow "
                   "stress, e.g. 0.02,0.05")
      ->delimiter(',');
  process->add_option("--shard", campaign.shard,
                      "Campaigns: process every N-th test from K into DIR/parts/K-of-N (K/N)");
  process->add_flag("--merge", campaign.merge,
                    "Campaigns: check DIR/parts holds every test once; write DIR/result");
  process->add_option("-o,--output", proc.output, "Output folder (replaced atomically)")
      ->required();
  process->add_option("--signals", signals,
                      "Gauge signals to process instead of the scene's measurement, e.g. a "
                      "gauges.csv written by `shpb simulate`");
  process->add_flag("--quiet,-q", proc.quiet, "No progress output on stderr");

  CompareArgs cmp;
  std::string striker_velocity;
  bool no_dispersion = false;
  auto* compare = app.add_subcommand(
      "compare",
      "Simulate the scene and compare its gauge signals with the measured ones, pulse "
      "by pulse; write comparison.csv and summary.json");
  compare->add_option("scene", cmp.scene, "Scene JSON file with a measurement")->required();
  compare->add_option("-o,--output", cmp.output, "Output folder (replaced atomically)")->required();
  compare->add_flag("--no-dispersion", no_dispersion,
                    "Do not propagate simulated pulses through Pochhammer–Chree dispersion");
  compare->add_option("--striker-velocity", striker_velocity,
                      "Striker velocity, e.g. \"22 m/s\" (default: the scene's "
                      "measurement.striker_velocity, else inferred from the measured incident "
                      "plateau; summary.json says which)");
  add_run_options(compare, cmp.overrides, contact, stepping, tolerance);

  DispersionArgs disp;
  std::string radius, c0;
  auto* dispersion = app.add_subcommand(
      "dispersion",
      "Print or write the first-mode Pochhammer–Chree curve of a solid round bar: "
      "a_over_lambda,c_over_c0,cg_over_c0,f_a_over_c0[,frequency_Hz]");
  dispersion->add_option("--poisson", disp.poisson, "Poisson ratio of the bar, in [0, 0.49]")
      ->required();  // its range checked by run_dispersion (dispersion/pochhammer_chree.hpp)
  dispersion
      ->add_option("--a-over-lambda", disp.a_over_lambda,
                   "Explicit list of radius/wavelength values")
      ->delimiter(',');
  dispersion
      ->add_option("--max-a-over-lambda", disp.max_a_over_lambda,
                   "Largest a/Λ of an evenly spaced table (default 1.6)")
      ->check(CLI::PositiveNumber);
  dispersion->add_option("--points", disp.points, "Number of table points (default 321)")
      ->check(CLI::Range(2, 1000000));
  dispersion->add_option("--radius", radius, "Bar radius, e.g. \"9.525 mm\" (adds frequency_Hz)");
  dispersion->add_option("--c0", c0, "Bar wave speed sqrt(E/ρ), e.g. \"4975 m/s\"");
  dispersion->add_option("-o,--output", disp.output, "CSV file to write (default: stdout)");

  StudyArgs study;
  auto* study_cmd = app.add_subcommand(
      "study",
      "Sweep contact methods, steppings, resolutions and penalty parameters: accuracy "
      "against cost (pareto.csv) and stability maps (stability.csv)");
  study_cmd->add_option("scene", study.scene, "Scene JSON file (not with --run/--merge)");
  study_cmd->add_option("-o,--output", study.output,
                        "Output folder (replaced atomically); with --merge default DIR/result");
  std::string sweep;
  const std::vector<std::string> sweeps = enum_names(kSweepNames);
  study_cmd
      ->add_option("--sweep", sweep,
                   alternatives(sweeps) + " (default " + to_string(StudyArgs{}.sweep) + ")")
      ->check(CLI::IsMember(sweeps));
  study_cmd
      ->add_option("--refine", study.refine,
                   "Stability map: refine-1 more points between neighbours on the stiffness "
                   "and Courant axes (2: about 4 x the points; default 1)")
      ->check(CLI::Range(1, 64));
  study_cmd->add_option("--plan", study.plan,
                        "Write the sweep's independent runs into DIR/plan.json instead of running "
                        "them (then --run DIR --shard K/N, then --merge DIR)");
  study_cmd->add_option("--run", study.run,
                        "Run shard --shard K/N of DIR's plan; writes DIR/parts/K-of-N.json "
                        "atomically (an existing part is skipped)");
  study_cmd->add_option("--shard", study.shard,
                        "K/N: every N-th run of the plan from K (K from 0)");
  study_cmd->add_option("--merge", study.merge,
                        "Check DIR's parts (each run exactly once) and write the outputs of the "
                        "whole sweep into -o (default DIR/result)");
  add_run_options(study_cmd, study.overrides, contact, stepping, tolerance);

  ValidateArgs val;
  auto* validate = app.add_subcommand(
      "validate",
      "Check a scene and print the resolved set-up (materials, meshes, time steps, "
      "Courant numbers, gauges, interfaces) without running it");
  validate->add_option("scene", val.scene, "Scene JSON file")->required();
  validate->add_flag("--json", val.json, "Print the resolved set-up as JSON");
  add_run_options(validate, val.overrides, contact, stepping, tolerance);

  ReportArgs rep;
  auto* report = app.add_subcommand(
      "report",
      "Turn an output folder of simulate/process/compare/study into PNG figures and one "
      "self-contained report.html (needs python3 with matplotlib)");
  report->add_option("folder", rep.folder, "Output folder")
      ->required()
      ->check(CLI::ExistingDirectory);

  FitArgs fit;
  auto* fit_cmd = app.add_subcommand(
      "fit",
      "Calibrate a specimen law from measured tests (a campaign file): fit the processed "
      "curves, then the simulated gauge signals; write fit.json (a material file), "
      "summary.json, curves.csv, signals.csv");
  fit_cmd->add_option("campaign", fit.campaign, "Campaign JSON file (tests, material, free, ...)")
      ->required();
  fit_cmd->add_option("-o,--output", fit.output, "Output folder (replaced atomically)")->required();
  fit_cmd->add_option("--threads", fit.threads, "Simulations in parallel (0 = all cores)")
      ->check(CLI::NonNegativeNumber);
  fit_cmd
      ->add_option(
          "--max-iterations", fit.max_iterations,
          "Solver iterations per stage (default " + std::to_string(FitArgs{}.max_iterations) + ")")
      ->check(CLI::Range(1, 10000));
  fit_cmd
      ->add_option("--relative-step", fit.relative_step,
                   "Central-difference step of the signals stage, relative to each parameter "
                   "(default 0.05: above the simulator's noise; the curve stage uses 1e-4)")
      ->check(CLI::Range(1e-8, 0.1));
  fit_cmd->add_flag("--quiet,-q", fit.quiet, "No progress output on stderr");

  auto* calibrate = add_calibrate_command(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "error: %s (see shpb --help)\n", e.what());
    return 2;
  }

  install_interrupt_handlers();
  try {
    if (*simulate) {
      resolve_run_options(sim.overrides, contact, stepping, tolerance);
      return run_simulate(sim);
    }
    if (*process) {
      const bool several = process_scenes.size() != 1 || !campaign_file.empty() ||
                           !campaign.shard.empty() || campaign.merge ||
                           !campaign.flow_strains.empty();
      if (several) {
        if (!signals.empty())
          throw input_error("--signals", "", "", "processes one scene: not with a campaign");
        for (const auto& s : process_scenes) campaign.scenes.push_back(s);
        if (!campaign_file.empty()) campaign.campaign = campaign_file;
        campaign.output = proc.output;
        campaign.quiet = proc.quiet;
        return run_process_campaign(campaign);
      }
      proc.scene = process_scenes.front();
      if (!signals.empty()) proc.signals = signals;
      return run_process(proc);
    }
    if (*compare) {
      resolve_run_options(cmp.overrides, contact, stepping, tolerance);
      cmp.dispersion = !no_dispersion;
      if (!striker_velocity.empty())
        cmp.striker_velocity =
            quantity_option("--striker-velocity", striker_velocity, Dimension::kVelocity);
      return run_compare(cmp);
    }
    if (*dispersion) {
      if (!radius.empty()) disp.radius_m = quantity_option("--radius", radius, Dimension::kLength);
      if (!c0.empty()) disp.c0_m_s = quantity_option("--c0", c0, Dimension::kVelocity);
      return run_dispersion(disp);
    }
    if (*study_cmd) {
      resolve_run_options(study.overrides, contact, stepping, tolerance);
      if (!sweep.empty()) study.sweep = *enum_value(kSweepNames, sweep);
      return run_study(study);
    }
    if (*validate) {
      resolve_run_options(val.overrides, contact, stepping, tolerance);
      return run_validate(val);
    }
    if (*report) return run_report(rep);
    if (*fit_cmd) return run_fit(fit);
    if (*calibrate) return run_calibrate_command();
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const NumericalError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 3;
  } catch (const WriteError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 3;
  } catch (const std::bad_alloc&) {
    // The estimate (validate) was passed but the machine could not give the memory: a failed
    // run, not an internal error.
    std::fprintf(stderr,
                 "error: out of memory: the run needs more memory than this machine could give; "
                 "`shpb validate` prints the estimate (coarser mesh, shorter duration or lower "
                 "sample rate reduce it)\n");
    return 3;
  } catch (const Interrupted&) {
    std::fprintf(stderr, "error: interrupted; previous results left intact\n");
    return 130;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: internal: %s\n", e.what());
    return 4;
  }
  return 2;
}
