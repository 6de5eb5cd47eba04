#include "core/signal_text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>

#include "core/error.hpp"
#include "core/input_file.hpp"
#include "core/output_folder.hpp"

namespace shpb {
namespace {

constexpr std::size_t kSniffLines = 200;  // lines inspected to choose delimiter and decimal mark

std::string trim(std::string_view s) {
  const auto not_blank = [](char c) { return c != ' ' && c != '\t' && c != '\r' && c != '\n'; };
  auto b = std::find_if(s.begin(), s.end(), not_blank);
  auto e = std::find_if(s.rbegin(), s.rend(), not_blank).base();
  if (b >= e) return {};
  std::string out(b, e);
  if (out.size() >= 2 && out.front() == '"' && out.back() == '"')
    out = out.substr(1, out.size() - 2);
  return out;
}

std::vector<std::string> split(std::string_view line, char delimiter) {
  std::vector<std::string> fields;
  if (delimiter == ' ') {
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      if (i >= line.size()) break;
      std::size_t j = i;
      while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
      fields.push_back(trim(line.substr(i, j - i)));
      i = j;
    }
    return fields;
  }
  bool quoted = false;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= line.size(); ++i) {
    if (i < line.size() && line[i] == '"') quoted = !quoted;
    if (i == line.size() || (line[i] == delimiter && !quoted)) {
      fields.push_back(trim(line.substr(start, i - start)));
      start = i + 1;
    }
  }
  return fields;
}

bool looks_like_decimal_comma_number(std::string_view f) {
  // 12,5 or -0,0012 or 1,5E-03: digits, one comma, digits, optional exponent; no '.'
  const auto comma = f.find(',');
  if (comma == std::string_view::npos || f.find('.') != std::string_view::npos) return false;
  return parse_number(std::string(f.substr(0, comma)) + "." + std::string(f.substr(comma + 1)),
                      false)
      .has_value();
}

}  // namespace

std::optional<double> parse_number(std::string_view field, bool decimal_comma) {
  std::string s(field);
  if (decimal_comma) std::replace(s.begin(), s.end(), ',', '.');
  if (s.empty()) return std::nullopt;
  const char* b = s.data();
  if (*b == '+') ++b;
  double v = 0;
  const auto [end, ec] = std::from_chars(b, s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::string text_place(std::size_t line, std::size_t column_index) {
  return "line " + std::to_string(line) + ", column " + std::to_string(column_index + 1);
}

DelimitedText read_delimited_text(const std::filesystem::path& file) {
  // Type (no FIFO or device) and size checked before reading: 1 GiB is far beyond any record.
  std::string bytes =
      read_input_file(file, file.string(), "a signal file", std::uintmax_t{1} << 30);
  // Byte order marks: UTF-8 is dropped (spreadsheets write it); UTF-16 text is refused by name
  // rather than failing later on the NUL bytes between its characters.
  if (bytes.rfind("\xEF\xBB\xBF", 0) == 0) bytes.erase(0, 3);
  if (bytes.rfind("\xFF\xFE", 0) == 0 || bytes.rfind("\xFE\xFF", 0) == 0 ||
      bytes.find('\0') != std::string::npos)
    throw input_error(file.string(), "line 1", "UTF-16 or binary data",
                      "expected text (ASCII, UTF-8 or Latin-1); save the file as UTF-8 or CSV");

  // Lines (LF, CRLF or lone CR) with their numbers.
  std::vector<std::pair<std::size_t, std::string_view>> lines;
  std::size_t line_no = 1, start = 0;
  for (std::size_t i = 0; i <= bytes.size(); ++i) {
    const bool end = i == bytes.size();
    if (end || bytes[i] == '\n' || bytes[i] == '\r') {
      if (line_no % 65536 == 0) throw_if_interrupted();  // a long record stops within a second
      std::string_view l(bytes.data() + start, i - start);
      if (l.find_first_not_of(" \t") != std::string_view::npos) lines.emplace_back(line_no, l);
      if (!end && bytes[i] == '\r' && i + 1 < bytes.size() && bytes[i + 1] == '\n') ++i;
      start = i + 1;
      ++line_no;
    }
  }
  if (lines.empty())
    throw input_error(file.string(), "line 1", "empty file", "expected signal rows");

  DelimitedText text;
  text.file = file;
  // Delimiter: the one present in most of the first lines (tab beats semicolon beats comma).
  std::size_t tabs = 0, semis = 0, commas = 0;
  const std::size_t sniff = std::min(lines.size(), kSniffLines);
  for (std::size_t i = 0; i < sniff; ++i) {
    const auto l = lines[i].second;
    tabs += l.find('\t') != std::string_view::npos;
    semis += l.find(';') != std::string_view::npos;
    commas += l.find(',') != std::string_view::npos;
  }
  if (tabs * 2 > sniff)
    text.delimiter = '\t';
  else if (semis * 2 > sniff)
    text.delimiter = ';';
  else if (commas * 2 > sniff)
    text.delimiter = ',';
  else
    text.delimiter = ' ';

  text.rows.reserve(lines.size());
  for (const auto& [n, l] : lines) {
    if (text.rows.size() % 65536 == 0) throw_if_interrupted();
    text.rows.push_back({n, split(l, text.delimiter)});
  }

  // Decimal comma: only possible when the comma is not the delimiter; decided on the last
  // sniffed rows (data, not header) by numbers with a comma against numbers with a point.
  if (text.delimiter != ',') {
    std::size_t with_comma = 0, numbers = 0;
    const std::size_t from = text.rows.size() > sniff ? text.rows.size() - sniff : 0;
    for (std::size_t i = from; i < text.rows.size(); ++i)
      for (const auto& f : text.rows[i].fields) {
        if (looks_like_decimal_comma_number(f))
          ++with_comma;
        else if (f.find('.') != std::string::npos && parse_number(f, false))
          ++numbers;
      }
    text.decimal_comma = with_comma > numbers;
  }
  return text;
}

}  // namespace shpb
