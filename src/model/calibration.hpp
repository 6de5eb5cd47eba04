#pragma once
// A bar calibration (docs/scene-format.md "Calibration"): the wave speed and Poisson ratio of bars,
// the positions of gauges and the gain and delay of their channels, as `shpb calibrate` fits them
// from a lab's bars-apart and bars-together shots. A scene names one with a top-level
// "calibration": its values replace the scene's nominal ones once, when the scene is read, for
// every command. This file holds the one format of calibration.json: its writer and its reader.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace shpb {

struct Scene;

// A fitted value with its standard uncertainty (null when the shots do not determine it).
struct CalibratedValue {
  double value = 0;
  std::optional<double> sd;
};

struct BarCalibration {
  std::string bar;  // the bar's name in the scenes
  CalibratedValue wave_speed_m_s, poisson_ratio;
  double density_kg_m3 = 0;  // the scene's (E = ρ c0²)
};

struct GaugeCalibration {
  std::string gauge;  // the gauge's name in the scenes
  std::string bar;
  CalibratedValue position_m;  // from the bar's left end
  // The channel's strain over the true strain (relative to the reference channel unless `absolute`)
  // and the time by which its record lags the reference channel's.
  CalibratedValue gain, delay_s;
};

struct Calibration {
  std::vector<BarCalibration> bars;
  std::vector<GaugeCalibration> gauges;
  std::string reference_gauge;  // gains and delays are relative to its channel
  bool absolute_gain = false;   // a measured striker velocity made the gains absolute
  nlohmann::json provenance;    // shots, residuals, warnings: written as given, not read back
};

// calibration.json's text (docs/outputs.md `calibrate`).
nlohmann::json calibration_to_json(const Calibration& c);

// Reads calibration.json; InputError naming the file, the JSON path and the value.
Calibration read_calibration_file(const std::filesystem::path& file);

// Replaces the scene's bar constants, gauge positions and channel gains and delays by the
// calibration's and records its file in scene.calibration_file. Every bar and gauge the
// calibration names must be in the scene (InputError naming the scene's `calibration` key).
void apply_calibration(Scene& scene, const Calibration& c, const std::filesystem::path& file);

// What summary.json says of the calibration a scene used: its file and digest, or null.
nlohmann::json calibration_summary(const Scene& scene);

}  // namespace shpb
