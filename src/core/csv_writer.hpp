#pragma once
// Comma-separated output that pandas and spreadsheets read: one header row, units in the column
// names, '.' decimals, shortest round-trip doubles (docs/outputs.md). Every write is checked
// (core/checked_write.hpp).
#include <cstdio>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace shpb {

class CsvWriter {
 public:
  CsvWriter(const std::filesystem::path& file, const std::vector<std::string>& header);
  ~CsvWriter();
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;

  void row(std::span<const double> values);
  void row(std::initializer_list<double> values) { row(std::span(values.begin(), values.size())); }
  // A row whose first `leading_columns` cells are already text (comma-separated, each from
  // format_double), then the values: a long-format file repeats its key cells on many rows.
  void row(std::string_view leading, std::size_t leading_columns, std::span<const double> values);
  // Numbers, then `trailing` (cells already formatted, each led by its comma; its columns counted
  // from the commas): a table whose last columns may be undefined (empty fields).
  void row(std::span<const double> values, std::string_view trailing);
  // A row of cells already formatted (format_double, quote_cell, or empty for an undefined
  // value): files that mix text and numbers through their columns.
  void row(std::span<const std::string> cells);
  std::size_t columns() const { return columns_; }
  // Flushes and closes the file, checking both: a full disk is a WriteError naming the file and
  // the reason. Call it when the last row is written; the destructor of an unclosed writer (an
  // exception on the way) closes without checking.
  void close();

 private:
  void write(const std::string& text);  // checked fwrite
  void row(std::string_view leading, std::size_t leading_columns, std::span<const double> values,
           std::string_view trailing, std::size_t trailing_columns);

  std::vector<char> buffer_ = std::vector<char>(1 << 18);  // stdio buffer, outlives file_
  std::FILE* file_ = nullptr;
  std::filesystem::path path_;
  std::size_t columns_ = 0;
  std::string line_;
  unsigned rows_ = 0;
};

// A text cell: quoted when it holds a comma, a quote or a line break (RFC 4180).
std::string quote_cell(const std::string& text);

// Shortest text that reads back to the same double.
std::string format_double(double value);
// A CSV field: format_double, empty for a non-finite value (an undefined number, docs/outputs.md),
// 0 for a subnormal one (as CsvWriter::row writes it).
std::string format_field(double value);

}  // namespace shpb
