#pragma once
// From a scene's `measurement` block to strain at each gauge (tension positive): read every
// channel through read_signal_columns, volts → strain through the bridge, polarity, averaging of
// the channels of one gauge (opposite gauges cancel bending), one common time base.
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "model/scene.hpp"

namespace shpb {

struct GaugeSignals {
  std::vector<double> time_s;  // uniform
  double dt_s = 0;
  std::vector<std::string> gauges;
  std::vector<std::vector<double>> strain;  // per gauge, tension positive
  std::vector<std::string> warnings;
  // Where each gauge was read (one per gauge, as `gauges`; none for signals made in memory): its
  // record's file, and its column with the scene's channel (a gauge's channels joined by "and").
  struct Source {
    std::string file, where;
  };
  std::vector<Source> sources;
  // Each gauge's stated full scale in its strain, [low, high] (measurement.channels[].range, after
  // its scale, sign and gain): none where not stated or where the gauge averages two channels
  // (their mean has no one full scale); none at all for signals made in memory.
  std::vector<std::optional<std::array<double, 2>>> ranges;
  std::optional<std::array<double, 2>> range_of(std::string_view gauge) const;

  // The strain of `gauge`, or nullptr.
  const std::vector<double>* find(std::string_view gauge) const;
};

// The one-line refusal of `gauge` for the reason `what`: it names the record's file and column the
// user would open, and the scene's channel. A signal made in memory (no source) is named by the
// scene's channel alone.
InputError channel_error(const GaugeSignals& signals, const std::string& gauge,
                         const std::string& scene_file, const std::string& what);

// … whose signal never rises above its noise; `purpose` says what the pulse was for.
InputError no_pulse_error(const GaugeSignals& signals, const std::string& gauge,
                          const std::string& scene_file, const std::string& purpose);

// ε = (4/arms)·V / (GF · gain · V_ex): quarter bridge arms = 1, half 2, full 4.
double volts_to_strain(const BridgeSpec& bridge);

// Strain per unit of the channel's column (its bridge or scale for volts, a thousandth of that
// for millivolts), before its polarity and calibrated gain.
double strain_per_unit(const ChannelSpec& channel);

// Peak strains outside [1e-5, 5e-2] are not what a Kolsky bar produces: a warning names the
// gauge and its peak (the unit or the bridge is probably wrong).
inline constexpr double kPlausibleStrainMin = 1e-5;
inline constexpr double kPlausibleStrainMax = 5e-2;

// No record holds more samples than this between two places it is moved (16.8 M: 1.7 s at
// 10 MHz); a larger delay means a wrong time unit and would pad the FFT beyond memory.
inline constexpr double kMaxDelaySamples = 1 << 24;

// Reads the channels of `m`; relative file names are taken relative to `base_dir` (the scene's
// folder). Throws InputError for unreadable or broken files.
GaugeSignals read_gauge_signals(const MeasurementSpec& m, const std::filesystem::path& base_dir);

}  // namespace shpb
