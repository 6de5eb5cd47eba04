#include "analysis/gauge_signals.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "analysis/signal_checks.hpp"
#include "core/error.hpp"
#include "core/interpolation.hpp"
#include "core/median.hpp"
#include "core/number_format.hpp"
#include "core/signal_reader.hpp"
#include "core/time_series.hpp"

namespace shpb {
namespace {

// Two files' time bases count as the same if they agree to this fraction of a sample.
constexpr double kSameClock = 1e-3;
// Opposite gauges of one section read the axial strain plus and minus the bending strain, which
// their mean cancels. Bending of half the axial strain (RMS where the mean reaches half its peak:
// the pulses, the quiet record's noise says nothing of bending) is a bar far out of line (the
// LANL PMMA record's pairs: 4 % and 3 %); a dead, flat or mis-scaled channel deviates from the
// mean by 100 %, an inverted one or one of another gauge or test by more.
constexpr double kTwinChannelDisagreement = 0.5;
constexpr double kTwinPulseLevel = 0.5;  // of the mean's peak: the samples compared

// "column index 4 (measurement.channels[0], gauge "incident")": where a channel's message points.
std::string channel_label(const MeasurementSpec& m, std::size_t channel) {
  const ChannelSpec& ch = m.channels[channel];
  return (ch.column.index ? "column index " + std::to_string(*ch.column.index)
                          : "column \"" + ch.column.name + "\"") +
         " (measurement.channels[" + std::to_string(channel) + "], gauge \"" + ch.gauge + "\")";
}

// The largest strain a column can read in the wrong unit: a plausible strain (below
// kPlausibleStrainMax) in microstrain declared as strain. That slip is warned about and reduced
// (docs/scene-format.md); a sample beyond it has no unit that explains it (a value scaled by
// 1e300 overflowed to inf in the reduction), and is refused where it is: by its line when the
// record was not resampled onto another clock, else by its time.
constexpr double kMaxReadStrain = kPlausibleStrainMax * 1e6;

void check_strain_magnitude(const std::filesystem::path& file, const MeasurementSpec& m,
                            std::size_t channel, const std::vector<double>& read, double factor,
                            const LineMap& lines, const std::vector<double>& time_s) {
  for (std::size_t i = 0; i < read.size(); ++i) {
    if (std::abs(read[i] * factor) <= kMaxReadStrain) continue;
    throw input_error(file.string(),
                      (i < lines.size() ? "line " + std::to_string(lines[i])
                                        : "at " + format_number(time_s[i]) + " s") +
                          ", " + channel_label(m, channel),
                      format_number(read[i]) + " read as strain " + format_number(read[i] * factor),
                      "expected |strain| within " + format_number(kMaxReadStrain) +
                          " (a bar's record stays within " + format_number(kPlausibleStrainMax) +
                          ", microstrain read as strain within " + format_number(kMaxReadStrain) +
                          "); check the value, the channel's unit and bridge or scale");
  }
}

// The channels of one gauge agree within kTwinChannelDisagreement; `channels` are their indices.
void check_twin_channels(const MeasurementSpec& m, const std::vector<std::size_t>& channels,
                         const std::vector<std::vector<double>>& channel_strain,
                         const std::vector<std::filesystem::path>& files) {
  const std::size_t n = channel_strain[channels.front()].size();
  std::vector<std::vector<double>> level;  // each channel from its own median baseline
  std::vector<double> mean(n, 0.0);
  for (std::size_t c : channels) {
    const double med = median(channel_strain[c]);
    level.emplace_back(channel_strain[c]);
    for (std::size_t i = 0; i < n; ++i)
      level.back()[i] -= med, mean[i] += level.back()[i] / static_cast<double>(channels.size());
  }
  double peak = 0;
  for (double x : mean) peak = std::max(peak, std::abs(x));
  double mean_ss = 0;
  for (double x : mean) mean_ss += std::abs(x) >= kTwinPulseLevel * peak ? x * x : 0;
  std::size_t worst = 0;  // the channel furthest from the mean (of two: the first)
  double worst_ss = 0;
  for (std::size_t k = 0; k < channels.size(); ++k) {
    double dev_ss = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (std::abs(mean[i]) >= kTwinPulseLevel * peak)
        dev_ss += (level[k][i] - mean[i]) * (level[k][i] - mean[i]);
    if (dev_ss > worst_ss) worst = k, worst_ss = dev_ss;
  }
  if (worst_ss <= kTwinChannelDisagreement * kTwinChannelDisagreement * mean_ss) return;
  // Two channels deviate from their mean alike: both are named, either may be the wrong one.
  if (channels.size() == 2) worst = 0;
  const std::string with = channels.size() == 2 ? "with " + files[channels[1]].string() + ", " +
                                                      channel_label(m, channels[1]) + ": each"
                                                : "";
  char value[160];
  if (mean_ss > 0)
    std::snprintf(value, sizeof value,
                  "deviates from the mean of the gauge's %zu channels by %.3g %% RMS",
                  channels.size(), 100 * std::sqrt(worst_ss / mean_ss));
  else
    std::snprintf(value, sizeof value, "cancels the gauge's other channels (a flat mean)");
  throw input_error(files[channels[worst]].string(), channel_label(m, channels[worst]),
                    with + (with.empty() ? "" : " ") + value,
                    "expected the channels of one gauge (opposite gauges of one section, "
                    "averaged to cancel bending) to agree within " +
                        format_number(100 * kTwinChannelDisagreement) +
                        " %: a dead, flat, inverted or mis-scaled channel, or one of another "
                        "gauge?");
}

std::vector<double> resample(const std::vector<double>& t, const std::vector<double>& y,
                             const std::vector<double>& onto) {
  std::vector<double> out(onto.size());
  for (std::size_t i = 0; i < onto.size(); ++i) out[i] = interpolate(t, y, onto[i]);
  return out;
}

double median_abs_peak(const std::vector<double>& x) {
  // Peak distance from the median (the baseline) of the record.
  const double med = median(x);
  double peak = 0;
  for (double v : x) peak = std::max(peak, std::abs(v - med));
  return peak;
}

// A sample interval outside what any digitizer records (a time unit that does not match the
// column, e.g. "us" on seconds) is refused before anything is sized from it.
void check_sample_interval(const SignalColumns& cols, const MeasurementSpec& m) {
  if (cols.dt_s >= kMinSampleInterval_s && cols.dt_s <= kMaxSampleInterval_s) return;
  const bool first_column = m.time_column.name.empty() && !m.time_column.index &&
                            cols.format == SignalFormat::kCsv && !m.time_clock;
  const std::string column = m.time_column.index
                                 ? "column index " + std::to_string(*m.time_column.index)
                             : first_column               ? "the first column (the default)"
                             : m.time_column.name.empty() ? "the format's time base"
                                                          : "column \"" + m.time_column.name + "\"";
  char value[160], expected[400];
  std::snprintf(value, sizeof value, "time %s in \"%s\": sample interval %.3g s", column.c_str(),
                m.time_unit.c_str(), cols.dt_s);
  // Whole steps of one: sample numbers (Rigol's "Sequence", a DAQ's "Sample", a spreadsheet's
  // index), no time at all.
  const bool counts = cols.dt_s == 1.0 && m.time_unit == "s" && cols.time_s.front() >= 0 &&
                      cols.time_s.front() == std::round(cols.time_s.front());
  std::snprintf(expected, sizeof expected, "expected %.0e s to %.0e s (a digitizer's range); %s",
                kMinSampleInterval_s, kMaxSampleInterval_s,
                counts ? "the column counts samples (0, 1, 2, ...): give the record's time base as "
                         "measurement.time.interval (and start), its channels by name or index"
                       : "is the column in another unit than measurement.time.unit says?");
  const std::string place =
      cols.lines.size() > 1 ? "line " + std::to_string(cols.lines[1]) : std::string();
  throw input_error(cols.file.string(), place, value, expected);
}

// Each gauge's strain, the mean of its channels (checked to agree), in order of first appearance.
void average_channels(const MeasurementSpec& m, std::vector<std::vector<double>>& channel_strain,
                      const std::vector<std::filesystem::path>& channel_file,
                      const std::vector<double>& channel_factor, GaugeSignals& out) {
  for (std::size_t c = 0; c < m.channels.size(); ++c) {
    const std::string& g = m.channels[c].gauge;
    if (out.find(g)) continue;
    std::vector<std::size_t> twins;
    for (std::size_t d = c; d < m.channels.size(); ++d)
      if (m.channels[d].gauge == g) twins.push_back(d);
    GaugeSignals::Source source{channel_file[c].string(), channel_label(m, c)};
    for (std::size_t k = 1; k < twins.size(); ++k)
      source.where +=
          " and " +
          (channel_file[twins[k]] == channel_file[c] ? ""
                                                     : channel_file[twins[k]].string() + ", ") +
          channel_label(m, twins[k]);
    out.sources.push_back(std::move(source));
    if (twins.size() == 1) {  // the mean of one channel is the channel, moved (0 + x: -0 is 0)
      for (double& x : channel_strain[c]) x = 0.0 + x;
      out.gauges.push_back(g);
      out.strain.push_back(std::move(channel_strain[c]));
      std::optional<std::array<double, 2>> range = m.channels[c].range;
      if (range) {  // in strain; a negative factor (inverted) swaps its ends
        for (double& e : *range) e *= channel_factor[c];
        if ((*range)[0] > (*range)[1]) std::swap((*range)[0], (*range)[1]);
      }
      out.ranges.push_back(range);
      continue;
    }
    std::vector<double> sum(out.time_s.size(), 0.0);
    for (std::size_t d : twins)
      for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += channel_strain[d][i];
    check_twin_channels(m, twins, channel_strain, channel_file);
    for (double& x : sum) x /= static_cast<double>(twins.size());
    out.gauges.push_back(g);
    out.strain.push_back(std::move(sum));
    out.ranges.emplace_back();
  }
}

}  // namespace

std::optional<std::array<double, 2>> GaugeSignals::range_of(std::string_view gauge) const {
  for (std::size_t i = 0; i < gauges.size() && i < ranges.size(); ++i)
    if (gauges[i] == gauge) return ranges[i];
  return std::nullopt;
}

const std::vector<double>* GaugeSignals::find(std::string_view gauge) const {
  for (std::size_t i = 0; i < gauges.size(); ++i)
    if (gauges[i] == gauge) return &strain[i];
  return nullptr;
}

InputError channel_error(const GaugeSignals& signals, const std::string& gauge,
                         const std::string& scene_file, const std::string& what) {
  for (std::size_t g = 0; g < signals.sources.size() && g < signals.gauges.size(); ++g)
    if (signals.gauges[g] == gauge)
      return input_error(signals.sources[g].file, signals.sources[g].where, "", what);
  return input_error(scene_file, "measurement.channels", "gauge \"" + gauge + "\"", what);
}

InputError no_pulse_error(const GaugeSignals& signals, const std::string& gauge,
                          const std::string& scene_file, const std::string& purpose) {
  return channel_error(signals, gauge, scene_file,
                       "its signal never rises above its noise: " + purpose);
}

double volts_to_strain(const BridgeSpec& b) {
  return (4.0 / b.arms) / (b.gauge_factor * b.gain * b.excitation_V);
}

double strain_per_unit(const ChannelSpec& ch) {
  switch (ch.unit) {
    case SignalUnit::kVolt:
    case SignalUnit::kMillivolt:
      if (!ch.scale && !ch.bridge)
        throw input_error("measurement", "channels[].bridge", "missing",
                          "a channel in volts needs a bridge (arms, gauge_factor, excitation, "
                          "gain) or a scale");
      return (ch.unit == SignalUnit::kMillivolt ? 1e-3 : 1.0) *
             (ch.scale ? *ch.scale : volts_to_strain(*ch.bridge));
    case SignalUnit::kMicrostrain:
      return 1e-6;
    case SignalUnit::kStrain:
      break;
  }
  return 1.0;
}

GaugeSignals read_gauge_signals(const MeasurementSpec& m, const std::filesystem::path& base_dir) {
  auto resolve = [&](const std::filesystem::path& p) {
    if (p.is_absolute() || base_dir.empty()) return p;
    return base_dir / p;
  };
  // One read per file, with all the columns its channels need.
  std::map<std::filesystem::path, std::vector<std::size_t>> by_file;
  for (std::size_t c = 0; c < m.channels.size(); ++c)
    by_file[resolve(m.channels[c].file.empty() ? m.file : m.channels[c].file)].push_back(c);

  GaugeSignals out;
  std::vector<std::vector<double>> channel_strain(m.channels.size());
  std::vector<std::filesystem::path> channel_file(m.channels.size());
  std::vector<double> channel_factor(m.channels.size(), 1.0);
  bool first_file = true;
  // Files in channel order, so the first channel's file sets the common clock.
  std::vector<std::filesystem::path> order;
  for (const auto& ch : m.channels) {
    const auto f = resolve(ch.file.empty() ? m.file : ch.file);
    if (std::find(order.begin(), order.end(), f) == order.end()) order.push_back(f);
  }
  for (const auto& file : order) {
    const auto& channels = by_file[file];
    SignalRequest req;
    req.file = file;
    req.format = m.format;
    req.time_column = m.time_column;
    req.time_unit_s = m.time_unit_s;
    req.sheet = m.sheet;
    req.resample = m.time_resample;
    req.clock = m.time_clock;
    for (std::size_t c : channels) {
      req.columns.push_back(m.channels[c].column);
      req.column_units.push_back(m.channels[c].unit);
    }
    SignalColumns cols = read_signal_columns(req);
    check_sample_interval(cols, m);
    out.warnings.insert(out.warnings.end(), cols.warnings.begin(), cols.warnings.end());
    const bool sets_clock = first_file;
    if (sets_clock) {  // the common clock, moved there
      out.time_s = std::move(cols.time_s);
      out.dt_s = cols.dt_s;
      first_file = false;
    }
    const std::vector<double>& file_time = sets_clock ? out.time_s : cols.time_s;
    const bool same_clock =
        file_time.size() == out.time_s.size() &&
        std::abs(file_time.front() - out.time_s.front()) < kSameClock * out.dt_s &&
        std::abs(cols.dt_s - out.dt_s) * static_cast<double>(out.time_s.size()) <
            kSameClock * out.dt_s;
    if (!same_clock) {
      // Files of one test record it over the same time: a file with next to no samples within
      // the first's record (its time in another unit, or its own trigger's clock) holds no pulse
      // there, and resampled it would be a flat line.
      const auto within = std::count_if(file_time.begin(), file_time.end(), [&](double t) {
        return t >= out.time_s.front() && t <= out.time_s.back();
      });
      if (static_cast<std::size_t>(within) < kMinRecordSamples) {
        char value[200];
        std::snprintf(value, sizeof value,
                      "%td samples (record %s s to %s s, interval %.3g s) within %s's "
                      "record (%s s to %s s)",
                      within, format_resolved(file_time.front(), cols.dt_s, 6).c_str(),
                      format_resolved(file_time.back(), cols.dt_s, 6).c_str(), cols.dt_s,
                      order.front().filename().string().c_str(),
                      format_resolved(out.time_s.front(), out.dt_s, 6).c_str(),
                      format_resolved(out.time_s.back(), out.dt_s, 6).c_str());
        throw input_error(file.string(), "time column", value,
                          "expected the files of one test to record the same time, at least " +
                              std::to_string(kMinRecordSamples) +
                              " samples: is the time unit the same in both files "
                              "(measurement.time.unit applies to every file)?");
      }
      out.warnings.push_back(file.string() + ": time base differs from " + order.front().string() +
                             "; its channels were resampled onto the first file's clock (linear)");
    }
    for (std::size_t k = 0; k < channels.size(); ++k) {
      const ChannelSpec& ch = m.channels[channels[k]];
      std::vector<double> v =
          same_clock ? std::move(cols.values[k]) : resample(file_time, cols.values[k], out.time_s);
      double factor = strain_per_unit(ch);
      if (ch.invert) factor = -factor;
      factor /= ch.calibrated_gain;   // model/calibration.hpp
      static const LineMap kNoLines;  // resampled: samples named by time
      check_strain_magnitude(file, m, channels[k], v, factor, same_clock ? cols.lines : kNoLines,
                             out.time_s);
      for (double& x : v) x *= factor;
      if (ch.calibrated_delay_s != 0) {  // its record on the reference channel's clock
        const std::vector<double> late = v;
        const double shift = ch.calibrated_delay_s / out.dt_s;
        for (std::size_t i = 0; i < v.size(); ++i)
          v[i] = sample_at(late, static_cast<double>(i) + shift, late.front(), late.back());
      }
      channel_strain[channels[k]] = std::move(v);
      channel_factor[channels[k]] = factor;
      channel_file[channels[k]] = file;
    }
  }
  average_channels(m, channel_strain, channel_file, channel_factor, out);
  for (std::size_t g = 0; g < out.gauges.size(); ++g) {
    const double peak = median_abs_peak(out.strain[g]);
    if (peak < kPlausibleStrainMin || peak > kPlausibleStrainMax) {
      // Microstrain declared as strain is the usual slip: say so when ×1e-6 would be plausible.
      const bool micro = peak * 1e-6 >= kPlausibleStrainMin && peak * 1e-6 <= kPlausibleStrainMax;
      out.warnings.push_back(
          "gauge \"" + out.gauges[g] + "\": implausible strain scale: peak |strain| " +
          format_number(peak) + " is outside " +
          format_range(kPlausibleStrainMin, kPlausibleStrainMax) +
          " for a Kolsky bar; check the channel's unit and bridge" +
          (micro ? " (the values look like microstrain: \"unit\": \"microstrain\")" : ""));
    }
  }
  return out;
}

}  // namespace shpb
