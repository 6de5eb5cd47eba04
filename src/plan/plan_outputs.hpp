#pragma once
// The files of `shpb plan` (docs/outputs.md#plan): the planned scene, summary.json with the
// recommended scope settings, the search's path, and the verification run's own files.
#include <filesystem>
#include <string>
#include <vector>

#include "plan/plan_search.hpp"

namespace shpb {

// What the lab should know of the chosen set-up beyond the criteria (summary.json `warnings`,
// printed by `shpb plan`): a mean rate over the whole loading more than the band off the target.
std::vector<std::string> plan_warnings(const PlanResult& result, const PlanTargets& targets);

// Writes into `dir` (the temporary folder of `final_dir`: the planned scene's material paths are
// made relative to `final_dir`); summary.json names the scene `scene_shown` (the file as given).
void write_plan_outputs(const PlanResult& result, const PlanInput& input,
                        const PlanTargets& targets, const PlanOptions& options,
                        const std::string& scene_shown, const std::filesystem::path& dir,
                        const std::filesystem::path& final_dir);

}  // namespace shpb
