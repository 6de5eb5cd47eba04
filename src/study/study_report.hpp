#pragma once
// The files of `shpb study` (docs/outputs.md) from every run's result: pareto.csv and summary.json
// of a Pareto sweep; stability.csv, stability_boundary.csv and summary.json of a stability map.
#include <filesystem>

#include "model/scene.hpp"
#include "study/study_plan.hpp"

namespace shpb {

void write_study(const StudyPlan& plan, const Scene& scene, const StudyResults& results,
                 int threads, double wall_s, const std::filesystem::path& dir);

}  // namespace shpb
