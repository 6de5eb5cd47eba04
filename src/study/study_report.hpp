#pragma once
// The files of `shpb study` (docs/outputs.md) from every run's result: pareto.csv and summary.json
// of a Pareto sweep; stability.csv, stability_boundary.csv and summary.json of a stability map.
#include <filesystem>
#include <string>
#include <vector>

#include "model/scene.hpp"
#include "study/study_plan.hpp"

namespace shpb {

// Returns the warnings to print on stderr (a Monte Carlo study's failed draws, a Pareto sweep of a
// scene whose every interface is bonded).
std::vector<std::string> write_study(const StudyPlan& plan, const Scene& scene,
                                     const StudyResults& results, int threads, double wall_s,
                                     const std::filesystem::path& dir);

}  // namespace shpb
