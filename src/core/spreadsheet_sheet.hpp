#pragma once
// The part the .xlsx and .xls readers share (core/signal_spreadsheet.cpp, core/signal_xlsx.cpp):
// the cells of one sheet gathered by row and column, within limits set before anything is
// allocated, and turned into rows of text fields as a CSV file would give them.
#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/signal_text.hpp"

namespace shpb::spreadsheet {

// Excel's own limits (Excel 2007+: 1 048 576 rows × 16 384 columns): anything beyond is refused
// before rows are allocated.
constexpr std::size_t kMaxRows = 1048576;
constexpr std::size_t kMaxColumns = 16384;
// Cells of one sheet: a full-height sheet of 16 channels. A signal record is a time column and a
// few gauges; a sheet claiming more cells is refused before it takes gigabytes (each cell costs
// tens of bytes here).
constexpr std::size_t kMaxCells = kMaxRows * 16;

// InputError naming the file: "<file>: <what>: expected an Excel workbook (.xlsx or .xls)".
[[noreturn]] void broken(const std::filesystem::path& file, const std::string& what);
// "\"a\", \"b\"": the names a workbook has, for a message about a missing one.
std::string names_text(const std::vector<std::string>& names);
// "B7": the spreadsheet name of a cell (row 1-based, column 0-based).
std::string cell_name(std::size_t row, std::size_t column);

// Rows of a sheet: row number → fields by column.
class Sheet {
 public:
  explicit Sheet(std::filesystem::path file) : file_(std::move(file)) {}
  void set(std::size_t row, std::size_t column, std::string value);
  // The rows as text (blank rows dropped); InputError for a sheet without a non-blank row.
  DelimitedText text() &&;

 private:
  std::filesystem::path file_;
  std::map<std::size_t, std::vector<std::string>> rows_;
  std::size_t cells_ = 0;
};

DelimitedText read_xlsx(const std::filesystem::path& file, const std::string& sheet);

}  // namespace shpb::spreadsheet
