#pragma once
// `shpb study` as a library: the plan of a sweep's independent runs (study/study_plan.hpp), its
// runs on threads (all of them, or one shard's), and the merge of the shards' parts.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/shards.hpp"
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
};

// The plan of the sweep the options ask for (ids and the scene's text filled in by the caller).
StudyPlan make_study_plan(const StudyOptions& options, const Scene& scene);
// The file's text, as read (the plan keeps the scene as planned).
std::string read_text(const std::filesystem::path& file);
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

}  // namespace shpb
