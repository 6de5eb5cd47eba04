#pragma once
// One file per subcommand in app/: it registers its options (add_<command>_command, called by
// main.cpp in the order of `shpb --help`) and runs it (run_<command>, also called by the Python
// module): options checked (IsValid), one library call that returns a result, the result written.
// Each run_<command> returns the process exit code: 0 success, 2 bad input (InputError), 3
// numerical failure (NumericalError). main() catches what escapes and maps it to these codes.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "analysis/uncertainty.hpp"
#include "core/options_check.hpp"
#include "fit/calibration.hpp"
#include "fit/fit_run.hpp"
#include "model/run_overrides.hpp"
#include "model/scene.hpp"
#include "model/scene_inputs.hpp"
#include "model/scene_validation.hpp"
#include "plan/plan_search.hpp"
#include "study/study_args.hpp"

namespace CLI {
class App;
}

namespace shpb {

class OutputFolder;

// A registered subcommand and what runs it once the command line is parsed.
struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
};
Command add_simulate_command(CLI::App& app);
Command add_process_command(CLI::App& app);
Command add_compare_command(CLI::App& app);
Command add_dispersion_command(CLI::App& app);
Command add_study_command(CLI::App& app);
Command add_validate_command(CLI::App& app);
Command add_report_command(CLI::App& app);
Command add_fit_command(CLI::App& app);
Command add_calibrate_command(CLI::App& app);
// app/plan.cpp (its options: plan/plan_search.hpp; --rate and --strain: plan/loading_metrics.hpp)
Command add_plan_command(CLI::App& app);
// Every subcommand, registered in the order of `shpb --help` (main.cpp; the documentation's check,
// tests/app/test_docs_complete.cpp).
std::vector<Command> add_commands(CLI::App& app);

struct SimulateArgs {
  std::filesystem::path scene;
  std::filesystem::path output;
  RunOverrides overrides;
  bool full_model = false;  // disable causal economy (docs/methods.md §7)
};
int run_simulate(const SimulateArgs& args);

struct ProcessArgs {
  std::filesystem::path scene;
  std::filesystem::path output;
  std::optional<std::filesystem::path> signals;  // a gauges.csv written by simulate, or a file
  bool quiet = false;
  MonteCarloOptions monte_carlo;  // --draws, --seed, --threads (measurement.uncertainty)
};
int run_process(const ProcessArgs& args);

struct CompareArgs {
  std::filesystem::path scene;
  std::filesystem::path output;
  RunOverrides overrides;
  bool dispersion = true;                  // propagate simulated pulses through Pochhammer–Chree
  std::optional<double> striker_velocity;  // else the scene's, or inferred from the measurement
};
int run_compare(const CompareArgs& args);

struct DispersionArgs {
  double poisson = 0.29;
  std::vector<double> a_over_lambda;  // explicit list, or an evenly spaced table (not both)
  std::optional<double> max_a_over_lambda;
  std::optional<int> points;
  std::optional<double> radius_m;
  std::optional<double> c0_m_s;
  std::optional<std::filesystem::path> output;  // CSV file; stdout when absent or "-"
};
int run_dispersion(const DispersionArgs& args);

int run_study(const StudyArgs& args);
// The files a study of `scene` reads (its output folder may hold none of them).
std::vector<std::filesystem::path> study_inputs(const Scene& scene,
                                                const std::filesystem::path& distributions);

struct ValidateArgs {
  std::filesystem::path scene;
  bool json = false;
  RunOverrides overrides;
};
int run_validate(const ValidateArgs& args);
// What `shpb validate --json` prints of `scene` (read and checked) run with `overrides`: the
// resolved set-up as JSON text (the Python module's validate returns it as a dict).
std::string validate_setup(Scene scene, const RunOverrides& overrides);

struct ReportArgs {
  std::filesystem::path folder;
  // The script's stderr collected here instead of printed (the Python module's report): its
  // `warning: ` lines' text, and its `error: ` line thrown as the command's exit code says
  // (InputError for 2, WriteError for 3).
  std::vector<std::string>* warnings = nullptr;
};
int run_report(const ReportArgs& args);

struct FitArgs {
  std::filesystem::path campaign;
  std::filesystem::path output;
  FitOptions options;  // fit/fit_run.hpp: threads, iterations, step, bootstrap and their defaults
  bool quiet = false;
  bool IsValid(std::string* error) const { return options.IsValid(error); }
};
int run_fit(const FitArgs& args);

struct CalibrateArgs {
  std::vector<std::filesystem::path> scenes;
  std::filesystem::path output;
  int threads = 0;
  bool quiet = false;
  bool warnings_on_stderr = true;          // the Python module returns them (result.warnings)
  bool IsValid(std::string* error) const;  // a shot at least, and --threads
};
int run_calibrate(const CalibrateArgs& args);
// The files a calibration of `scenes` reads (its output folder may hold none of them).
std::vector<std::filesystem::path> calibrate_inputs(
    const std::vector<std::filesystem::path>& scenes);

struct PlanArgs {
  std::filesystem::path scene;
  std::filesystem::path output;
  PlanTargets targets;  // --rate, --strain
  PlanOptions options;  // --search-tolerance, --tolerance, --threads
  bool quiet = false;
};
// A plan run: what it read, what it was asked and what it found.
struct PlannedTest {
  std::filesystem::path file;  // the scene as given (messages, summary.json's `scene`)
  PlanInput input;
  PlanTargets targets;
  PlanOptions options;
  PlanResult result;
};
// The options checked and the scene's plan read: InputError (exit 2) before anything is written.
PlannedTest prepare_plan(const PlanArgs& args);
// The search; NumericalError (exit 3, nothing written) naming the scene and the criterion its
// closest set-up misses most when no set-up within the bounds meets the targets.
void search_plan(PlannedTest& plan);
// The files a plan reads (its output folder may hold none of them).
std::vector<std::filesystem::path> plan_inputs(const PlanInput& input);
// The plan's files into `out` (scene.json's paths relative to its final folder), `out` committed.
void write_plan(const PlannedTest& plan, OutputFolder& out);
int run_plan(const PlanArgs& args);

}  // namespace shpb
