#pragma once
// The fit's keys of a campaign file (docs/methods.md §9), read with the rest of the file by
// read_campaign (model/campaign.hpp) when it has any: `process --campaign` judges them as `fit`
// does.
//   "material": FILE | {...}       the starting law; its model is the one fitted
//   "free": {"A": [lo, hi], ...}   parameters of that law freed within bounds (others stay)
//   "nuisance": {"striker_velocity": [lo, hi] | "10 %", "rise_time": [lo, hi],
//                "time_shift": [lo, hi], "incident_wave_speed": [lo, hi] | "3 %",
//                "transmitter_wave_speed": [lo, hi] | "3 %", "transmitted_delay": [lo, hi]}
//                                  per-test parameters freed in the signals stage
//   "stages": ["curve", "signals"]  (the default; either alone is allowed)
//   "loss": "linear" (default) | "huber" | "cauchy"
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/enum_names.hpp"
#include "core/units.hpp"
#include "model/material.hpp"

namespace shpb {

struct Campaign;

struct FreeParameter {
  std::string name;
  double start = 0, lower = 0, upper = 0;  // SI
  std::string json_path;                   // "free.A"
};

// The per-test parameters of the signals stage (docs/methods.md §9): the striker, the impact, the
// clock, and the bars themselves for a lab without calibration shots (the incident and transmitter
// bars' wave speeds, and the delay of the transmitted channel against the incident one).
enum class NuisanceKind {
  kStrikerVelocity,
  kRiseTime,
  kTimeShift,
  kIncidentWaveSpeed,
  kTransmitterWaveSpeed,
  kTransmittedDelay
};
inline constexpr EnumName<NuisanceKind> kNuisanceNames[] = {
    {"striker_velocity", NuisanceKind::kStrikerVelocity},
    {"rise_time", NuisanceKind::kRiseTime},
    {"time_shift", NuisanceKind::kTimeShift},
    {"incident_wave_speed", NuisanceKind::kIncidentWaveSpeed},
    {"transmitter_wave_speed", NuisanceKind::kTransmitterWaveSpeed},
    {"transmitted_delay", NuisanceKind::kTransmittedDelay}};
std::string to_string(NuisanceKind k);
Dimension nuisance_dimension(NuisanceKind k);
// A shift or a delay: starts at 0, may be negative, takes absolute bounds only.
bool nuisance_is_offset(NuisanceKind k);
bool nuisance_is_wave_speed(NuisanceKind k);

// A per-test parameter: absolute bounds, or ± a fraction of each test's own starting value.
struct NuisanceSpec {
  NuisanceKind kind = NuisanceKind::kStrikerVelocity;
  std::optional<std::pair<double, double>> bounds;
  std::optional<double> relative;
  std::string json_path;
};

enum class FitStage { kCurve, kSignals };
enum class FitLoss { kLinear, kHuber, kCauchy };
inline constexpr EnumName<FitStage> kFitStageNames[] = {{"curve", FitStage::kCurve},
                                                        {"signals", FitStage::kSignals}};
inline constexpr EnumName<FitLoss> kFitLossNames[] = {
    {"linear", FitLoss::kLinear}, {"huber", FitLoss::kHuber}, {"cauchy", FitLoss::kCauchy}};
std::string to_string(FitStage s);
std::string to_string(FitLoss l);

struct FitSpec {
  std::string material_display;         // the material file as written, or "material" (inline)
  std::filesystem::path material_file;  // the starting material's file (an input), if not inline
  nlohmann::json material_document;
  MaterialSpec material;
  std::vector<FreeParameter> free;
  std::vector<NuisanceSpec> nuisance;
  std::vector<FitStage> stages = {FitStage::kCurve, FitStage::kSignals};
  FitLoss loss = FitLoss::kLinear;
};

// Reads and checks the fit's keys of a campaign (read_campaign calls it when the file has any);
// InputError (exit 2) names the file and JSON path: without `material`, that it is required.
FitSpec read_fit_spec(const Campaign& campaign);

}  // namespace shpb
