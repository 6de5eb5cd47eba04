#pragma once
// Delimited text as measurement software writes it: any encoding (read as bytes), CRLF/LF/CR,
// comma, semicolon, tab or blank separated, optional decimal comma, quoted fields, header and
// metadata lines. Splits into fields and remembers each row's line number for error messages.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace shpb {

struct TextRow {
  std::size_t line = 0;             // 1-based line number in the file
  std::vector<std::string> fields;  // unquoted, trimmed
};

struct DelimitedText {
  std::filesystem::path file;
  char delimiter = ',';  // '\t', ';', ',' or ' ' (runs of blanks)
  bool decimal_comma = false;
  std::vector<TextRow> rows;  // non-blank lines only
};

// Reads and splits a file; throws InputError if it cannot be read or holds no non-blank line.
DelimitedText read_delimited_text(const std::filesystem::path& file);

// Strict number parsing of one field (the whole field must be a finite number; decimal comma
// accepted when `decimal_comma`). Returns nullopt for anything else, including NaN and inf.
std::optional<double> parse_number(std::string_view field, bool decimal_comma);

// "line 12, column 3" — the place of a field in messages (columns 1-based, as editors count).
std::string text_place(std::size_t line, std::size_t column_index);

}  // namespace shpb
