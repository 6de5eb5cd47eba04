#include "core/signal_text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>

#include "core/error.hpp"
#include "core/input_file.hpp"
#include "core/interrupt.hpp"

namespace shpb {
namespace {

constexpr std::size_t kSniffLines = 200;  // lines inspected to choose delimiter and decimal mark

std::string_view trim_field(std::string_view s) {
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  std::size_t b = 0, e = s.size();
  while (b < e && blank(s[b])) ++b;
  while (e > b && blank(s[e - 1])) --e;
  std::string_view out = s.substr(b, e - b);
  if (out.size() >= 2 && out.front() == '"' && out.back() == '"')
    out = out.substr(1, out.size() - 2);
  return out;
}

// Appends the fields of one line to `fields`.
void split(std::string_view line, char delimiter, std::vector<std::string_view>& fields) {
  // A line that is one quoted field with no quote inside (some exports, e.g. TranAX's, quote
  // each whole line): its inside is the line.
  if (const auto b = line.find_first_not_of(" \t"), e = line.find_last_not_of(" \t");
      b != std::string_view::npos && e > b && line[b] == '"' && line[e] == '"' &&
      line.find('"', b + 1) == e)
    line = line.substr(b + 1, e - b - 1);
  if (delimiter == ' ') {
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      if (i >= line.size()) break;
      std::size_t j = i;
      while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
      fields.push_back(trim_field(line.substr(i, j - i)));
      i = j;
    }
    return;
  }
  if (line.find('"') == std::string_view::npos) {  // no quotes: from delimiter to delimiter
    std::size_t start = 0;
    for (;;) {
      const std::size_t d = line.find(delimiter, start);
      fields.push_back(trim_field(line.substr(start, d == std::string_view::npos ? d : d - start)));
      if (d == std::string_view::npos) return;
      start = d + 1;
    }
  }
  bool quoted = false;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= line.size(); ++i) {
    if (i < line.size() && line[i] == '"') quoted = !quoted;
    if (i == line.size() || (line[i] == delimiter && !quoted)) {
      fields.push_back(trim_field(line.substr(start, i - start)));
      start = i + 1;
    }
  }
}

// Clinger's fast path: a decimal of at most 19 significant digits whose value is m·10^k with
// m < 2^53 and |k| ≤ 22 is m and 10^|k| exactly, so one multiplication or division rounds it
// correctly — the value std::from_chars gives. Anything else (more digits, larger exponents,
// other syntax) returns nullopt and is left to std::from_chars.
std::optional<double> exact_short_decimal(const char* p, const char* end) {
  static constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                      1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                      1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  constexpr std::uint64_t kExactMantissa = std::uint64_t{1} << 53;
  constexpr int kMaxDigits = 19;
  const bool negative = p < end && *p == '-';
  if (negative) ++p;
  const auto digit = [](char c) { return static_cast<unsigned>(c - '0') <= 9; };
  std::uint64_t m = 0;
  const char* first = p;
  while (p < end && digit(*p)) m = 10 * m + static_cast<unsigned>(*p++ - '0');
  std::ptrdiff_t digits = p - first, exponent = 0;
  if (digits == 0) return std::nullopt;  // no integer digit (".5", "nan", …): from_chars decides
  if (p < end && *p == '.') {
    const char* fraction = ++p;
    while (p < end && digit(*p)) m = 10 * m + static_cast<unsigned>(*p++ - '0');
    digits += p - fraction;
    exponent = fraction - p;
  }
  if (digits > kMaxDigits) return std::nullopt;
  if (p < end && (*p == 'e' || *p == 'E')) {
    ++p;
    const bool minus = p < end && *p == '-';
    if (p < end && (*p == '-' || *p == '+')) ++p;
    int x = 0;
    const char* exponent_digits = p;
    for (; p < end && digit(*p) && x < 1000; ++p) x = 10 * x + (*p - '0');
    if (p == exponent_digits) return std::nullopt;
    exponent += minus ? -x : x;
  }
  if (p != end || m >= kExactMantissa || exponent < -22 || exponent > 22) return std::nullopt;
  double v = static_cast<double>(m);
  v = exponent < 0 ? v / kPow10[-exponent] : v * kPow10[exponent];
  return negative ? -v : v;
}

bool looks_like_decimal_comma_number(std::string_view f) {
  // 12,5 or -0,0012 or 1,5E-03: digits, one comma, digits, optional exponent; no '.'
  const auto comma = f.find(',');
  if (comma == std::string_view::npos || f.find('.') != std::string_view::npos) return false;
  return parse_number(f, true).has_value();
}

