#pragma once
// One interface for every signal file format (plain CSV/TSV, Tektronix per-channel CSV, LANL
// `.raw`): ask for a time base and some columns, get them back on a checked uniform time base.
// Problems in the file are InputErrors naming file, line and column; things a person should
// know but that do not stop the work (a rebuilt time base) are returned as warnings.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/line_map.hpp"
#include "core/signal_spec.hpp"

namespace shpb {

struct SignalRequest {
  std::filesystem::path file;
  SignalFormat format = SignalFormat::kAuto;
  ColumnRef
      time_column;  // empty: the format's own (CSV: first column; Tektronix: 4th; LANL: header)
  double time_unit_s = 1.0;  // seconds per unit of the time column
  std::vector<ColumnRef> columns;
  // The unit each column is read in, one per column (empty: none checked). A CSV or workbook
  // header naming a column's unit ("CH1 (mV)", a unit row's "µm/m") must name this one.
  std::vector<SignalUnit> column_units;
  std::string sheet;  // .xlsx/.xls: the sheet by name (empty: the first)
  TimeResampling resample;
  std::optional<SampleClock> clock;  // a file without a time column: its time base
};

// Steps within this fraction of the mean interval are a jittered clock (time stamps written with
// the digitizer's clock error or rounding, e.g. 998 / 1022 ns alternating): resampled by default.
// A step further off is a gap or a jump in the record, refused unless resampling is asked for.
inline constexpr double kAutoResampleJitter = 0.05;

struct SignalColumns {
  std::filesystem::path file;
  SignalFormat format = SignalFormat::kCsv;  // as detected
  std::vector<double> time_s;                // uniform, increasing
  double dt_s = 0;
  std::vector<std::string> names;           // resolved name of each requested column
  std::vector<std::vector<double>> values;  // one per requested column, time_s.size() each
  LineMap lines;  // the file's line (a sheet's row) of each sample; empty once resampled onto
                  // another grid
  std::vector<std::string> warnings;
};

SignalColumns read_signal_columns(const SignalRequest& request);

std::string_view to_string(SignalFormat f);

}  // namespace shpb
