// The time base a signal file's header states (core/signal_header_clock.hpp).
#include "core/signal_header_clock.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/number_format.hpp"
#include "core/signal_header_units.hpp"

namespace shpb {
namespace {

// A time base stated in the metadata rows above the data: Yokogawa's ASCII export
// (HResolution, HOffset, HUnit rows: sample i at HOffset + i·HResolution) or LabVIEW's .lvm
// (Delta_X, X0 rows). Each row holds one value per trace.
struct HeaderClock {
  bool labview = false;  // Delta_X/X0: never read (below)
  std::optional<TextRow> interval_row;
  std::optional<TextRow> start_row;
  std::optional<TextRow> trace_names;  // Yokogawa's TraceName row: the channels' names
  SampleClock clock;
};

// Where a header states the sample interval so that reading it cannot mislead: the header's own
// digits. Yokogawa prints it to 5 significant digits (a rounding up to 5e-5 of it).
constexpr double kHeaderIntervalDigits = 1e-4;

// "line 7 (HResolution)"
std::string row_place(const TextRow& row) {
  return "line " + std::to_string(row.line) + " (" + std::string(row.fields[0]) + ")";
}

// The one value a header row gives every trace, in seconds per `unit_s`; refused when the traces
// differ (one file, one time base) or a value is not a number.
double header_value(const DelimitedText& text, const TextRow& row, double unit_s) {
  std::optional<double> value;
  for (std::size_t c = 1; c < row.fields.size(); ++c) {
    if (row.fields[c].empty()) continue;
    const auto v = parse_number(row.fields[c], text.decimal_comma);
    if (!v || !std::isfinite(*v))
      throw input_error(text.file.string(), text_place(row.line, c),
                        "\"" + std::string(row.fields[c]) + "\"",
                        "expected a number (the header's time base); or give it as "
                        "measurement.time.interval");
    if (value && std::abs(*v - *value) > kHeaderIntervalDigits * std::abs(*value))
      throw input_error(text.file.string(), row_place(row),
                        format_number(*value) + " and " + format_number(*v),
                        "one time base for every trace of a file; export the traces of one "
                        "sample rate together");
    if (!value) value = *v;
  }
  if (!value)
    throw input_error(text.file.string(), row_place(row), "(empty)",
                      "expected the header's time base; or give it as measurement.time.interval");
  return *value * unit_s;
}

// Rigol's CSV: "X,CH1,CH2,Start,Increment," over "Sequence,Volt,Volt,-1.0e-04,1.0e-07,": sample
// i at Start + i·Increment (the first column numbers the samples); the names left of Start name
// the channels.
void rigol_clock(const DelimitedText& text, std::size_t first_data, HeaderClock& h) {
  for (std::size_t i = 0; i + 1 < first_data; ++i) {
    const TextRow names = text.rows[i];
    const auto& f = names.fields;
    const auto start = std::find(f.begin(), f.end(), "Start");
    const auto increment = std::find(f.begin(), f.end(), "Increment");
    if (start == f.end() || increment == f.end()) continue;
    const TextRow values = text.rows[i + 1];
    const auto at = [&](auto it) {
      const auto c = static_cast<std::size_t>(it - f.begin());
      return TextRow{values.line, {*it, c < values.fields.size() ? values.fields[c] : ""}};
    };
    h.interval_row = at(increment);
    h.start_row = at(start);
    h.trace_names = TextRow{names.line, {f.begin(), start}};
    return;
  }
}

std::optional<HeaderClock> header_clock(const DelimitedText& text, std::size_t first_data) {
  HeaderClock h;
  std::optional<TextRow> unit_row;
  for (std::size_t i = 0; i < first_data; ++i) {
    const TextRow row = text.rows[i];
    if (row.fields.empty()) continue;
    const std::string_view key = row.fields[0];
    if (key == "HResolution" || key == "Delta_X")
      h.interval_row = row, h.labview = key == "Delta_X";
    if (key == "HOffset" || key == "X0") h.start_row = row;
    if (key == "HUnit") unit_row = row;
    if (key == "TraceName") h.trace_names = row;
  }
  if (!h.interval_row) rigol_clock(text, first_data, h);
  if (!h.interval_row) return std::nullopt;
  double unit_s = 1;  // Yokogawa's HUnit: "s" for a time record
  if (unit_row && unit_row->fields.size() > 1) {
    const auto u = time_unit(std::string(unit_row->fields[1]));
    if (!u)
      throw input_error(text.file.string(), row_place(*unit_row),
                        "\"" + std::string(unit_row->fields[1]) + "\"",
                        "expected a time unit (the header's HResolution is not a sample "
                        "interval); a record of time");
    unit_s = *u;
  }
  h.clock.interval_s = header_value(text, *h.interval_row, unit_s);
  if (!(h.clock.interval_s > 0))
    throw input_error(text.file.string(), row_place(*h.interval_row),
                      format_number(h.clock.interval_s) + " s",
                      "expected a sample interval > 0; or give it as measurement.time.interval");
  if (h.start_row && !h.labview) h.clock.start_s = header_value(text, *h.start_row, unit_s);
  return h;
}

// Whether the data's first column holds the header's clock (a time column exported beside the
// header's time base): its first stamps within a quarter interval, and half their printed last
// digit, of start + i·interval (of the first stamp + i·interval where the header's start is not
// read), where a channel's values are nowhere near. Stamps printed coarser than the interval
// (LabVIEW's 6 decimals at 10 MS/s: 10 rows a µs) are judged over as many rows as the clock takes
// to cross three of their digits, which a channel's values do not follow.
bool stamps_follow(const DelimitedText& text, std::size_t first_data, const HeaderClock& h,
                   double unit_s) {
  constexpr std::size_t kStampsJudged = 3;
  constexpr double kOffClock = 0.25;  // of the interval
  constexpr double kDigitsCrossed = 3;
  double start = h.clock.start_s;  // LabVIEW's X0 is not read: the first stamp's
  for (std::size_t i = 0, judged = kStampsJudged; i < judged; ++i) {
    if (first_data + i >= text.rows.size()) return false;
    const TextRow& row = text.rows[first_data + i];
    const auto t =
        row.fields.empty() ? std::nullopt : parse_number(row.fields[0], text.decimal_comma);
    if (!t) return false;
    const double digit = printed_step(row.fields[0], text.decimal_comma) * unit_s;
    judged = std::max(
        judged,
        static_cast<std::size_t>(std::ceil(kDigitsCrossed * digit / h.clock.interval_s)) + 1);
    if (h.labview && i == 0) start = *t * unit_s;
    if (std::abs(*t * unit_s - start - static_cast<double>(i) * h.clock.interval_s) >
        kOffClock * h.clock.interval_s + (h.labview && i > 0 ? digit : digit / 2))
      return false;
  }
  return true;
}

}  // namespace

FileClock file_clock(const DelimitedText& text, std::size_t first_data,
                     const SignalRequest& request, std::vector<std::string>& warnings) {
  const bool default_time = request.time_column.name.empty() && !request.time_column.index;
  if (!default_time) return {};  // a time column named by the scene
  const auto header = header_clock(text, first_data);
  if (!header) return {request.clock};
  const SampleClock& h = header->clock;
  if (request.clock) {
    if (std::abs(request.clock->interval_s / h.interval_s - 1) > kHeaderIntervalDigits)
      throw input_error(
          text.file.string(), row_place(*header->interval_row), format_number(h.interval_s) + " s",
          "the header's sample interval, but measurement.time.interval gives " +
              format_number(request.clock->interval_s) + " s: correct the one that is wrong");
    return {request.clock, header->trace_names};
  }
  if (stamps_follow(text, first_data, *header, request.time_unit_s))
    return {std::nullopt, header->trace_names};
  if (header->labview)
    throw input_error(text.file.string(), row_place(*header->interval_row),
                      format_number(h.interval_s),
                      "the first column does not follow it as a time column would, and LabVIEW's "
                      "Delta_X is not read (its X0 may be an absolute time, and each segment has "
                      "its own): give the record's time base as measurement.time.interval (and "
                      "start), or name its time column (measurement.time.column)");
  std::string start = header->start_row ? ", start " + format_number(h.start_s) + " s from " +
                                              row_place(*header->start_row)
                                        : ", start 0 s (the header gives no HOffset)";
  warnings.push_back(text.file.string() + ": no time column; time base from the header: interval " +
                     format_number(h.interval_s) + " s from " + row_place(*header->interval_row) +
                     start + " (measurement.time.interval would set it)");
  return {h, header->trace_names};
}

}  // namespace shpb
