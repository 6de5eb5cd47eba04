#pragma once
// The files of `shpb fit` (docs/outputs.md) from a finished fit/fit_run.hpp FitRun: fit.json (the
// starting material file with the fitted values), summary.json, curves.csv (the processed samples
// and the law at the start, after the curve stage, at the end) and signals.csv (measured, start
// and fitted strains in each compared window).
#include <filesystem>
#include <nlohmann/json.hpp>

#include "fit/fit_run.hpp"

namespace shpb {

nlohmann::json fit_material(const FitRun& run);
nlohmann::json fit_summary(const FitRun& run);
void write_fit_curves(const FitRun& run, const std::filesystem::path& file);
void write_fit_signals(const FitRun& run, const std::filesystem::path& file);
// All four into `dir`.
void write_fit_outputs(const FitRun& run, const std::filesystem::path& dir);

}  // namespace shpb