// "1,234" or "-12,345,678": an integer in groups of three digits (English thousands).
bool maybe_thousands(std::string_view f) {
  if (!f.empty() && (f.front() == '-' || f.front() == '+')) f.remove_prefix(1);
  const auto digits = [](std::string_view d) {
    return std::all_of(d.begin(), d.end(), [](char c) { return c >= '0' && c <= '9'; });
  };
  const auto comma = f.find(',');
  if (comma == std::string_view::npos || comma == 0 || comma > 3 || f.front() == '0' ||
      !digits(f.substr(0, comma)))
    return false;
  for (f.remove_prefix(comma); !f.empty(); f.remove_prefix(4))
    if (f.size() < 4 || f[0] != ',' || !digits(f.substr(1, 3))) return false;
  return true;
}

// Fortran's D exponent, as DOUBLE PRECISION values are written ("1.0D-03",
// "0.1234567890123457D+01"): a mantissa of digits with one decimal mark (point or comma), D or d,
// an exponent of 1 to 3 digits with or without its sign. The position of the D; nullopt for
// anything else ("3D", "2d4" and names hold no decimal mark).
std::optional<std::size_t> fortran_exponent(std::string_view f) {
  const auto d = f.find_first_of("dD");
  if (d == std::string_view::npos || d == 0) return std::nullopt;
  const auto digit = [](char c) { return c >= '0' && c <= '9'; };
  std::string_view mantissa = f.substr(0, d), exponent = f.substr(d + 1);
  if (mantissa.front() == '-' || mantissa.front() == '+') mantissa.remove_prefix(1);
  if (!exponent.empty() && (exponent.front() == '-' || exponent.front() == '+'))
    exponent.remove_prefix(1);
  const auto mark = [](char c) { return c == '.' || c == ','; };
  return std::count_if(mantissa.begin(), mantissa.end(), mark) == 1 && mantissa.size() > 1 &&
                 std::all_of(mantissa.begin(), mantissa.end(),
                             [&](char c) { return digit(c) || mark(c); }) &&
                 !exponent.empty() && exponent.size() <= 3 &&
                 std::all_of(exponent.begin(), exponent.end(), digit)
             ? std::optional(d)
             : std::nullopt;
}

}  // namespace

std::optional<double> parse_number(std::string_view field, bool decimal_comma) {
  // Where the decimal mark is the comma, a point is a thousands separator (German spreadsheets
  // write 1234 as "1.234") or the other mark: either way not a number that can be read.
  if (decimal_comma && field.find('.') != std::string_view::npos) return std::nullopt;
  // Numbers are parsed where they lie; only a decimal comma needs a copy with a point.
  std::string copy;
  if (decimal_comma && field.find(',') != std::string_view::npos) {
    copy.assign(field);
    std::replace(copy.begin(), copy.end(), ',', '.');
    field = copy;
  }
  if (field.empty()) return std::nullopt;
  const char* b = field.data();
  const char* e = b + field.size();
  if (*b == '+') ++b;
  if (const auto v = exact_short_decimal(b, e)) return v;
  double v = 0;
  const auto [end, ec] = std::from_chars(b, e, v);
  if (ec == std::errc() && end == e && std::isfinite(v)) return v;
  if (const auto d = fortran_exponent(field)) {
    std::string with_e(field);
    with_e[*d] = 'e';
    return parse_number(with_e, false);
  }
  return std::nullopt;
}

std::size_t exponent_mark(std::string_view field) {
  const auto e = field.find_first_of("eE");
  if (e != std::string_view::npos) return e;
  return fortran_exponent(field).value_or(std::string_view::npos);
}

double printed_step(std::string_view field, bool decimal_comma) {
  const auto e = exponent_mark(field);
  const std::string_view mantissa = field.substr(0, e);
  const auto mark = mantissa.find(decimal_comma ? ',' : '.');
  const auto decimals =
      mark == std::string_view::npos ? 0 : static_cast<int>(mantissa.size() - mark - 1);
  int exponent = 0;
  if (e != std::string_view::npos)
    if (const auto x = parse_number(field.substr(e + 1), false)) exponent = static_cast<int>(*x);
  return std::pow(10.0, exponent - decimals);
}

std::string text_place(std::size_t line, std::size_t column_index) {
  return "line " + std::to_string(line) + ", column " + std::to_string(column_index + 1);
}

