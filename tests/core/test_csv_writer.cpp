#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "../scratch.hpp"
#include "core/csv_writer.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_core_test_csv_writer {

using namespace shpb;

TEST_CASE("Doubles are written in shortest round-trip form and read back exactly", "[core][csv]") {
  for (double x : {0.1, 1.0 / 3.0, 2.5e-7, -1234567.891, 6.02214076e23}) {
    const std::string text = format_double(x);
    REQUIRE(std::strtod(text.c_str(), nullptr) == x);
  }
}

TEST_CASE("A CSV file has one header row and refuses non-finite values", "[core][csv]") {
  const shpb_test::ScratchDir scratch("csv_writer");
  const auto path = scratch.path() / "table.csv";
  {
    CsvWriter w(path, {"time_s", "strain"});
    w.row({0.0, 1e-3});
    REQUIRE_THROWS(w.row({1.0, std::nan("")}));
    REQUIRE_THROWS(w.row({1.0}));
  }
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  REQUIRE(s.str() == "time_s,strain\n0,0.001\n");
}

TEST_CASE("A subnormal value is written as 0 for every reader to take", "[core][csv]") {
  // A wave front's foot underflows to about 1e-323 in a run's gauges: std::stod (and spreadsheets
  // holding doubles down to 2.2e-308 only) refuse such a cell; no strain or stress is that small.
  const shpb_test::ScratchDir scratch("csv_writer_subnormal");
  const auto path = scratch.path() / "table.csv";
  {
    CsvWriter w(path, {"time_s", "strain"});
    w.row({4.65e-5, -1e-323});
    w.close();
  }
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  CHECK(s.str() == "time_s,strain\n4.65e-05,0\n");
  CHECK(format_field(8.8e-320) == "0");
  CHECK(format_field(2.3e-308) == format_double(2.3e-308));  // the smallest normal ones are kept
}

TEST_CASE("A row with preformatted leading cells reads as the same row of doubles", "[core][csv]") {
  const shpb_test::ScratchDir scratch("csv_leading");
  const auto path = scratch.path() / "table.csv";
  {
    CsvWriter w(path, {"time_s", "x_m", "stress_Pa"});
    const double stress = -2.5e8;
    w.row({1e-6, 0.3, stress});
    w.row(format_double(1e-6) + "," + format_double(0.3), 2, std::span(&stress, 1));
    REQUIRE_THROWS(w.row(format_double(1e-6), 1, std::span(&stress, 1)));  // one column short
    const double bad = std::nan("");
    REQUIRE_THROWS(w.row("0,0", 2, std::span(&bad, 1)));
  }
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  std::string header, plain, leading, extra;
  std::getline(s, header);
  std::getline(s, plain);
  std::getline(s, leading);
  REQUIRE_FALSE(std::getline(s, extra));
  REQUIRE(leading == plain);
  double t = 0, x = 0, sigma = 0;
  REQUIRE(std::sscanf(leading.c_str(), "%lf,%lf,%lf", &t, &x, &sigma) == 3);
  REQUIRE((t == 1e-6 && x == 0.3 && sigma == -2.5e8));
}

}  // namespace tests_core_test_csv_writer
