// Number parsing of signal files: every field parses to the value std::from_chars gives (the
// correctly rounded one), through the in-place fast path or without it.
#include <catch2/catch.hpp>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>

#include "../scratch.hpp"
#include "core/signal_reader.hpp"
#include "core/signal_text.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_core_test_signal_text {

using namespace shpb;

TEST_CASE("Numbers parse to the correctly rounded value, fast path or not", "[signal]") {
  // Oscilloscope and spreadsheet forms, the edges of the exact fast path (2^53, 10^±22, 19
  // digits) and beyond it, where std::from_chars decides alone.
  for (const std::string s : {"0",
                              "-0",
                              "1",
                              "-1.5",
                              "3.1415926535",
                              "1.0000000e-07",
                              "-9.675593e-07",
                              "7.194476E-04",
                              "12345678",
                              "0.1",
                              "0.3",
                              "1e22",
                              "1e23",
                              "1e-22",
                              "1e-23",
                              "9007199254740991",
                              "9007199254740993",
                              "1234567890123456789",
                              "12345678901234567890",
                              "4.9e-324",
                              "1.7976931348623157e308",
                              "1.",
                              "1.e5",
                              "000123.4500",
                              "2.5e+3",
                              "2.5e-0"}) {
    CAPTURE(s);
    double expected = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), expected);
    REQUIRE(ec == std::errc());
    REQUIRE(end == s.data() + s.size());
    const auto v = parse_number(s, false);
    REQUIRE(v.has_value());
    CHECK(*v == expected);
    CHECK(std::signbit(*v) == std::signbit(expected));
  }
  CHECK(parse_number("+2.5", false) == 2.5);
  CHECK(parse_number("2,5", true) == 2.5);
  // With a decimal comma a point is a thousands separator or the other mark: no number.
  CHECK_FALSE(parse_number("1.234", true).has_value());
  for (const std::string bad :
       {"", "-", "1e", "1e+", "e5", "1.2.3", "1,5", "nan", "inf", "1e400", "0x10", "1 2", "--1"}) {
    CAPTURE(bad);
    CHECK_FALSE(parse_number(bad, false).has_value());
  }
}

// A deep-memory record (10-100 M samples a channel) is held as its bytes plus a few bytes a row:
// a row's start (4 bytes) and its line as a run of consecutive lines, its fields split when it is
// read. A view per field (16 bytes) and a row record (24) took 124-202 bytes a sample through
// `process` and ran a laptop out of memory (docs/validation.md, "Deep-memory records").
TEST_CASE("A text's rows cost their start offset, not a view per field", "[signal]") {
  const shpb_test::ScratchDir scratch("signal_text");
  constexpr std::size_t kRows = 20000;
  constexpr std::size_t kRowStartBytes = sizeof(std::uint32_t);  // the one record kept per row
  constexpr std::size_t kReservedRows = kRows + 2;  // reserved once: the file's line ends, and one
  constexpr std::size_t kLineRunBytes = 64;         // the one run of lines, with room to spare
  const auto file = scratch.path() / "record.csv";
  {
    std::ofstream out(file, std::ios::binary);
    out << "time_s,incident_V,transmitted_V,reflected_V\n";
    for (std::size_t i = 0; i < kRows; ++i) out << i << "e-7,0.25,-0.5," << i % 7 << "\n";
  }
  const DelimitedText text = read_delimited_text(file);
  REQUIRE(text.rows.size() == kRows + 1);
  // Four fields a row, each a view of 16 bytes, and a 24-byte row record before (1.76 MB for
  // this file): now the rows' starts and the one run of lines (no blank line), 80 kB.
  CHECK(text.rows.bookkeeping_bytes() <= kReservedRows * kRowStartBytes + kLineRunBytes);
  const TextRow last = text.rows.back();
  CHECK(last.line == kRows + 1);
  REQUIRE(last.fields.size() == 4);
  CHECK(last.fields[0] == std::to_string(kRows - 1) + "e-7");
  CHECK(last.fields[3] == std::to_string((kRows - 1) % 7));

  // The samples' lines: one run, whatever the length.
  SignalRequest request;
  request.file = file;
  request.columns = {{"incident_V", std::nullopt}};
  const SignalColumns cols = read_signal_columns(request);
  REQUIRE(cols.lines.size() == kRows);
  CHECK(cols.lines.runs() == 1);
  CHECK(cols.lines[0] == 2);
  CHECK(cols.lines[kRows - 1] == kRows + 1);
}

TEST_CASE("Rows keep their file's line numbers across blank lines and line ends", "[signal]") {
  const shpb_test::ScratchDir scratch("signal_text_lines");
  const auto file = scratch.path() / "blank.csv";
  // CRLF, a lone CR and LF line ends; blank lines (one of blanks only) between rows.
  std::ofstream(file, std::ios::binary) << "t;v\r\n\r\n1;2\r\n  \r\n3;4\r5;6\n\n\n7;\"8\"";
  const DelimitedText text = read_delimited_text(file);
  REQUIRE(text.rows.size() == 5);
  const std::size_t lines[] = {1, 3, 5, 6, 9};
  const std::string second[] = {"v", "2", "4", "6", "8"};
  std::vector<std::string_view> fields;
  for (std::size_t i = 0; i < 5; ++i) {
    CAPTURE(i);
    CHECK(text.rows.line(i) == lines[i]);
    CHECK(text.rows[i].line == lines[i]);
    text.rows.fields(i, fields);
    REQUIRE(fields.size() == 2);
    CHECK(fields[1] == second[i]);
  }
  CHECK(text.last_row_unterminated);
}

}  // namespace tests_core_test_signal_text