std::string_view TextRows::line_text(std::size_t i) const {
  const std::size_t start = starts_[i];
  std::size_t end = start;
  if (!has_cr_) {
    const void* lf = std::memchr(bytes_.data() + start, '\n', bytes_.size() - start);
    end =
        lf ? static_cast<std::size_t>(static_cast<const char*>(lf) - bytes_.data()) : bytes_.size();
  } else {
    while (end < bytes_.size() && bytes_[end] != '\n' && bytes_[end] != '\r') ++end;
  }
  return bytes_.substr(start, end - start);
}

void TextRows::fields(std::size_t i, std::vector<std::string_view>& out) const {
  out.clear();
  if (!cell_ends_.empty()) {  // a sheet's cells
    const std::size_t begin = i > 0 ? cell_ends_[i - 1] : 0;
    out.assign(cells_.begin() + static_cast<std::ptrdiff_t>(begin),
               cells_.begin() + static_cast<std::ptrdiff_t>(cell_ends_[i]));
    return;
  }
  split(line_text(i), delimiter_, out);
}

std::size_t TextRows::max_fields(std::size_t i) const {
  if (!cell_ends_.empty()) return cell_ends_[i] - (i > 0 ? cell_ends_[i - 1] : 0);
  const std::string_view l = line_text(i);
  // split() ends a field only at the delimiter (blank or tab where runs of blanks separate).
  const auto separators =
      delimiter_ == ' '
          ? std::count_if(l.begin(), l.end(), [](char c) { return c == ' ' || c == '\t'; })
          : std::count(l.begin(), l.end(), delimiter_);
  return static_cast<std::size_t>(separators) + 1;
}

void TextRows::add_cells(std::size_t line, std::vector<std::string_view> cells) {
  cells_.insert(cells_.end(), cells.begin(), cells.end());
  cell_ends_.push_back(cells_.size());
  lines_.push_back(line);
}

std::size_t TextRows::bookkeeping_bytes() const {
  return starts_.capacity() * sizeof(std::uint32_t) + cells_.capacity() * sizeof(std::string_view) +
         cell_ends_.capacity() * sizeof(std::size_t) +
         lines_.runs() * sizeof(std::pair<std::size_t, std::size_t>);
}

namespace {
// UTF-16 text after its byte order mark (Excel's "Unicode Text", little-endian; big-endian
// too) as UTF-8. An unpaired surrogate or an odd byte count is no UTF-16 text: refused by line.
std::string utf8_of_utf16(const std::filesystem::path& file, std::string_view bytes) {
  const bool big = bytes[0] == '\xFE';
  const auto unit = [&](std::size_t i) {
    const auto hi = static_cast<unsigned char>(bytes[big ? i : i + 1]);
    const auto lo = static_cast<unsigned char>(bytes[big ? i + 1 : i]);
    return static_cast<std::uint32_t>(hi << 8 | lo);
  };
  std::string out;
  out.reserve(bytes.size() / 2);
  std::size_t line = 1;
  const auto refuse = [&](const std::string& what) {
    throw input_error(file.string(), "line " + std::to_string(line), what,
                      "expected UTF-16 text after its byte order mark; save the file as UTF-8 "
                      "or CSV");
  };
  for (std::size_t i = 2; i + 1 < bytes.size(); i += 2) {
    std::uint32_t c = unit(i);
    if (c >= 0xDC00 && c < 0xE000) refuse("an unpaired low surrogate");
    if (c >= 0xD800 && c < 0xDC00) {
      const std::uint32_t low = i + 2 < bytes.size() ? unit(i + 2) : 0;
      if (low < 0xDC00 || low >= 0xE000) refuse("an unpaired high surrogate");
      c = 0x10000 + ((c - 0xD800) << 10) + (low - 0xDC00);
      i += 2;
    }
    line += c == '\n';
    if (c < 0x80) {
      out.push_back(static_cast<char>(c));
    } else if (c < 0x800) {
      out.push_back(static_cast<char>(0xC0 | c >> 6));
      out.push_back(static_cast<char>(0x80 | (c & 0x3F)));
    } else if (c < 0x10000) {
      out.push_back(static_cast<char>(0xE0 | c >> 12));
      out.push_back(static_cast<char>(0x80 | (c >> 6 & 0x3F)));
      out.push_back(static_cast<char>(0x80 | (c & 0x3F)));
    } else {
      out.push_back(static_cast<char>(0xF0 | c >> 18));
      out.push_back(static_cast<char>(0x80 | (c >> 12 & 0x3F)));
      out.push_back(static_cast<char>(0x80 | (c >> 6 & 0x3F)));
      out.push_back(static_cast<char>(0x80 | (c & 0x3F)));
    }
  }
  if (bytes.size() % 2) refuse("an odd number of bytes (the file ends inside a character)");
  return out;
}

// The length of the UTF-8 character at bytes[i] (RFC 3629: no overlong form, no surrogate, none
// beyond U+10FFFF), 0 if none starts there.
std::size_t utf8_character(std::string_view bytes, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(bytes[k]); };
  const unsigned char c = byte(i);
  const std::size_t n = c < 0x80                 ? 1
                        : c >= 0xC2 && c <= 0xDF ? 2
                        : c >= 0xE0 && c <= 0xEF ? 3
                        : c >= 0xF0 && c <= 0xF4 ? 4
                                                 : 0;
  if (n == 0 || i + n > bytes.size()) return 0;
  // The range of the byte after the lead; the others 0x80–0xBF.
  const unsigned char low = c == 0xE0 ? 0xA0 : c == 0xF0 ? 0x90 : 0x80;
  const unsigned char high = c == 0xED ? 0x9F : c == 0xF4 ? 0x8F : 0xBF;
  for (std::size_t k = 1; k < n; ++k)
    if (k == 1 ? byte(i + k) < low || byte(i + k) > high : (byte(i + k) & 0xC0) != 0x80) return 0;
  return n;
}

