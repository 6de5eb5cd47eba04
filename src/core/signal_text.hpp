#pragma once
// Delimited text as measurement software writes it: any encoding (read as bytes), CRLF/LF/CR,
// comma, semicolon, tab or blank separated, optional decimal comma, quoted fields, header and
// metadata lines. Remembers where each row starts and its line number for error messages; a
// row is split into fields when it is read (views into the file's bytes, kept once by the
// DelimitedText). A deep-memory record (tens of millions of rows) thus costs its bytes and 4
// bytes a row, not a view (16 bytes) per field and a row record (24) per row.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/line_map.hpp"

namespace shpb {

struct TextRow {
  std::size_t line = 0;                  // 1-based line number in the file
  std::vector<std::string_view> fields;  // unquoted, trimmed (views into the file's bytes)
};

// The non-blank rows of a text, each split on demand: rows[i] is a TextRow (by value).
class TextRows {
 public:
  std::size_t size() const { return lines_.size(); }
  bool empty() const { return lines_.empty(); }
  TextRow operator[](std::size_t i) const {
    TextRow row;
    row.line = lines_[i];
    fields(i, row.fields);
    return row;
  }
  TextRow front() const { return (*this)[0]; }
  TextRow back() const { return (*this)[size() - 1]; }
  std::size_t line(std::size_t i) const { return lines_[i]; }
  const LineMap& lines() const { return lines_; }
  // Row i's fields into `out` (cleared first): a loop over many rows reuses one buffer.
  void fields(std::size_t i, std::vector<std::string_view>& out) const;
  // At least the number of row i's fields, counted without splitting it (its separators and
  // one): a scan for rows wider than a width skips the others at the cost of a byte count.
  std::size_t max_fields(std::size_t i) const;
  // What the rows cost beyond the text's bytes: the start offsets and line runs of a file, the
  // field views of a sheet.
  std::size_t bookkeeping_bytes() const;

  // A file's rows: one line each, from `start` to its line end, split at `delimiter`.
  void add_line(std::uint32_t start, std::size_t line) {
    starts_.push_back(start), lines_.push_back(line);
  }
  // A sheet's rows: their cells, as views into bytes kept by the text.
  void add_cells(std::size_t line, std::vector<std::string_view> cells);
  void reserve(std::size_t rows) { starts_.reserve(rows); }
  void set_text(std::string_view bytes, char delimiter, bool has_cr) {
    bytes_ = bytes, delimiter_ = delimiter, has_cr_ = has_cr;
  }

 private:
  std::string_view line_text(std::size_t i) const;  // a file's row i, without its line end
  std::string_view bytes_;
  char delimiter_ = ',';
  bool has_cr_ = false;
  std::vector<std::uint32_t> starts_;    // files: each row's first byte
  std::vector<std::string_view> cells_;  // sheets: every row's cells, one after another
  std::vector<std::size_t> cell_ends_;   // sheets: one past each row's last cell
  LineMap lines_;
};

struct DelimitedText {
  std::filesystem::path file;
  char delimiter = ',';  // '\t', ';', ',' or ' ' (runs of blanks)
  bool decimal_comma = false;
  TextRows rows;                       // non-blank lines only
  bool last_row_unterminated = false;  // the file ends inside its last row (no line end after it)
  // What the rows view: the file's bytes (shared so that copies and moves of the text keep the
  // views valid).
  std::shared_ptr<const std::string> bytes;
};

// Sets `text.decimal_comma` from its last rows' numbers (read_delimited_text does it for a file;
// a workbook's sheet, whose cells may be text with decimal commas, after its rows are made).
void detect_decimal_comma(DelimitedText& text);

// Reads and splits a file; throws InputError if it cannot be read or holds no non-blank line.
DelimitedText read_delimited_text(const std::filesystem::path& file);

// Strict number parsing of one field (the whole field must be a finite number; with
// `decimal_comma`, a decimal comma and no point; Fortran's "1.0D-03" is 1.0E-03). Returns nullopt
// for anything else, including NaN and inf.
std::optional<double> parse_number(std::string_view field, bool decimal_comma);

// Where a number's exponent starts: its E (or e), or Fortran's D of a DOUBLE PRECISION value
// ("1.0D-03", which parse_number reads as 1.0E-03); npos without one.
std::size_t exponent_mark(std::string_view field);

// The unit of the last digit a number is written with: 1e-6 for "-0.000100", 1e-7 for
// "1.25E-05", 1 for "42" (a stamp printed so lies within half of it of the value it rounds).
double printed_step(std::string_view field, bool decimal_comma);

// "line 12, column 3" — the place of a field in messages (columns 1-based, as editors count).
std::string text_place(std::size_t line, std::size_t column_index);

}  // namespace shpb
