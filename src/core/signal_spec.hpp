#pragma once
// How a signal file is addressed (docs/scene-format.md `measurement`): its format and a column by
// header name or index. File-format vocabulary only; the scene's measurement block
// (model/scene.hpp) is built from these, and the signal readers (signal_reader.hpp) take them.
#include <optional>
#include <string>

#include "core/enum_names.hpp"

namespace shpb {

enum class SignalFormat { kAuto, kCsv, kTektronix, kLanlRaw };
inline constexpr EnumName<SignalFormat> kSignalFormatNames[] = {
    {"auto", SignalFormat::kAuto},
    {"csv", SignalFormat::kCsv},
    {"tektronix", SignalFormat::kTektronix},
    {"lanl-raw", SignalFormat::kLanlRaw}};

// measurement.time.resample (docs/scene-format.md): what a time base whose steps are not uniform
// becomes. kAuto: resampled (linear) onto a uniform grid when every step is within
// kAutoResampleJitter of the mean interval (export jitter), refused otherwise (a gap or a jump);
// kNever: refused; kAlways: resampled whatever the steps, onto `interval_s` when given.
enum class TimeResample { kAuto, kNever, kAlways };
struct TimeResampling {
  TimeResample mode = TimeResample::kAuto;
  std::optional<double> interval_s;  // kAlways only: the grid's interval (else the mean step)
  bool operator==(const TimeResampling&) const = default;
};

// Sample intervals outside [1 ps, 100 µs] are no digitizer's record of a Kolsky bar pulse
// (tens of µs long): a time column in another unit than it is read in, or a scene's interval
// (measurement.time.interval) mistyped. Refused with an InputError.
inline constexpr double kMinSampleInterval_s = 1e-12;
inline constexpr double kMaxSampleInterval_s = 1e-4;

// measurement.time.interval / rate and start (docs/scene-format.md): the time base of a file that
// has no time column, sample i at start_s + i·interval_s. Every column is then a channel column.
struct SampleClock {
  double interval_s = 0;
  double start_s = 0;
  bool operator==(const SampleClock&) const = default;
};

// measurement.channels[].unit: what a column's values are in (volts become strain through a bridge
// or a scale). A header naming a column's unit must agree with it (signal_header_units.hpp).
enum class SignalUnit { kVolt, kMillivolt, kStrain, kMicrostrain };
inline constexpr EnumName<SignalUnit> kSignalUnitNames[] = {
    {"V", SignalUnit::kVolt},
    {"mV", SignalUnit::kMillivolt},
    {"strain", SignalUnit::kStrain},
    {"microstrain", SignalUnit::kMicrostrain}};

struct ColumnRef {
  std::string name;          // column by header name, or
  std::optional<int> index;  // by 0-based index
  bool operator==(const ColumnRef&) const = default;
};

}  // namespace shpb
