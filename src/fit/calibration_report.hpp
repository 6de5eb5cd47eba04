#pragma once
// The output folder of `shpb calibrate` (docs/outputs.md), written atomically from a fit.
#include <filesystem>
#include <vector>

#include "fit/calibration.hpp"

namespace shpb {

// Writes calibration.json (with the fit's provenance), summary.json and shot-K.csv into `output`
// (core/output_folder.hpp: replaced atomically; `inputs` may not lie inside it).
void write_calibration_outputs(CalibrationFit& fit, const std::filesystem::path& output,
                               const std::vector<std::filesystem::path>& inputs);

}  // namespace shpb