// Text that is not all UTF-8 (a Latin-1 file: "Messger\xE4t", "\xB5s") as UTF-8: its UTF-8
// characters kept, every other byte read as the Latin-1 character it is. Its names, units and any
// text quoted from it into a message, a warning or summary.json are then UTF-8, which JSON
// outputs require (a Latin-1 footer's warning ended process at exit 4, "invalid UTF-8 byte").
void latin1_as_utf8(std::string& bytes) {
  std::size_t i = 0;
  while (i < bytes.size())
    if (const std::size_t n = utf8_character(bytes, i))
      i += n;
    else
      break;
  if (i == bytes.size()) return;
  std::string out(bytes, 0, i);
  out.reserve(bytes.size() + bytes.size() / 8);
  while (i < bytes.size()) {
    if (const std::size_t n = utf8_character(bytes, i)) {
      out.append(bytes, i, n);
      i += n;
    } else {
      const auto c = static_cast<unsigned char>(bytes[i++]);
      out.push_back(static_cast<char>(0xC0 | c >> 6));
      out.push_back(static_cast<char>(0x80 | (c & 0x3F)));
    }
  }
  bytes = std::move(out);
}

// Byte order marks: UTF-8 is dropped (spreadsheets write it); UTF-16 text is read as UTF-8.
// Other text with NUL bytes (UTF-16 without its mark, binary data) is refused by name rather than
// failing later on them.
void drop_bom_or_refuse_binary(const std::filesystem::path& file, std::string& bytes) {
  if (bytes.rfind("\xEF\xBB\xBF", 0) == 0) bytes.erase(0, 3);
  if (bytes.rfind("\xFF\xFE", 0) == 0 || bytes.rfind("\xFE\xFF", 0) == 0)
    bytes = utf8_of_utf16(file, bytes);
  if (const auto nul = bytes.find('\0'); nul != std::string::npos) {
    // Named on its own line (LF, CRLF or lone CR end a line, as below), not on line 1.
    std::size_t number = 1;
    for (std::size_t i = 0; i < nul; ++i)
      number += bytes[i] == '\n' || (bytes[i] == '\r' && (i + 1 == nul || bytes[i + 1] != '\n'));
    throw input_error(file.string(), "line " + std::to_string(number),
                      "UTF-16 or binary data (a NUL byte)",
                      "expected text (ASCII, UTF-8 or Latin-1); save the file as UTF-8 or CSV");
  }
}
}  // namespace

