#pragma once
// `shpb process` in two halves, for callers that keep the result in memory (the Python module):
// process_scene() reads the signals and reduces them, writing nothing; write_process_outputs()
// writes the command's folder (docs/outputs.md) from that. run_process() is the two in sequence.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "analysis/gauge_signals.hpp"
#include "analysis/processing.hpp"
#include "analysis/test_processing.hpp"
#include "model/scene.hpp"

namespace shpb {

struct ProcessOutcome {
  MeasurementSpec measurement;  // what was read (the scene's, or the --signals file's columns)
  bool simulated = false;       // --signals: a gauges.csv of `shpb simulate`
  ProcessingOptions options;
  GaugeSignals signals;  // as read, in strain (raw_signals.csv)
  KolskySetup setup;
  ProcessingResult result;  // pulses.csv, curve.csv (rows up to result.loading_end)
  SpecimenCorrections corrections;
  CorrectionReport removed;
  std::vector<std::string> warnings;
  std::string failure;         // why the reduction cannot be reported (empty: it can)
  nlohmann::json calibration;  // the scene's calibration (model/calibration.hpp), or null
};

// Throws InputError for a scene that cannot be processed (no specimen: the command's
// bars-together check is not a reduction) and NumericalError for non-finite pulses.
ProcessOutcome process_scene(const Scene& scene,
                             const std::optional<std::filesystem::path>& signals_file,
                             bool print_warnings = true);
// curve.csv's columns in their order (docs/outputs.md): the primary reduction's rate, strain,
// stress and true values lead; rows up to result.loading_end.
using CurveColumn = std::pair<const char*, const std::vector<double>*>;
std::vector<CurveColumn> curve_columns(const ProcessOutcome& o);
// `scene_display` is the scene as named in summary.json. A failed reduction writes pulses.csv and
// the summary's error, then throws NumericalError, as the command does.
void write_process_outputs(const ProcessOutcome& o, const Scene& scene,
                           const std::string& scene_display, const std::filesystem::path& output);
nlohmann::json process_summary(const ProcessOutcome& o, const std::string& scene_display);

}  // namespace shpb
