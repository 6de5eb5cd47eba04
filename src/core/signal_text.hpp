#pragma once
// Delimited text as measurement software writes it: any encoding (read as bytes), CRLF/LF/CR,
// comma, semicolon, tab or blank separated, optional decimal comma, quoted fields, header and
// metadata lines. Splits into fields and remembers each row's line number for error messages.
// The fields are views into the file's bytes, kept once by the DelimitedText (no string per cell).
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace shpb {

struct TextRow {
  std::size_t line = 0;                      // 1-based line number in the file
  std::span<const std::string_view> fields;  // unquoted, trimmed (views into the file's bytes)
};

struct DelimitedText {
  std::filesystem::path file;
  char delimiter = ',';  // '\t', ';', ',' or ' ' (runs of blanks)
  bool decimal_comma = false;
  std::vector<TextRow> rows;           // non-blank lines only
  bool last_row_unterminated = false;  // the file ends inside its last row (no line end after it)
  // What the rows view: the file's bytes and every row's fields, one after the other (shared so
  // that copies and moves of the text keep the views valid).
  std::shared_ptr<const std::string> bytes;
  std::shared_ptr<const std::vector<std::string_view>> all_fields;
};

// Sets `text.decimal_comma` from its last rows' numbers (read_delimited_text does it for a file;
// a workbook's sheet, whose cells may be text with decimal commas, after its rows are made).
void detect_decimal_comma(DelimitedText& text);

// Reads and splits a file; throws InputError if it cannot be read or holds no non-blank line.
DelimitedText read_delimited_text(const std::filesystem::path& file);

// Strict number parsing of one field (the whole field must be a finite number; with
// `decimal_comma`, a decimal comma and no point). Returns nullopt for anything else, including
// NaN and inf.
std::optional<double> parse_number(std::string_view field, bool decimal_comma);

// "line 12, column 3" — the place of a field in messages (columns 1-based, as editors count).
std::string text_place(std::size_t line, std::size_t column_index);

}  // namespace shpb
