#pragma once
// The format-specific halves of read_signal_columns (signal_reader.hpp); internal to core.
#include "core/signal_reader.hpp"
#include "core/signal_text.hpp"

namespace shpb {

// Raw columns as found: time stamps (or a time base built from the header) with the line of
// each sample, before the time base is checked.
struct RawSignalColumns {
  std::vector<double> time;       // in the file's time unit (times request.time_unit_s later)
  bool time_from_header = false;  // LANL: start + i·dt, nothing to check
  // The column read as the time shows itself one (the format's own, or a header naming time or a
  // time unit, and no channel read from it): a refusal of its stamps is of a time column.
  bool time_column_shown = false;
  double header_dt = 0;  // … that dt
  LineMap lines;         // line of each sample
  std::vector<std::string> names;
  std::vector<std::vector<double>> values;
  std::vector<std::string> warnings;  // a time base read from the file's header
};

// Plain CSV/TSV: header lines skipped, columns by name or index.
RawSignalColumns read_csv_columns(const DelimitedText& text, const SignalRequest& request);
// Tektronix: metadata in columns 1–3, time in column 4, volts in column 5.
RawSignalColumns read_tektronix_columns(const DelimitedText& text, const SignalRequest& request);
// LANL `.raw`: metadata in columns 1–2; per signal column a name, start time, interval, samples.
RawSignalColumns read_lanl_raw_columns(const DelimitedText& text, const SignalRequest& request);

// Shared: the numeric value of row[column] or an InputError naming file, line and column.
double number_at(const DelimitedText& text, const TextRow& row, std::size_t column,
                 std::string_view column_name);

}  // namespace shpb
