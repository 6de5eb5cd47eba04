// The one number formatter of messages (core/number_format.hpp): values as a user would write
// them, exact where the user typed them, short where they were computed.
#include <catch2/catch.hpp>
#include <limits>

#include "core/number_format.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_core_test_number_format {

using shpb::format_number;
using shpb::format_range;
using shpb::format_resolved;

TEST_CASE("Numbers in messages read as a user writes them", "[core][format]") {
  // Typed values come back as typed (the shortest text that reads back as the same double).
  CHECK(format_number(1e-7) == "1e-07");
  CHECK(format_number(-1e-7) == "-1e-07");  // printf's %f: "-0.000000"
  CHECK(format_number(0.05) == "0.05");
  CHECK(format_number(2.5e11) == "2.5e+11");
  CHECK(format_number(1e12) == "1e+12");
  CHECK(format_number(1200) == "1200");
  CHECK(format_number(0.29) == "0.29");
  // 1e308 is 309 digits and ".000000" under %f.
  CHECK(format_number(1e308) == "1e+308");
  CHECK(format_number(std::numeric_limits<double>::max()) == "1.79769e+308");
  // Computed values: 6 significant digits, not 17.
  CHECK(format_number(0.1 + 0.2) == "0.3");
  CHECK(format_number(1.0 / 3) == "0.333333");
  CHECK(format_number(-0.0) == "0");
  CHECK(format_number(std::numeric_limits<double>::quiet_NaN()) == "nan");
  CHECK(format_number(-std::numeric_limits<double>::infinity()) == "-inf");
}

TEST_CASE("Ranges in messages are printed as a user would write them", "[core][format]") {
  CHECK(format_range(1e-5, 0.05) == "[1e-05, 0.05]");
  CHECK(format_range(0, 1, true, false) == "(0, 1]");
  CHECK(format_range(0, 0.49, false, true) == "[0, 0.49)");
}

TEST_CASE("Times on a record's clock resolve its sample interval", "[core][format]") {
  // A clock near zero keeps "%.6g": the digits already resolve the sample.
  CHECK(format_resolved(450.3, 0.1, 6) == "450.3");
  CHECK(format_resolved(-197.6, 0.08, 4) == "-197.6");
  // A clock armed 58.3 s before the test: 1 us samples need 8 digits, 0.1 us ones 9.
  CHECK(format_resolved(58312841, 1, 6) == "58312841");
  CHECK(format_resolved(58300450.3, 0.1, 6) == "58300450.3");
  CHECK(format_resolved(58.313055, 1e-6, 6) == "58.313055");
  // The last sample of 50000 at 8 ns from -80 us: 320 us to 4 digits names no sample.
  CHECK(format_resolved(319.992, 0.008, 4) == "319.992");
  // No resolution, or a zero: the digits asked for.
  CHECK(format_resolved(58312841, 0, 6) == "5.83128e+07");
  CHECK(format_resolved(0, 1e-6, 6) == "0");
}

}  // namespace tests_core_test_number_format
