#pragma once
// The folder of `shpb process` (docs/outputs.md) from analysis/process_scene.hpp's results:
// raw_signals.csv, pulses.csv, curve.csv and summary.json; or, for a scene without a specimen,
// the bars-together check's pulses.csv and summary.json.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "analysis/process_scene.hpp"

namespace shpb {

// `scene_display` is the scene as named in summary.json. A failed reduction writes pulses.csv and
// the summary's error, then throws NumericalError, as the command does.
void write_process_outputs(const ProcessOutcome& o, const Scene& scene,
                           const std::string& scene_display, const std::filesystem::path& output);
nlohmann::json process_summary(const ProcessOutcome& o, const std::string& scene_display);

void write_bar_check(const BarCheckOutcome& o, const Scene& scene, const std::string& scene_display,
                     const std::filesystem::path& output);
nlohmann::json bar_check_summary(const BarCheckOutcome& o, const Scene& scene,
                                 const std::string& scene_display);

// The one-test command's work: the scene read and reduced (or, without a specimen, its bars
// checked together), the folder written. Exactly one of `outcome` and `bars` is set. The
// warnings are in the outcome (and its summary.json), also printed with `print_warnings`.
struct ProcessedScene {
  Scene scene;
  std::optional<ProcessOutcome> outcome;
  std::optional<BarCheckOutcome> bars;
};
ProcessedScene process_into(const std::filesystem::path& scene_file,
                            const std::optional<std::filesystem::path>& signals_file,
                            const std::filesystem::path& output,
                            const MonteCarloOptions* monte_carlo = nullptr,
                            bool print_warnings = true);

// The one-line summaries the command prints on stderr (with the uncertainty's line when drawn).
std::string bar_check_headline(const BarCheckOutcome& o, const std::filesystem::path& output);
std::string process_headline(const ProcessOutcome& o, const std::filesystem::path& output);

}  // namespace shpb
