// Number parsing of signal files: every field parses to the value std::from_chars gives (the
// correctly rounded one), through the in-place fast path or without it.
#include <catch2/catch.hpp>
#include <charconv>
#include <cmath>
#include <string>

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

}  // namespace tests_core_test_signal_text
