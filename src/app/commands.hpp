#pragma once
// One function per subcommand (one file each in app/). Each returns the process exit code:
// 0 success, 2 bad input (InputError), 3 numerical failure (NumericalError). main() catches
// what escapes and maps it to these codes.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "model/scene.hpp"
#include "model/scene_validation.hpp"
#include "study/sweep.hpp"

namespace CLI {
class App;
}

namespace shpb {

// `shpb calibrate` (app/calibrate.cpp) registers its own subcommand and options; run the parsed
// command with run_calibrate_command().
CLI::App* add_calibrate_command(CLI::App& app);
int run_calibrate_command();

// Options shared by simulate, compare and study (docs/commands.md); unset means "as the scene
// says".
struct RunOverrides {
  std::optional<ContactMethod> contact;
  std::optional<Stepping> stepping;
  std::optional<double> courant;
  std::optional<double> tolerance;  // --tolerance: the gauge error accepted (a fraction)
  int threads = 0;                  // 0: all cores
  bool quiet = false;
};

// Applies --contact/--stepping/--courant/--tolerance to a scene read from file, then checks the
// result with resolve_scene() (model/scene_validation.hpp), the one validation every command
// shares (with a tolerance it also meshes the scene); returns the discretization the run will use.
// Throws InputError (exit 2).
ChainDiscretization apply_overrides(const RunOverrides& overrides, Scene& scene);

// The files a run of `scene` reads (the scene, its material files and, unless `measured_files` is
// false — simulate and study never open them — its measured signal files): the inputs each
// command declares to its output folder (core/output_folder.hpp) and records in plans and parts.
std::vector<std::filesystem::path> scene_inputs(const Scene& scene, bool measured_files = true);

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
};
int run_process(const ProcessArgs& args);

// `shpb process` over several tests (docs/commands.md): scenes or a campaign file; each test's
// folder by run_process, plus campaign.csv; --shard K/N and --merge as for `study`.
struct CampaignArgs {
  std::vector<std::filesystem::path> scenes;
  std::optional<std::filesystem::path> campaign;
  std::filesystem::path output;
  std::vector<double> flow_strains;  // engineering strains of the flow_stress_Pa_at_<e> columns
  std::string shard;                 // "K/N"
  bool merge = false;
  bool quiet = false;
};
int run_process_campaign(const CampaignArgs& args);

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
  std::vector<double> a_over_lambda;  // explicit list, or
  double max_a_over_lambda = 1.6;
  int points = 321;
  std::optional<double> radius_m;
  std::optional<double> c0_m_s;
  std::optional<std::filesystem::path> output;  // CSV file; stdout when absent
};
int run_dispersion(const DispersionArgs& args);

struct StudyArgs {
  std::filesystem::path scene;
  std::filesystem::path output;
  Sweep sweep = Sweep::kPareto;
  RunOverrides overrides;
  int refine = 1;  // stability grid refinement (study/sweep.hpp)
  // Plan, run, merge (docs/commands.md): at most one of the three.
  std::optional<std::filesystem::path> plan;   // write DIR/plan.json (needs the scene)
  std::optional<std::filesystem::path> run;    // run shard `shard` of DIR's plan
  std::optional<std::filesystem::path> merge;  // merge DIR's parts into -o (default DIR/result)
  std::string shard;                           // "K/N"
};
int run_study(const StudyArgs& args);

struct ValidateArgs {
  std::filesystem::path scene;
  bool json = false;
  RunOverrides overrides;
};
int run_validate(const ValidateArgs& args);

struct ReportArgs {
  std::filesystem::path folder;
};
int run_report(const ReportArgs& args);

struct FitArgs {
  std::filesystem::path campaign;
  std::filesystem::path output;
  int threads = 0;          // simulations of one Jacobian in parallel; 0: all cores
  int max_iterations = 40;  // per stage
  // Central-difference step of the signals stage, relative to each parameter: well above the
  // simulator's sensitivity noise (docs/methods.md §9; docs/validation.md (shpb fit) gives the
  // measurement).
  double relative_step = 0.05;
  bool quiet = false;
};
int run_fit(const FitArgs& args);

}  // namespace shpb
