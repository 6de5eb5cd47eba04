// LANL `.raw` (HopPyBar "LANLstandard"): tab separated; columns 1–2 a key/value metadata block,
// each further column a signal: its name, start time, sample interval, then the samples.
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/number_format.hpp"
#include "core/signal_formats.hpp"

namespace shpb {

RawSignalColumns read_lanl_raw_columns(const DelimitedText& text, const SignalRequest& request) {
  constexpr std::size_t kFirstSignalColumn = 2, kHeaderRows = 3;
  const auto& rows = text.rows;
  const TextRow head = rows[0];  // the signals' names
  if (rows.size() <= kHeaderRows || head.fields.size() <= kFirstSignalColumn)
    throw input_error(text.file.string(), "line 1", "",
                      "not a LANL .raw file (expected signal names in columns 3 and on, then start "
                      "time, sample interval and samples)");
  std::vector<std::size_t> indices;
  RawSignalColumns raw;
  for (const auto& c : request.columns) {
    std::size_t index = 0;
    if (c.index) {
      if (*c.index < static_cast<int>(kFirstSignalColumn) ||
          *c.index >= static_cast<int>(head.fields.size()))
        throw input_error(text.file.string(), "", "column index " + std::to_string(*c.index),
                          "signal columns of this file are " + std::to_string(kFirstSignalColumn) +
                              "–" + std::to_string(head.fields.size() - 1));
      index = static_cast<std::size_t>(*c.index);
    } else {
      std::string names;
      for (std::size_t k = kFirstSignalColumn; k < head.fields.size(); ++k) {
        if (head.fields[k] == c.name) index = k;
        names += (names.empty() ? "\"" : ", \"") + std::string(head.fields[k]) + "\"";
      }
      if (index == 0)
        throw input_error(text.file.string(), "line 1", "column \"" + c.name + "\"",
                          "no such signal; the file has " + names);
    }
    indices.push_back(index);
    raw.names.emplace_back(head.fields[index]);
  }
  // Every signal column of the file shares one time base: check they agree.
  const std::size_t c0 = indices.empty() ? kFirstSignalColumn : indices.front();
  const double start = number_at(text, rows[1], c0, head.fields[c0]);
  const double dt = number_at(text, rows[2], c0, head.fields[c0]);
  if (!(dt > 0))
    throw input_error(text.file.string(), text_place(rows[2].line, c0), format_number(dt) + " s",
                      "sample interval must be > 0");
  // The time base start + k·dt must increase at every sample: an interval below the start's
  // floating-point resolution (|start|·2^-52 per sample) would repeat time stamps.
  const double last = start + static_cast<double>(rows.size()) * dt;
  if (!std::isfinite(last) || dt <= 4 * std::numeric_limits<double>::epsilon() * std::abs(last))
    throw input_error(text.file.string(), text_place(rows[2].line, c0), format_number(dt) + " s",
                      "sample interval too small for the start time " + format_number(start) +
                          " s: the time stamps would not increase");
  for (std::size_t idx : indices) {
    if (number_at(text, rows[1], idx, head.fields[idx]) != start ||
        number_at(text, rows[2], idx, head.fields[idx]) != dt)
      throw input_error(text.file.string(), text_place(rows[1].line, idx),
                        std::string(head.fields[idx]),
                        "start time and sample interval differ between signal columns");
  }
  raw.time_from_header = true;
  raw.header_dt = dt;
  raw.values.resize(indices.size());
  TextRow row;  // one buffer for every row
  for (std::size_t r = kHeaderRows; r < rows.size(); ++r) {
    row.line = rows.line(r);
    rows.fields(r, row.fields);
    for (std::size_t k = 0; k < indices.size(); ++k)
      raw.values[k].push_back(number_at(text, row, indices[k], head.fields[indices[k]]));
    raw.time.push_back(start + static_cast<double>(r - kHeaderRows) * dt);
    raw.lines.push_back(row.line);
  }
  return raw;
}

}  // namespace shpb