void detect_decimal_comma(DelimitedText& text) {
  // Decided on the last sniffed rows (data, not header) by numbers with a comma against numbers
  // with a point. In a comma-separated file only a quoted field holds a comma: "-0,25" as pandas
  // and LibreOffice quote decimal commas there, but also "1,234" as English spreadsheets quote
  // thousands, so a field that may be thousands is no evidence there (nor a workbook's text cell).
  std::size_t with_comma = 0, numbers = 0;
  const std::size_t from = text.rows.size() > kSniffLines ? text.rows.size() - kSniffLines : 0;
  std::vector<std::string_view> fields;
  for (std::size_t i = from; i < text.rows.size(); ++i) {
    text.rows.fields(i, fields);
    for (const auto& f : fields) {
      if (looks_like_decimal_comma_number(f))
        with_comma += text.delimiter != ',' || !maybe_thousands(f);
      else if (f.find('.') != std::string_view::npos && parse_number(f, false))
        ++numbers;
    }
  }
  text.decimal_comma = with_comma > numbers;
}

DelimitedText read_delimited_text(const std::filesystem::path& file) {
  // Type (no FIFO or device) and size checked before reading: 1 GiB is far beyond any record
  // (and a row's start fits the 4 bytes TextRows keeps, also once Latin-1 is read as UTF-8, at
  // most twice as long).
  constexpr std::uintmax_t kMaxBytes = std::uintmax_t{1} << 30;
  static_assert(2 * kMaxBytes <= std::numeric_limits<std::uint32_t>::max());
  auto owned = std::make_shared<std::string>(
      read_input_file(file, file.string(), "a signal file", kMaxBytes));
  std::string& bytes = *owned;
  drop_bom_or_refuse_binary(file, bytes);
  latin1_as_utf8(bytes);

  // Lines (LF, CRLF or lone CR) with their numbers, one at a time, blank ones skipped.
  const bool has_cr = bytes.find('\r') != std::string::npos;
  struct Line {
    std::size_t number = 0;
    std::string_view text;
  };
  struct Cursor {
    std::size_t start = 0, number = 1;
  };
  const auto next_line = [&](Cursor& at, Line& line) {
    while (at.start <= bytes.size()) {
      std::size_t i = at.start;
      if (!has_cr) {  // LF only: jump to the next line end
        const void* lf = std::memchr(bytes.data() + i, '\n', bytes.size() - i);
        i = lf ? static_cast<std::size_t>(static_cast<const char*>(lf) - bytes.data())
               : bytes.size();
      } else {
        while (i < bytes.size() && bytes[i] != '\n' && bytes[i] != '\r') ++i;
      }
      if (at.number % 65536 == 0) throw_if_interrupted();  // a long record stops within a second
      const std::string_view l(bytes.data() + at.start, i - at.start);
      const std::size_t number = at.number;
      if (i < bytes.size() && bytes[i] == '\r' && i + 1 < bytes.size() && bytes[i + 1] == '\n') ++i;
      at.start = i + 1;
      ++at.number;
      if (l.find_first_not_of(" \t") != std::string_view::npos) {
        line = {number, l};
        return true;
      }
    }
    return false;
  };
  Line line;
  if (Cursor c; !next_line(c, line))
    throw input_error(file.string(), "line 1", "empty file", "expected signal rows");

  DelimitedText text;
  text.file = file;
  // Delimiter: the one present in most of the first lines (tab beats semicolon beats comma).
  std::size_t tabs = 0, semis = 0, commas = 0, sniff = 0;
  for (Cursor c; sniff < kSniffLines && next_line(c, line); ++sniff) {
    tabs += line.text.find('\t') != std::string_view::npos;
    semis += line.text.find(';') != std::string_view::npos;
    commas += line.text.find(',') != std::string_view::npos;
  }
  if (tabs * 2 > sniff)
    text.delimiter = '\t';
  else if (semis * 2 > sniff)
    text.delimiter = ';';
  else if (commas * 2 > sniff)
    text.delimiter = ',';
  else
    text.delimiter = ' ';

  // Every row's start and line; its fields are split when it is read (TextRows).
  text.rows.set_text(bytes, text.delimiter, has_cr);
  text.rows.reserve(
      static_cast<std::size_t>(std::count(bytes.begin(), bytes.end(), has_cr ? '\r' : '\n')) + 1);
  for (Cursor c; next_line(c, line);)
    text.rows.add_line(static_cast<std::uint32_t>(line.text.data() - bytes.data()), line.number);
  const auto last_end = bytes.find_last_of("\r\n");
  text.last_row_unterminated =
      bytes.find_first_not_of(" \t", last_end == std::string::npos ? 0 : last_end + 1) !=
      std::string::npos;
  text.bytes = std::move(owned);

  detect_decimal_comma(text);
  return text;
}

}  // namespace shpb
