#pragma once
// A study as a plan of independent runs (docs/commands.md `shpb study --plan/--run/--merge`):
// plan.json names the scene (its absolute path and a copy of its text, so a changed scene is
// caught) and every run's parameters; a shard's part holds its runs' results. The in-process
// `shpb study` goes through the same jobs, results and assembly without the files.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "model/scene.hpp"
#include "study/monte_carlo_sweep.hpp"
#include "study/pareto_sweep.hpp"
#include "study/stability_sweep.hpp"

namespace shpb {

struct StudyPlan {
  std::string id;               // random; parts carry it so that parts of another plan are refused
  Sweep sweep{};                // pareto | stability (kSweepNames, study/sweep.hpp)
  std::filesystem::path scene;  // absolute
  std::string scene_text;       // the scene file as planned
  // Every file the runs read (the scene, its material files) with its digest when planned
  // (core/file_digest.hpp); runs and the merge refuse a plan whose inputs changed since.
  nlohmann::json inputs = nlohmann::json::array();
  // The options of the planning command that change the scene (applied to it again by every run).
  std::optional<ContactMethod> contact;
  std::optional<Stepping> stepping;
  std::optional<double> courant;
  int refine = 1;                       // of the stability grid (summary.json says it when > 1)
  std::vector<ParetoJob> pareto;        // sweep "pareto"
  std::vector<StabilityJob> stability;  // sweep "stability"
  // Sweep "monte-carlo": the distributions as read from their file (which the runs do not read
  // again: every run's drawn values are in the plan), the seed, and the runs (the nominal first).
  std::vector<Distribution> distributions;
  std::uint64_t seed = 0;
  std::vector<MonteCarloJob> monte_carlo;

  std::size_t runs() const {
    return sweep == Sweep::kPareto      ? pareto.size()
           : sweep == Sweep::kStability ? stability.size()
                                        : monte_carlo.size();
  }
};

// Every run's result, by run index (only the runs of one shard filled in a part).
struct StudyResults {
  std::vector<ParetoJobResult> pareto;
  std::vector<StabilityJobResult> stability;
  std::vector<MonteCarloJobResult> monte_carlo;
};

// A fresh random plan id.
std::string new_plan_id();

// The text of DIR/plan.json, and the plan read back from it. Reading throws InputError naming
// the file for anything that is not a plan written by shpb.
std::string plan_text(const StudyPlan& plan);
StudyPlan read_study_plan(const std::filesystem::path& plan_file);

// The part of one shard: the plan id, the inputs' digests it ran with, the shard's own figures
// (threads, wall time) and the results of `runs`. Exact round trip of every double.
nlohmann::ordered_json part_json(const StudyPlan& plan, const StudyResults& results,
                                 const std::vector<std::size_t>& runs);
// Reads a part into `results` at its runs (which must be `expected`); throws InputError naming
// `file` on another plan's part, a part run on other inputs than the plan's, or a damaged one:
// gauge records whose columns, times and values disagree in size, a reference run without one.
void read_part(const nlohmann::json& part, const std::filesystem::path& file, const StudyPlan& plan,
               const std::vector<std::size_t>& expected, StudyResults& results);

}  // namespace shpb
