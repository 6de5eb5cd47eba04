#pragma once
// `shpb process` as a library, for the command and for callers that keep the result in memory
// (the Python module): process_scene() reads the signals and reduces them, writing nothing;
// analysis/process_outputs.hpp writes the command's folder (docs/outputs.md) from its result.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "analysis/bar_check.hpp"
#include "analysis/gauge_signals.hpp"
#include "analysis/processing.hpp"
#include "analysis/test_processing.hpp"
#include "analysis/uncertainty.hpp"
#include "core/time_series.hpp"
#include "model/calibration.hpp"
#include "model/scene.hpp"

namespace shpb {

struct ProcessOutcome {
  MeasurementSpec measurement;  // what was read (the scene's, or the --signals file's columns)
  bool simulated = false;       // --signals: a gauges.csv of `shpb simulate`
  // How summary.json names the signals' file when it is not one to name: a simulation held in
  // memory, read through a temporary file (the Python module); empty: measurement.file.
  std::string signals_shown;
  ProcessingOptions options;
  GaugeSignals signals;  // as read, in strain (raw_signals.csv)
  KolskySetup setup;
  ProcessingResult result;  // pulses.csv, curve.csv (rows up to result.loading_end)
  SpecimenCorrections corrections;
  CorrectionReport removed;
  std::vector<std::string> warnings;
  std::string failure;         // why the reduction cannot be reported (empty: it can)
  nlohmann::json calibration;  // the scene's calibration (model/calibration.hpp), or null
  // measurement.uncertainty propagated (process_into with Monte Carlo options; absent without
  // the block).
  std::optional<UncertaintyResult> uncertainty;
};

// Why a reduction cannot be reported (empty: it can): a non-finite value, or an engineering strain
// of 1. The pulses are checked separately: they are written even when the reduction fails.
std::string reduction_failure(const ProcessingResult& r);

// Signals of the 1D bar model (a simulation's gauges) reduced as `process --signals` reduces them:
// the model does not disperse, so no dispersion correction (the faces are reached by a pure
// delay), and no windows of the scene (they are on the measured clock).
void use_simulated_signals(ProcessingOptions& options);
// A simulation's gauges (tension positive, one column per gauge) as the signals of those gauges.
GaugeSignals simulated_signals(const TimeSeries& gauges, const std::vector<std::string>& names);

// Throws InputError for a scene that cannot be processed (no specimen: the command's
// bars-together check is not a reduction) and NumericalError for non-finite pulses.
ProcessOutcome process_scene(const Scene& scene,
                             const std::optional<std::filesystem::path>& signals_file,
                             bool print_warnings = true);
// curve.csv's columns in their order (docs/outputs.md): the primary reduction's rate, strain,
// stress and true values lead; rows up to result.loading_end.
// measurement.uncertainty propagated by Monte Carlo into o.uncertainty (analysis/uncertainty.hpp),
// when the scene has the block, the signals are its measured record and the reduction succeeded;
// simulated signals (--signals) get a warning instead.
void add_uncertainty(const Scene& scene, const MonteCarloOptions& monte_carlo, ProcessOutcome& o);
using CurveColumn = std::pair<const char*, const std::vector<double>*>;
std::vector<CurveColumn> curve_columns(const ProcessOutcome& o);

// A scene without a specimen: the bars-together check of the bars' dispersion (bar_check.hpp).
struct BarCheckOutcome {
  BarCheckSetup setup;
  BarCheckResult result;
  std::vector<std::string> warnings;
};
// InputError when the scene cannot be checked (no measurement, or `with_signals_file`: --signals
// reduces a simulated test). The warnings are in the outcome, also printed with `print_warnings`.
BarCheckOutcome check_scene_bars(const Scene& scene, bool with_signals_file,
                                 bool print_warnings = true);

}  // namespace shpb
