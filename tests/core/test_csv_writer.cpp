#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

#include "core/csv_writer.hpp"

using namespace shpb;

TEST_CASE("Doubles are written in shortest round-trip form and read back exactly", "[core][csv]") {
  for (double x : {0.1, 1.0 / 3.0, 2.5e-7, -1234567.891, 6.02214076e23}) {
    const std::string text = format_double(x);
    REQUIRE(std::strtod(text.c_str(), nullptr) == x);
  }
}

TEST_CASE("A CSV file has one header row and refuses non-finite values", "[core][csv]") {
  const auto path = std::filesystem::temp_directory_path() /
                    ("shpb_test_csv_writer_" + std::to_string(::getpid()) + ".csv");
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
  std::filesystem::remove(path);
}
