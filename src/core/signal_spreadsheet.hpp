#pragma once
// Excel workbooks as signal files: .xlsx (Office Open XML: a zip of XML parts, read with libzip and
// expat) and .xls (BIFF, read with FreeXL). One sheet, by name (empty: the first), becomes rows of
// text fields as a CSV file would give them, so columns are then found by header name or index
// exactly as in a CSV file; the "line" of a row is its row number in the sheet.
#include <filesystem>
#include <string>

#include "core/signal_text.hpp"

namespace shpb {

// True for the extensions .xlsx and .xls (any case).
bool is_spreadsheet(const std::filesystem::path& file);

// What an empty cell of `file` may be beyond an empty cell, for messages: in an .xls, a formula
// (FreeXL, its reader, gives no formula's value); "" for any other file.
std::string empty_cell_cause(const std::filesystem::path& file);

// Reads `sheet` (empty: the first worksheet, past any chart sheet) of a workbook. InputError naming
// the file for a broken workbook, a missing sheet (with the names it has) or a sheet beyond Excel's
// limits.
DelimitedText read_spreadsheet(const std::filesystem::path& file, const std::string& sheet);

}  // namespace shpb
