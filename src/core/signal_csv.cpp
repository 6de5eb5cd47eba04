// Plain CSV/TSV and Tektronix per-channel CSV (signal_formats.hpp).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <exception>
#include <thread>

#include "core/error.hpp"
#include "core/interrupt.hpp"
#include "core/median.hpp"
#include "core/number_format.hpp"
#include "core/signal_formats.hpp"
#include "core/signal_header_clock.hpp"
#include "core/signal_header_units.hpp"
#include "core/signal_spreadsheet.hpp"

namespace shpb {
namespace {

// IEEE 488.2 instruments (SCPI scopes) write ±9.9E37 for an overrange (±∞) and 9.91E37 for not a
// number: no time, voltage or strain of a record comes near them.
bool instrument_marker(double v) { return std::abs(v) >= 9.9e37 && std::abs(v) <= 9.91e37; }

// Records of at least this many rows are parsed on two threads (a thread's start-up, ~50 µs, is
// then below 1 % of the parsing).
constexpr std::size_t kParallelParseRows = 100000;

// What instruments and spreadsheets write for a sample that is not a number: NaN, ±inf, ±∞
// (PicoScope's overrange), Excel's #N/A. Never a header's name.
bool not_a_number_marker(std::string_view f) {
  if (!f.empty() && (f.front() == '-' || f.front() == '+')) f.remove_prefix(1);
  std::string lower(f);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return lower == "nan" || lower == "inf" || lower == "infinity" || lower == "\u221e" ||
         lower == "#n/a";
}

// A row of numbers, where a field may also be empty or a not-a-number marker: a column of NaN (a
// channel not recorded) beside the samples leaves every row a data row. Read columns are checked
// sample by sample (number_at).
bool all_numeric(const TextRow& row, bool decimal_comma) {
  std::size_t numbers = 0;
  for (const auto& f : row.fields) {
    if (f.empty() || not_a_number_marker(f)) continue;
    if (!parse_number(f, decimal_comma)) return false;
    ++numbers;
  }
  return numbers > 0;
}

// Whether a row holds words and no number (text and empty fields only): after the data, a footer
// ("End of data", "# 8001 samples written …"), never a sample, whose time column holds a number.
// A line cut short to a sign or a mark holds no word: refused as a sample.
bool footer_row(const TextRow& row, bool decimal_comma) {
  const auto word = [](std::string_view f) {
    return std::any_of(f.begin(), f.end(), [](unsigned char c) { return std::isalpha(c); });
  };
  return std::none_of(row.fields.begin(), row.fields.end(),
                      [&](std::string_view f) { return parse_number(f, decimal_comma); }) &&
         std::any_of(row.fields.begin(), row.fields.end(), word);
}

std::string describe(const ColumnRef& c) {
  return c.index ? "column index " + std::to_string(*c.index) : "column \"" + c.name + "\"";
}

// Fields of a row up to its last non-empty one (a trailing separator adds none).
std::size_t filled_width(const std::vector<std::string_view>& fields) {
  std::size_t n = fields.size();
  while (n > 0 && fields[n - 1].empty()) --n;
  return n;
}
std::size_t filled_width(const TextRow& row) { return filled_width(row.fields); }

// The first decimal-comma number of a row of a comma-separated file whose fields read as exactly
// `names` numbers once each integer followed by a field of digits is joined into one ("-0",
// "0002" as -0,0002): the row is numbers with decimal commas split in two. Nothing otherwise.
std::optional<std::string> decimal_commas_split(const TextRow& row, std::size_t names) {
  const auto digit = [](char c) { return c >= '0' && c <= '9'; };
  const auto integer = [&](std::string_view f) {
    if (!f.empty() && (f.front() == '-' || f.front() == '+')) f.remove_prefix(1);
    return !f.empty() && std::all_of(f.begin(), f.end(), digit);
  };
  std::optional<std::string> first;
  std::size_t numbers = 0;
  for (std::size_t i = 0, n = filled_width(row); i < n; ++numbers) {
    const std::string joined =
        i + 1 < n ? std::string(row.fields[i]) + "," + std::string(row.fields[i + 1]) : "";
    if (i + 1 < n && integer(row.fields[i]) && !row.fields[i + 1].empty() &&
        digit(row.fields[i + 1].front()) && parse_number(joined, true)) {
      if (!first) first = joined;
      i += 2;
    } else {
      ++i;
    }
  }
  return numbers == names ? first : std::nullopt;
}

// Decimal commas in a comma-separated file split every number in two: columns by index land on
// the halves as names would (refused by resolve), and the integer parts of the times pass for a
// rounded time column. A header of one name is too little to judge the split by.
void refuse_split_decimal_commas(const DelimitedText& text, const TextRow* header,
                                 const TextRow* wider) {
  constexpr std::size_t kNamesToJudgeBy = 2;
  if (!header || !wider || text.delimiter != ',' || is_spreadsheet(text.file) ||
      filled_width(*header) < kNamesToJudgeBy)
    return;
  if (const auto number = decimal_commas_split(*wider, filled_width(*header)))
    throw input_error(
        text.file.string(), "line " + std::to_string(wider->line), "\"" + *number + "\"",
        "a number with a decimal comma in a comma-separated file: the line's " +
            std::to_string(filled_width(*wider)) + " fields read as the " +
            std::to_string(filled_width(*header)) + " columns the header (line " +
            std::to_string(header->line) +
            ") names only with decimal commas, which split every number in two; export with a "
            "semicolon or tab separator");
}

// The rows right above a header that are as wide as it, nearest first, up to the first row of
// another width: the rest of a header of several rows (a TranAX export's channel names over a row
// of quantities, "Zeit;Signal;Signal", over the units), never the metadata above it.
std::vector<TextRow> header_block(const DelimitedText& text, std::size_t header) {
  std::vector<TextRow> block;
  const std::size_t width = filled_width(text.rows[header]);
  for (std::size_t i = header; i-- > 0 && filled_width(text.rows[i]) == width;)
    block.push_back(text.rows[i]);
  return block;
}

// Column index of a reference: by 0-based index, or by exact (then case-insensitive) header name.
// `wider`: the first data row holding more filled fields than the header names, if any. `names`:
// the row above a header of units (PicoScope's "Time,Channel A" over "(ms),(mV)"), searched first;
// then the header, then the rows of its block above (header_block), nearest first.
std::size_t resolve(const DelimitedText& text, const TextRow* header, const TextRow* names,
                    const std::vector<TextRow>& block, const ColumnRef& ref,
                    std::size_t columns_in_data, const TextRow* wider) {
  if (ref.index) {
    if (*ref.index < 0 || static_cast<std::size_t>(*ref.index) >= columns_in_data)
      throw input_error(text.file.string(), "", describe(ref),
                        "no such column (the data rows have " + std::to_string(columns_in_data) +
                            " columns, indices from 0)");
    return static_cast<std::size_t>(*ref.index);
  }
  if (header) {
    // A header naming fewer columns than the data hold cannot say which column a name means:
    // a comma-separated file with decimal commas splits every number in two ("0,5" is "0", "5")
    // and the names would land on the halves.
    if (wider)
      throw input_error(
          text.file.string(), "line " + std::to_string(header->line), describe(ref),
          "the header names " + std::to_string(filled_width(*header)) + " columns but line " +
              std::to_string(wider->line) + " holds " + std::to_string(filled_width(*wider)) +
              ": a name cannot say which column it means; decimal commas in a comma-separated "
              "file split every number in two (export with a semicolon or tab separator), else "
              "give the column as an index");
    auto lower = [](std::string s) {
      std::transform(s.begin(), s.end(), s.begin(),
                     [](unsigned char c) { return std::tolower(c); });
      return s;
    };
    // Exact first; the case-insensitive match only if it is the only one. Two candidates are
    // refused, never one picked silently.
    const auto find = [&](const TextRow& row) -> std::optional<std::size_t> {
      const auto& f = row.fields;
      auto exact = [&](std::string_view h) { return h == ref.name; };
      auto folded = [&](std::string_view h) { return lower(std::string(h)) == lower(ref.name); };
      const auto n_exact = std::count_if(f.begin(), f.end(), exact);
      const auto n_folded = std::count_if(f.begin(), f.end(), folded);
      if (n_exact > 1 || (n_exact == 0 && n_folded > 1))
        throw input_error(text.file.string(), "line " + std::to_string(row.line), describe(ref),
                          "several header columns match this name; rename them so that each is "
                          "unique");
      auto it = n_exact ? std::find_if(f.begin(), f.end(), exact)
                        : std::find_if(f.begin(), f.end(), folded);
      if (it == f.end()) return std::nullopt;
      return static_cast<std::size_t>(it - f.begin());
    };
    if (names)
      if (const auto c = find(*names)) return *c;
    if (const auto c = find(*header)) return *c;
    for (const auto& row : block)
      if (const auto c = find(row)) return *c;
    const TextRow& listed = names ? *names : *header;
    std::string list;
    for (const auto& h : listed.fields) (list += list.empty() ? "\"" : ", \"").append(h) += '"';
    throw input_error(text.file.string(), "line " + std::to_string(listed.line), describe(ref),
                      "no such column; the header has " + list);
  }
  throw input_error(text.file.string(), "", describe(ref),
                    "no such column: the file has no header row (give the column as an index)");
}

// How a number is written: its decimals and its exponent's digits (0: none). A column exported
// in a fixed format ("%.6e", "%.4f", Tektronix's "e-005") writes every value the same way.
struct NumberShape {
  std::size_t decimals = 0;
  std::size_t exponent = 0;
  bool operator==(const NumberShape&) const = default;
};
NumberShape shape_of(std::string_view field, char decimal_mark) {
  const auto e = exponent_mark(field);
  const std::string_view mantissa = field.substr(0, e);
  const auto mark = mantissa.find(decimal_mark);
  const std::string_view exponent =
      e == std::string_view::npos ? std::string_view() : field.substr(e + 1);
  return {mark == std::string_view::npos ? 0 : mantissa.size() - mark - 1,
          e == std::string_view::npos ? 0
                                      : static_cast<std::size_t>(std::count_if(
                                            exponent.begin(), exponent.end(),
                                            [](char ch) { return ch >= '0' && ch <= '9'; }))};
}

// "7 decimals and an exponent of 2 digits"
std::string written(const NumberShape& n) {
  return std::to_string(n.decimals) + (n.decimals == 1 ? " decimal" : " decimals") +
         (n.exponent ? " and an exponent of " + std::to_string(n.exponent) +
                           (n.exponent == 1 ? " digit" : " digits")
                     : "");
}

// Whether column `c` of rows [from, end) is written in one fixed format, `shape` (a row too short
// to hold it has no say).
bool written_alike(const DelimitedText& text, std::size_t from, std::size_t end, std::size_t c,
                   const NumberShape& shape) {
  const char mark = text.decimal_comma ? ',' : '.';
  std::vector<std::string_view> fields;
  for (std::size_t i = from; i < end; ++i) {
    text.rows.fields(i, fields);
    if (c < fields.size() && !(shape_of(fields[c], mark) == shape)) return false;
  }
  return true;
}

// A file that ends inside its last line (no line end after it) may have been cut there. When
// that line still parses ("1.2e-05" cut to "1.2"), the cut shows only in a column written in a
// fixed format: all the other rows' values have the same decimals (and exponent), the last one
// fewer. Such a last line is refused by line and column. A column of varying widths ("%g") gives
// nothing to judge by, and a last line without a line end is otherwise accepted (some exports
// write none).
void refuse_cut_last_line(const DelimitedText& text, std::size_t first_data, std::size_t end,
                          const std::vector<std::size_t>& columns,
                          const std::vector<std::string_view>& names) {
  constexpr std::size_t kRowsToJudgeBy = 2;
  if (!text.last_row_unterminated || end < text.rows.size() ||
      text.rows.size() < first_data + kRowsToJudgeBy + 1)
    return;
  const char mark = text.decimal_comma ? ',' : '.';
  const TextRow& last = text.rows.back();
  for (std::size_t k = 0; k < columns.size(); ++k) {
    const std::size_t c = columns[k];
    const NumberShape cut = shape_of(last.fields[c], mark);
    const NumberShape fixed = shape_of(text.rows[first_data].fields[c], mark);
    if (cut.decimals >= fixed.decimals && cut.exponent >= fixed.exponent &&
        (cut.exponent > 0) == (fixed.exponent > 0))
      continue;
    if (!written_alike(text, first_data + 1, text.rows.size() - 1, c, fixed)) continue;
    throw input_error(
        text.file.string(),
        text_place(last.line, c) + (names[k].empty() ? "" : " (\"" + std::string(names[k]) + "\")"),
        "\"" + std::string(last.fields[c]) + "\"",
        "the file ends inside this line, and this value is written with " + written(cut) +
            " where every other value of the column has " + written(fixed) +
            ": a line cut off (an interrupted export or copy); expected complete rows");
  }
}

// A data row of numbers with more filled fields than the first data row holds has had its columns
// shifted (a decimal comma or a stray separator splits a field in two): read by index, the
// columns after the split would take their neighbours' values. Refused by line; a file with a
// header and columns by name is refused earlier (resolve), with the header to judge by. A row
// with a text beside its numbers (a scope's marker or a note) shifts nothing, and a sheet's
// cells are cells.
void refuse_wider_rows(const DelimitedText& text, std::size_t first_data, std::size_t end) {
  if (is_spreadsheet(text.file)) return;
  const std::size_t width = text.rows[first_data].fields.size();
  const auto number_or_empty = [&](std::string_view f) {
    return f.empty() || parse_number(f, text.decimal_comma).has_value();
  };
  std::vector<std::string_view> fields;
  for (std::size_t i = first_data + 1; i < end; ++i) {
    if (text.rows.max_fields(i) <= width) continue;
    text.rows.fields(i, fields);
    if (const std::size_t filled = filled_width(fields);
        filled > width && std::all_of(fields.begin(), fields.end(), number_or_empty))
      throw input_error(text.file.string(), "line " + std::to_string(text.rows.line(i)),
                        std::to_string(filled) + " fields",
                        "expected at most the " + std::to_string(width) + " of line " +
                            std::to_string(text.rows[first_data].line) +
                            ", the first data row: a decimal comma or a stray separator splits a "
                            "field and shifts the columns after it");
  }
}

// The rows [first_data, end): the time column's stamps (none without one: a clock fills them)
// and the columns `indices`.
RawSignalColumns read_columns(const DelimitedText& text, std::size_t first_data, std::size_t end,
                              const TextRow* header, std::optional<std::size_t> time_index,
                              const std::vector<std::size_t>& indices,
                              const std::vector<std::string>& names) {
  refuse_wider_rows(text, first_data, end);
  RawSignalColumns raw;
  raw.names = names;
  const std::size_t n = end - first_data;
  raw.time.resize(n);
  raw.lines = text.rows.lines().from(first_data);
  raw.values.assign(indices.size(), std::vector<double>(n));
  auto header_name = [&](std::size_t c) {
    return header && c < header->fields.size() ? header->fields[c] : std::string_view();
  };
  const std::string_view time_name = time_index ? header_name(*time_index) : std::string_view();
  std::vector<std::string_view> column_names;
  for (std::size_t c : indices) column_names.push_back(header_name(c));
  // Samples [a, b) into their places; the first bad field of the range throws.
  const auto parse = [&](std::size_t a, std::size_t b) {
    TextRow row;  // one buffer for the range's rows
    for (std::size_t i = a; i < b; ++i) {
      if (i % 65536 == 0) throw_if_interrupted();  // a long record stops within a second
      row.line = text.rows.line(first_data + i);
      text.rows.fields(first_data + i, row.fields);
      if (time_index) raw.time[i] = number_at(text, row, *time_index, time_name);
      for (std::size_t k = 0; k < indices.size(); ++k)
        raw.values[k][i] = number_at(text, row, indices[k], column_names[k]);
    }
  };
  // A long record is parsed in two halves at once (the process's largest single cost on a
  // million rows); an error in the first half is reported before one in the second, so the
  // message names the first bad field either way.
  std::vector<std::size_t> columns;
  std::vector<std::string_view> names_read;
  if (time_index) columns.push_back(*time_index), names_read.push_back(time_name);
  columns.insert(columns.end(), indices.begin(), indices.end());
  names_read.insert(names_read.end(), column_names.begin(), column_names.end());
  if (n < kParallelParseRows) {
    parse(0, n);
    refuse_cut_last_line(text, first_data, end, columns, names_read);
    return raw;
  }
  const std::size_t half = n / 2;
  std::exception_ptr second_error;
  std::thread second([&] {
    try {
      parse(half, n);
    } catch (...) {
      second_error = std::current_exception();
    }
  });
  std::exception_ptr first_error;
  try {
    parse(0, half);
  } catch (...) {
    first_error = std::current_exception();
  }
  second.join();
  if (first_error) std::rethrow_exception(first_error);
  if (second_error) std::rethrow_exception(second_error);
  refuse_cut_last_line(text, first_data, end, columns, names_read);
  return raw;
}

// A number written with the file's other mark. German spreadsheets write 1234 as "1.234",
// English ones as "1,234": in a file of the other decimal mark, read as a decimal it would be a
// thousand times too small.
std::string other_mark(const DelimitedText& text) {
  const std::string mark = text.decimal_comma ? "comma" : "point";
  return std::string(text.decimal_comma ? "a point" : "a comma") +
         " in a file whose decimal mark is the " + mark +
         ": a thousands separator or the other decimal mark; expected numbers with a decimal " +
         mark + " and no thousands separator";
}

// A number whose digits are grouped by thousands ("-1.197,266" in a German file, "1 197,266"
// with a French (narrow) no-break space, "1'197.266" in a Swiss one): what the grouping character
// is, for the message; nullopt for anything else. Never read: "1.234" alone may be either mark.
std::optional<std::string> thousands_separator(std::string_view f, bool decimal_comma) {
  struct Separator {
    std::string_view bytes, name;
  };
  static constexpr Separator kSeparators[] = {{"\xE2\x80\xAF", "narrow no-break space"},
                                              {"\xC2\xA0", "no-break space"},
                                              {"\xE2\x80\x99", "apostrophe"},
                                              {"\xA0", "no-break space (Latin-1)"},
                                              {" ", "space"},
                                              {"'", "apostrophe"},
                                              {".", "point"},
                                              {",", "comma"}};
  const std::string_view mark = decimal_comma ? "," : ".";
  std::string digits;
  std::optional<std::string> found;
  for (std::size_t i = 0; i < f.size();) {
    const auto sep = std::find_if(std::begin(kSeparators), std::end(kSeparators), [&](auto s) {
      return s.bytes != mark && f.substr(i).starts_with(s.bytes);
    });
    const bool between = i > 0 && std::isdigit(static_cast<unsigned char>(f[i - 1]));
    if (sep != std::end(kSeparators) && between) {
      found = std::string(sep->name);
      i += sep->bytes.size();
    } else {
      digits += f[i++];
    }
  }
  if (!found || !parse_number(digits, decimal_comma)) return std::nullopt;
  return found;
}

}  // namespace

double number_at(const DelimitedText& text, const TextRow& row, std::size_t column,
                 std::string_view column_name) {
  if (column < row.fields.size())
    if (const auto v = parse_number(row.fields[column], text.decimal_comma);
        v && !instrument_marker(*v))
      return *v;
  // Not a number: the message (and its place) is only built now.
  const std::string where = text_place(row.line, column) +
                            (column_name.empty() ? "" : " (\"" + std::string(column_name) + "\")");
  if (const auto v = column < row.fields.size()
                         ? parse_number(row.fields[column], text.decimal_comma)
                         : std::nullopt)
    throw input_error(text.file.string(), where, "\"" + std::string(row.fields[column]) + "\"",
                      "an instrument's overrange or not-a-number marker (IEEE 488.2: 9.9E37, "
                      "9.91E37), not a sample; expected a finite sample");
  if (column >= row.fields.size())
    throw input_error(
        text.file.string(), where, "missing value",
        "the row has only " + std::to_string(row.fields.size()) + " fields (truncated line?)");
  const std::string f(row.fields[column]);
  if (f.empty())
    throw input_error(text.file.string(), where, "empty field",
                      "expected a number" + empty_cell_cause(text.file));
  const bool nan = f.find("nan") != std::string::npos || f.find("NaN") != std::string::npos ||
                   f.find("NAN") != std::string::npos;
  if (parse_number(f, !text.decimal_comma))
    throw input_error(text.file.string(), where, "\"" + f + "\"", other_mark(text));
  if (const auto separator = thousands_separator(f, text.decimal_comma))
    throw input_error(
        text.file.string(), where, "\"" + f + "\"",
        "digits grouped by thousands (a " + *separator +
            " between them); expected numbers without a thousands separator (export the "
            "column in a number format without digit grouping)");
  if (f.front() == '=')
    throw input_error(text.file.string(), where, "\"" + f + "\"",
                      "a formula whose value the workbook does not hold (written by a program "
                      "that does not compute formulas); expected a number: open and save the "
                      "workbook in a spreadsheet program");
  throw input_error(
      text.file.string(), where, "\"" + f + "\"",
      nan ? "not a number (NaN) where a finite sample was expected" : "expected a finite number");
}

namespace {

// Why no row of `text` is all numbers, judged on its last row (a data row, if there are any):
// the separator, the decimal mark or a field that is text.
std::string no_numbers_cause(const DelimitedText& text) {
  const TextRow& row = text.rows.back();
  const char* separator = text.delimiter == '\t'  ? "tabs"
                          : text.delimiter == ';' ? "semicolons"
                          : text.delimiter == ',' ? "commas"
                                                  : "blanks";
  std::string read =
      "line " + std::to_string(row.line) + " was read as " + std::to_string(row.fields.size()) +
      (is_spreadsheet(text.file) ? std::string(" cell(s)")
                                 : std::string(" field(s) separated by ") + separator) +
      ", decimal " + (text.decimal_comma ? "comma" : "point");
  for (const auto& f : row.fields) {
    if (f.empty() || parse_number(f, text.decimal_comma)) continue;
    const std::string field = "\"" + std::string(f.substr(0, 40)) + "\"";
    if (parse_number(f, !text.decimal_comma)) return read + ": " + field + ": " + other_mark(text);
    if (is_spreadsheet(text.file))
      return read + ": " + field +
             " is not a number; are the signals on another sheet? (measurement.sheet; by default "
             "the first worksheet)";
    if (text.delimiter == ',' && f.find_first_of(" \t") != std::string_view::npos)
      return read + ": " + field +
             " looks like blank-separated numbers with decimal commas, the comma taken as the "
             "separator; export with a tab or semicolon separator";
    if (row.fields.size() == 1)
      return read + ": the whole line is one field " + field +
             ": values separated by a character other than tab, semicolon, comma or blanks, or a "
             "quoted line with quotes inside it";
    return read + ": " + field + " is not a number";
  }
  return read;
}

// One past the last data row: a footer (rows after the data that hold words and no number) is
// not read, and said.
std::size_t data_end(const DelimitedText& text, std::size_t first,
                     std::vector<std::string>& warnings) {
  std::size_t end = text.rows.size();
  while (end > first + 1 && footer_row(text.rows[end - 1], text.decimal_comma)) --end;
  if (end == text.rows.size()) return end;
  const bool several = end + 1 < text.rows.size();
  warnings.push_back(text.file.string() + ": line" +
                     (several ? "s " + std::to_string(text.rows.line(end)) + "–" +
                                    std::to_string(text.rows.back().line)
                              : " " + std::to_string(text.rows.line(end))) +
                     " after the data hold" + (several ? "" : "s") + " no number (a footer, \"" +
                     std::string(text.rows[end].fields.front().substr(0, 40)) + "\"): not read");
  return end;
}

// A channel header (catman's and other acquisition programs' exports) may hold rows of numbers
// only between the column names and the data: sample rates, channel numbers, unit codes. Such a
// row is shaped as a sample, and read as one it would put a sample rate or a channel number into
// the record. Rows of numbers at the top of the data are therefore header rows, refused by line
// with that cause and the remedy, when a row below them holds no number (a row of units), or
// when they are no samples of the record below them: with a time column, their times off the
// clock of the rows below; without one (measurement.time.interval), a value read off the level
// of the rows below or written in another form than the whole column below. Never read. A
// channel header holds a handful of rows; a record's samples are thousands.
constexpr std::size_t kHeaderRowsOfNumbers = 16;
// The rows below that must lie on one uniform clock to judge the rows above by it.
constexpr std::size_t kClockRows = 4;
// A record's first samples are its rest before the pulse (at least 10, which the reduction needs
// to read its rest level): a row above them lies among the next ones, within this many times
// their range of their median (or of the column's digitizer step, on which a quiet record's
// samples may all read one level). Gaussian noise puts a sample so far from 16 others' median in
// none of 2·10⁶ draws (3 × their range: none either; 2 ×: 1.3·10⁻⁵); a header's sample rate,
// sample count or channel number in volts lies hundreds of ranges off.
constexpr std::size_t kLevelRows = 16;
constexpr double kLevelRanges = 4;

// Lines [first, first + rows) named for a message: "line 3" or "lines 3–4".
std::string lines_named(const DelimitedText& text, std::size_t first, std::size_t rows) {
  const std::string from = std::to_string(text.rows.line(first));
  return rows == 1 ? "line " + from
                   : "lines " + from + "–" + std::to_string(text.rows.line(first + rows - 1));
}

// Why rows [first, first + rows) of numbers are not read, and what to do.
std::string header_rows_cause(const DelimitedText& text, std::size_t first, std::size_t rows) {
  return lines_named(text, first, rows) +
         (first > 0 ? " under the header (line " + std::to_string(text.rows.line(first - 1)) + ")"
                    : "") +
         (rows == 1 ? " holds" : " hold") +
         " numbers only, which cannot be told from samples (a header's sample count, sample rates, "
         "channel numbers or unit codes";
}

// Rows [first, first + rows) refused as a channel header's: the value of the first one in
// `column` (named `name`) is no sample of the record below, `why`.
[[noreturn]] void refuse_header_rows(const DelimitedText& text, std::size_t first, std::size_t rows,
                                     std::size_t column, std::string_view name,
                                     const std::string& why) {
  const TextRow row = text.rows[first];
  throw input_error(
      text.file.string(),
      text_place(row.line, column) + (name.empty() ? "" : " (\"" + std::string(name) + "\")"),
      "\"" + std::string(row.fields[column]) + "\"",
      why + ": " + header_rows_cause(text, first, rows) +
          ", or samples out of place); expected samples from the first row of "
          "numbers on: delete " +
          lines_named(text, first, rows) + " from the file, or export without the channel header");
}

// A sample count alone on its line at the top of the numbers (scope exports that write the number
// of points first, above the names or the samples): a header's, not read, when it is the number of
// rows of numbers from the next one to the data's end (said in a warning); refused when it is not
// and the rows below are wider (so it is no sample of theirs): rows lost or added after the
// export, or another header's number. Returns the row after it (0 if it is none): the data's top.
std::size_t after_sample_count(const DelimitedText& text, std::size_t first,
                               std::vector<std::string>& warnings) {
  const TextRow row = text.rows[first];
  const std::string_view f = row.fields.empty() ? std::string_view() : row.fields.front();
  if (filled_width(row) != 1 || f.empty() || f.size() > 12 ||
      !std::all_of(f.begin(), f.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return 0;
  std::size_t data = first + 1;
  while (data < text.rows.size() && !all_numeric(text.rows[data], text.decimal_comma)) ++data;
  if (data == text.rows.size()) return 0;
  std::vector<std::string> footer;
  const std::size_t samples = data_end(text, data, footer) - data;
  const std::string rows = lines_named(text, data, samples);
  if (std::stoull(std::string(f)) == samples) {
    warnings.push_back(text.file.string() + ": line " + std::to_string(row.line) + " holds " +
                       std::string(f) + " alone, the number of samples below it (" + rows +
                       "): read as the header's sample count");
    return first + 1;
  }
  if (filled_width(text.rows[data]) > 1)
    throw input_error(
        text.file.string(), "line " + std::to_string(row.line), "\"" + std::string(f) + "\"",
        "a number alone on its line above rows of " +
            std::to_string(filled_width(text.rows[data])) +
            " fields: a header's sample count, but " + rows + " hold " + std::to_string(samples) +
            " samples (rows lost or added after the export, or another number of "
            "the header); expected the number of samples below it");
  return 0;
}

void refuse_numbers_above_header_rows(const DelimitedText& text, std::size_t first,
                                      std::size_t end) {
  const std::size_t last = std::min(end, first + kHeaderRowsOfNumbers + 1);
  for (std::size_t r = first + 1; r < last; ++r) {
    const TextRow row = text.rows[r];
    if (all_numeric(row, text.decimal_comma)) continue;
    // A sample with a marker ("OVER" beside its time, NaN throughout) is read as one.
    if (!footer_row(row, text.decimal_comma) ||
        std::all_of(row.fields.begin(), row.fields.end(),
                    [](std::string_view f) { return f.empty() || not_a_number_marker(f); }))
      return;
    const std::string lines = lines_named(text, first, r - first);
    throw input_error(
        text.file.string(), "line " + std::to_string(row.line),
        "\"" + std::string(row.fields.front().substr(0, 40)) + "\"",
        "no number in this row, above the samples: " + header_rows_cause(text, first, r - first) +
            "); expected the samples below the header rows: delete " + lines +
            " from the file, or export without the channel header");
  }
}

void refuse_rows_off_the_clock(const DelimitedText& text, std::size_t first, std::size_t end,
                               std::size_t time_index, std::string_view time_name, double unit_s) {
  const std::size_t n = std::min(end - first, kHeaderRowsOfNumbers + kClockRows);
  std::vector<double> t(n), digit(n);  // each row's time and the unit of its last digit
  std::vector<std::string_view> fields;
  for (std::size_t i = 0; i < n; ++i) {
    text.rows.fields(first + i, fields);
    const auto v = time_index < fields.size() ? parse_number(fields[time_index], text.decimal_comma)
                                              : std::nullopt;
    if (!v) return;  // refused by line and column when read
    t[i] = *v;
    digit[i] = printed_step(fields[time_index], text.decimal_comma);
  }
  for (std::size_t j = 0; j + kClockRows <= n; ++j) {
    const double dt = (t[j + kClockRows - 1] - t[j]) / static_cast<double>(kClockRows - 1);
    bool uniform = dt > 0;
    for (std::size_t k = j; uniform && k + 1 < j + kClockRows; ++k)
      uniform = std::abs(t[k + 1] - t[k] - dt) <= kAutoResampleJitter * dt;
    if (!uniform) continue;
    // The rows above, each where the clock puts it within the jitter and the stamps' rounding
    // (their finest digit: "0" is as exact as "1e-07"), by every step back to it, and a digit:
    // samples, or the clock's own faults (a gap, a jump) that the time base judges.
    const double rounding =
        *std::min_element(digit.begin() + static_cast<std::ptrdiff_t>(j),
                          digit.begin() + static_cast<std::ptrdiff_t>(j + kClockRows));
    bool on_clock = true;
    for (std::size_t i = 0; i < j && on_clock; ++i) {
      const auto back = static_cast<double>(j - i);
      on_clock = std::abs(t[i] - (t[j] - back * dt)) <=
                 back * (kAutoResampleJitter * dt + rounding) + rounding;
    }
    if (on_clock) return;
    refuse_header_rows(text, first, j, time_index, time_name,
                       "not on the clock of the samples below (every " +
                           format_number(dt * unit_s) + " s from " + format_number(t[j] * unit_s) +
                           " s at line " + std::to_string(text.rows.line(first + j)) + ")");
  }
}

// The values of column `c` in rows [from, end) that are numbers.
std::vector<double> column_values(const DelimitedText& text, std::size_t from, std::size_t end,
                                  std::size_t c) {
  std::vector<double> v;
  std::vector<std::string_view> fields;
  for (std::size_t i = from; i < end; ++i) {
    text.rows.fields(i, fields);
    if (c < fields.size())
      if (const auto x = parse_number(fields[c], text.decimal_comma)) v.push_back(*x);
  }
  return v;
}

// Why row r's value in column c is no sample of the record in the rows below it (nullopt: it may
// be one): off their level (kLevelRanges), or written in another form than the whole column below
// when that is written in one fixed format ("%.6e" throughout, a channel number "1" above).
std::optional<std::string> off_the_record(const DelimitedText& text, std::size_t r, std::size_t end,
                                          std::size_t c) {
  std::vector<std::string_view> fields;
  text.rows.fields(r, fields);
  const auto v = c < fields.size() ? parse_number(fields[c], text.decimal_comma) : std::nullopt;
  if (!v) return std::nullopt;  // refused by line and column when read
  const std::string_view field = fields[c];
  const std::vector<double> below =
      column_values(text, r + 1, std::min(end, r + 1 + kLevelRows), c);
  if (below.size() < kLevelRows) return std::nullopt;
  const auto [low, high] = std::minmax_element(below.begin(), below.end());
  const double level = median(below), off = std::abs(*v - level);
  if (off > kLevelRanges * (*high - *low)) {
    // The column's digitizer step: the smallest difference of its distinct values below.
    std::vector<double> all = column_values(text, r + 1, end, c);
    std::sort(all.begin(), all.end());
    double step = 0;
    for (std::size_t i = 1; i < all.size(); ++i)
      if (all[i] > all[i - 1] && (step == 0 || all[i] - all[i - 1] < step))
        step = all[i] - all[i - 1];
    if (off > kLevelRanges * std::max(*high - *low, step))
      return "off the level of the samples below (" + format_number(level) + ", from " +
             format_number(*low) + " to " + format_number(*high) + " over " +
             lines_named(text, r + 1, kLevelRows) + ")";
  }
  const char mark = text.decimal_comma ? ',' : '.';
  text.rows.fields(r + 1, fields);
  if (c >= fields.size()) return std::nullopt;
  const NumberShape shape = shape_of(field, mark), fixed = shape_of(fields[c], mark);
  if (shape == fixed || !written_alike(text, r + 2, end, c, fixed)) return std::nullopt;
  return "written with " + written(shape) + " where every value below it in the column has " +
         written(fixed) + " (lines " + std::to_string(text.rows.line(r + 1)) + "–" +
         std::to_string(text.rows.line(end - 1)) + ")";
}

// Without a time column: the top rows, each judged against the rows below it in every column
// read (off_the_record), down to the first that lies among them; the rows above it are refused.
void refuse_rows_off_the_level(const DelimitedText& text, std::size_t first, std::size_t end,
                               const std::vector<std::size_t>& columns,
                               const std::vector<std::string_view>& names) {
  std::optional<std::pair<std::size_t, std::string>> refused;  // the first row's column and why
  std::size_t r = first;
  for (; r < std::min(end, first + kHeaderRowsOfNumbers); ++r) {
    std::optional<std::pair<std::size_t, std::string>> off;
    for (std::size_t k = 0; k < columns.size() && !off; ++k)
      if (auto why = off_the_record(text, r, end, columns[k])) off = {k, std::move(*why)};
    if (!off) break;
    if (!refused) refused = off;
  }
  if (refused)
    refuse_header_rows(text, first, r - first, columns[refused->first], names[refused->first],
                       refused->second);
}
// Whether a header field names a time column: "Time", "TIME", "t", or a time unit ("Time (ms)",
// "time_s", a unit row's "(us)").
bool names_time(std::string_view field) {
  std::string lower(field);
  for (auto& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return lower == "t" || lower.rfind("time", 0) == 0 ||
         header_unit(field, time_unit, kTimeUnitCuts).has_value();
}

// RawSignalColumns::time_column_shown of the column read as the time: the header (or the row of
// names above a unit row) names time there, and no channel is read from it.
bool time_column_shown(const TextRow* header, const TextRow* named,
                       std::optional<std::size_t> time_index,
                       const std::vector<std::size_t>& channels) {
  if (!time_index || std::find(channels.begin(), channels.end(), *time_index) != channels.end())
    return false;
  for (const TextRow* row : {header, named})
    if (row && *time_index < row->fields.size() && names_time(row->fields[*time_index]))
      return true;
  return false;
}

// A header that names the time column's unit must agree with the unit it is read in: a column in
// ms read as seconds passes the sample-interval check at 10 MHz and above (0.1 ms -> 1e-4 s).
void check_time_unit(const DelimitedText& text, const TextRow& header, std::size_t time_index,
                     double time_unit_s) {
  if (time_index >= header.fields.size()) return;
  if (const auto unit = header_unit(header.fields[time_index], time_unit, kTimeUnitCuts);
      unit && std::abs(unit->second / time_unit_s - 1) > kSameUnit)
    throw input_error(text.file.string(), text_place(header.line, time_index),
                      "\"" + std::string(header.fields[time_index]) + "\"",
                      "the header gives the time in " + unit->first +
                          ", but the column is read in units of " + format_number(time_unit_s) +
                          " s (measurement.time.unit, default s): set \"time\": {\"unit\": \"" +
                          unit->first + "\"} or correct the header");
}

}  // namespace

RawSignalColumns read_csv_columns(const DelimitedText& text, const SignalRequest& request) {
  // Data start at the first row whose fields are all numbers; the row before is the header.
  std::size_t first = 0;
  while (first < text.rows.size() && !all_numeric(text.rows[first], text.decimal_comma)) ++first;
  if (first == text.rows.size())
    throw input_error(text.file.string(), "line " + std::to_string(text.rows.back().line),
                      "no numeric rows",
                      "expected rows of numbers after the header; " + no_numbers_cause(text));
  std::vector<std::string> warnings;
  const std::size_t top = after_sample_count(text, first, warnings);
  for (first = std::max(first, top);
       first < text.rows.size() && !all_numeric(text.rows[first], text.decimal_comma);)
    ++first;
  const std::size_t width = text.rows[first].fields.size();
  const std::size_t end = data_end(text, first, warnings);
  refuse_numbers_above_header_rows(text, first, end);
  const auto [clock, trace_names] = file_clock(text, first, request, warnings);
  ColumnRef time_ref = request.time_column;
  if (time_ref.name.empty() && !time_ref.index && !clock) time_ref.index = 0;
  // Rows just above that are shaped as data are data rows with a text in some field (a scope's
  // "OVER", "NaN" or "∞" in its first samples), never the header: taken as the header they
  // would drop those samples unseen, or hide the real header. Such a row has the data rows'
  // width and a number in the time column (by index), or, with the time column named, lacks
  // that name and is at least half numbers. Its fields are then read as every sample's: a text
  // in a column read is refused by line and column, one in a column not read is left alone.
  const auto data_shaped = [&](const TextRow& row) {
    if (row.fields.size() != width) return false;
    if (time_ref.index)
      return static_cast<std::size_t>(*time_ref.index) < width &&
             parse_number(row.fields[static_cast<std::size_t>(*time_ref.index)],
                          text.decimal_comma);
    std::size_t numbers = 0, filled = 0;
    for (const auto& f : row.fields) {
      if (!clock && f == time_ref.name) return false;
      for (const auto& c : request.columns)
        if (clock && !c.name.empty() && f == c.name) return false;
      filled += !f.empty();
      numbers += parse_number(f, text.decimal_comma).has_value();
    }
    return numbers > 0 && 2 * numbers >= filled;
  };
  while (first > top && data_shaped(text.rows[first - 1])) --first;
  const std::optional<TextRow> header_row =
      first > 0 ? std::optional(text.rows[first - 1]) : std::nullopt;
  const TextRow* header = header_row ? &*header_row : nullptr;
  std::optional<TextRow> wider_row;
  if (header) {
    std::vector<std::string_view> fields;
    for (std::size_t i = first; i < end && !wider_row; ++i) {
      if (text.rows.max_fields(i) <= filled_width(*header)) continue;
      text.rows.fields(i, fields);
      if (filled_width(fields) > filled_width(*header)) wider_row = text.rows[i];
    }
  }
  const TextRow* wider = wider_row ? &*wider_row : nullptr;
  if ((time_ref.index || clock) &&
      std::all_of(request.columns.begin(), request.columns.end(),
                  [](const ColumnRef& c) { return c.index.has_value(); }))
    refuse_split_decimal_commas(text, header, wider);
  // Yokogawa's trace names stand over their samples when the data rows keep the key column (empty,
  // or the time): as wide as the names row.
  const std::optional<TextRow> above =
      header && first >= 2 ? std::optional(text.rows[first - 2]) : std::nullopt;
  const TextRow* names_row =
      trace_names && filled_width(*trace_names) <= width                            ? &*trace_names
      : above && unit_row(*header) && filled_width(*above) == filled_width(*header) ? &*above
                                                                                    : nullptr;
  const TextRow* named = names_row ? names_row : header;  // what names each column
  const std::vector<TextRow> block =
      header ? header_block(text, first - 1) : std::vector<TextRow>();
  const std::optional<std::size_t> time_index =
      clock ? std::nullopt
            : std::optional(resolve(text, header, names_row, block, time_ref, width, wider));
  if (header && time_index) check_time_unit(text, *header, *time_index, request.time_unit_s);
  std::vector<std::size_t> indices;
  std::vector<std::string> names;
  for (const auto& c : request.columns) {
    indices.push_back(resolve(text, header, names_row, block, c, width, wider));
    names.push_back(named && indices.back() < named->fields.size()
                        ? std::string(named->fields[indices.back()])
                        : "column " + std::to_string(indices.back()));
  }
  const auto name_of = [&](std::size_t c) {
    return named && c < named->fields.size() ? named->fields[c] : std::string_view();
  };
  if (!time_index) {
    std::vector<std::string_view> header_names;
    for (std::size_t c : indices) header_names.push_back(name_of(c));
    refuse_rows_off_the_level(text, first, end, indices, header_names);
  } else if (request.resample.mode != TimeResample::kAlways) {
    refuse_rows_off_the_clock(text, first, end, *time_index, name_of(*time_index),
                              request.time_unit_s);
  }
  if (header)
    for (std::size_t k = 0; k < request.column_units.size(); ++k)
      check_value_unit(text, *header, indices[k], request.column_units[k]);
  RawSignalColumns raw = read_columns(text, first, end, named, time_index, indices, names);
  raw.time_column_shown = time_column_shown(header, named, time_index, indices);
  if (clock) {  // sample i at start + i·interval
    for (std::size_t i = 0; i < raw.time.size(); ++i) {
      raw.time[i] = clock->start_s + static_cast<double>(i) * clock->interval_s;
      // A start so far from 0 that a double cannot tell its samples' times apart.
      if (i > 0 && !(raw.time[i] > raw.time[i - 1]))
        throw input_error(text.file.string(), "measurement.time.start (or the header's HOffset)",
                          format_number(clock->start_s) + " s",
                          "too far from 0 for samples " + format_number(clock->interval_s) +
                              " s apart to have distinct times; expected the first sample's "
                              "time, e.g. a pre-trigger \"-20 us\"");
    }
    raw.time_from_header = true;
    raw.header_dt = clock->interval_s;
  }
  raw.warnings = std::move(warnings);
  return raw;
}

RawSignalColumns read_tektronix_columns(const DelimitedText& text, const SignalRequest& request) {
  constexpr std::size_t kTimeColumn = 3, kVoltColumn = 4;
  std::vector<std::size_t> indices;
  std::vector<std::string> names;
  // Channels laid side by side (a sheet with several Tektronix blocks: time 3, volts 4, then
  // 8, 9, ...) are plain columns of numbers below metadata: the CSV reader takes them by index.
  const std::string as_csv =
      "; several channels side by side (a workbook sheet holding Tektronix blocks) are read with "
      "\"format\": \"csv\", \"time\": {\"column\": 3} and each channel's volts column by "
      "index (4, 9, ...)";
  for (const auto& c : request.columns) {
    if (c.index && (*c.index < 0 || *c.index > static_cast<int>(kVoltColumn)))
      throw input_error(text.file.string(), "", describe(c),
                        "a Tektronix channel file has columns 0–4 (time 3, volts 4)" + as_csv);
    if (!c.index && !c.name.empty())
      throw input_error(
          text.file.string(), "", describe(c),
          "a Tektronix channel file has no header: give the column as an index (4)" + as_csv);
    indices.push_back(c.index ? static_cast<std::size_t>(*c.index) : kVoltColumn);
    names.push_back(text.file.filename().string());
  }
  const std::size_t time_index = request.time_column.index
                                     ? static_cast<std::size_t>(*request.time_column.index)
                                     : kTimeColumn;
  RawSignalColumns raw =
      read_columns(text, 0, text.rows.size(), nullptr, time_index, indices, names);
  raw.time_column_shown = true;  // the format's own
  return raw;
}

}  // namespace shpb
