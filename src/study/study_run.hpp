#pragma once
// `shpb study` as a library: the plan of a sweep's independent runs (study/study_plan.hpp), its
// runs on threads (all of them, or one shard's), and the merge of the shards' parts.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/shards.hpp"
#include "model/run_overrides.hpp"
#include "model/scene.hpp"
#include "study/study_plan.hpp"

namespace shpb {

// The options of a sweep (docs/commands.md): a method or stepping given on the command line
// restricts the sweep to it.
struct StudyOptions {
  Sweep sweep = Sweep::kPareto;
  std::optional<ContactMethod> contact;
  std::optional<Stepping> stepping;
  std::optional<double> courant;
  int refine = 1;  // stability grid refinement (study/sweep.hpp)
  // Monte Carlo: the distributions file, the number of draws and their seed.
  std::filesystem::path distributions;
  std::size_t draws = kDefaultMonteCarloDraws;
  std::uint64_t seed = 1;
};

// The plan of the sweep the options ask for (ids and the scene's text filled in by the caller);
// InputError for a bad distributions file.
StudyPlan make_study_plan(const StudyOptions& options, const Scene& scene);
// The file's text, as read (the plan keeps the scene as planned).
std::string read_text(const std::filesystem::path& file);
// The command line's overrides as a study applies them: it sweeps multiples of the automatic
// meshes (its reference 8 x them) unless the scene or --tolerance asks for a tolerance, so the
// default tolerance does not move its grid.
RunOverrides study_overrides(RunOverrides o);
// The scene of a plan read from its folder: the same files (scene, materials), unchanged, with
// the same options. InputError when an input changed since the plan.
Scene plan_scene(const StudyPlan& plan, const std::filesystem::path& plan_file);
// Runs `runs` of the plan on `threads` workers, each result into its slot; `progress` (done,
// total) may be empty.
void run_plan(const StudyPlan& plan, const Scene& scene, const std::vector<std::size_t>& runs,
              int threads, const std::function<void(std::size_t, std::size_t)>& progress,
              StudyResults& results);
std::vector<std::size_t> all_runs(std::size_t n);

// The parts of a plan's folder, read and checked (each run exactly once, every gauge record with
// the scene's gauge columns): InputError naming the part to run again.
struct MergedParts {
  std::vector<Part> parts;
  StudyResults results;
  int threads = 0;    // the most threads a shard used
  double wall_s = 0;  // the shards' sum
};
MergedParts merge_parts(const StudyPlan& plan, const Scene& scene,
                        const std::filesystem::path& dir);

// A plan goes into a new or empty folder: InputError otherwise.
void require_new_plan_folder(const std::filesystem::path& dir);
// --plan DIR: the plan of `scene` (read from `scene_file`, run overrides applied) written into an
// empty or new DIR as DIR/plan.json with DIR/parts/, nothing run; InputError for a DIR in use.
StudyPlan write_study_plan(const std::filesystem::path& scene_file, const Scene& scene,
                           const StudyOptions& options, const std::filesystem::path& dir);

// --run DIR --shard K/N: the shard's runs of DIR's plan into DIR/parts/K-of-N.json, atomically; a
// part that exists is left as it is (`skipped`).
struct ShardRun {
  std::filesystem::path part;
  std::size_t runs = 0;
  double wall_s = 0;
  bool skipped = false;
};
ShardRun run_study_shard(const StudyPlan& plan, const std::filesystem::path& dir,
                         const std::string& shard_text, int threads,
                         const std::function<void(std::size_t, std::size_t)>& progress);

// --merge DIR [-o OUT]: the whole study from DIR's checked parts, written into `output` (the
// plan, its parts and the files they were computed from are its inputs); returns the folder.
struct MergedStudy {
  std::filesystem::path folder;
  std::size_t parts = 0;
  std::string scene_name;
  std::vector<std::string> warnings;  // write_study()'s
};
MergedStudy merge_study_parts(const StudyPlan& plan, const std::filesystem::path& dir,
                              const std::filesystem::path& output);

}  // namespace shpb
