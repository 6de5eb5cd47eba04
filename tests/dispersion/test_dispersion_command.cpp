
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "../app/output_schema_check.hpp"
#include "../app/run_shpb.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_dispersion_test_dispersion_command {

namespace fs = std::filesystem;

namespace {

// Rows of a CSV file as numbers, keyed by the first column rounded to 1e-6.
std::map<long, std::vector<double>> read_rows(const fs::path& p, std::string* header = nullptr) {
  std::map<long, std::vector<double>> rows;
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);
  if (header) *header = line;
  while (std::getline(in, line)) {
    std::vector<double> v;
    std::stringstream s(line);
    std::string f;
    while (std::getline(s, f, ',')) v.push_back(std::stod(f));
    rows[std::lround(v[0] * 1e6)] = v;
  }
  return rows;
}

}  // namespace

TEST_CASE("shpb dispersion writes the curve and matches the reference within 2e-5",
          "[dispersion][app]") {
  const fs::path ref_dir = fs::path(SHPB_SOURCE_DIR) / "tests/data/pochhammer-chree";
  const shpb_test::ScratchDir scratch("dispersion");
  const fs::path out = scratch.path() / "dispersion.csv";
  for (const char* nu : {"0.29", "0.30"}) {
    CAPTURE(nu);
    fs::remove(out);
    REQUIRE(shpb_test::run_shpb({"dispersion", "--poisson", nu, "--radius", "9.525 mm", "--c0",
                                 "5000 m/s", "-o", out.string()})
                .code == 0);
    std::string header;
    const auto got = read_rows(out, &header);
    CHECK(header == "a_over_lambda,c_over_c0,cg_over_c0,f_a_over_c0,frequency_Hz");
    shpb_test::check_schema_columns(out, "dispersion");
    REQUIRE(got.size() == 321);  // default: 0 … 1.6 in 321 points
    const auto& last = got.rbegin()->second;
    CHECK(last[0] == Approx(1.6));
    CHECK(last[4] == Approx(last[3] * 5000 / 9.525e-3));  // f = (f a/c0)·c0/a
    const fs::path ref = ref_dir / (std::string("pc_nu") + nu + ".csv");
    REQUIRE(fs::exists(ref));
    constexpr double kReferenceTolerance = 2e-5;  // the reference table is printed to five decimals
    double worst = 0;
    std::size_t matched = 0;
    for (const auto& [key, r] : read_rows(ref)) {
      const auto it = got.find(key);
      if (it == got.end()) continue;
      ++matched;
      worst = std::max(worst, std::abs(it->second[1] - r[2]));
    }
    CHECK(matched == 321);
    CHECK(worst < kReferenceTolerance);
  }
}

TEST_CASE("shpb dispersion rejects a radius without c0 with exit code 2", "[dispersion][app]") {
  CHECK(shpb_test::run_shpb({"dispersion", "--poisson", "0.3", "--radius", "5 mm"}).code == 2);
}

// docs/commands.md#dispersion: --a-over-lambda is a list of numbers. An empty list was read as 0
// and wrote a row nobody asked for; a word was CLI11's "Could not convert".
TEST_CASE("shpb dispersion refuses an empty or non-numeric a/Λ in one line", "[dispersion][app]") {
  for (const char* list : {"", "0.1,abc"}) {
    INFO("--a-over-lambda \"" << list << "\"");
    const auto r =
        shpb_test::run_shpb({"dispersion", "--poisson", "0.29", "--a-over-lambda", list});
    CHECK(r.code == 2);
    CHECK(r.out.empty());
    CHECK(r.err.rfind("error: --a-over-lambda: ", 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
}

// A list of a/Λ is the table: a table's size or end given with it was ignored without a word
// (`--a-over-lambda 0.1 --points 5` printed one row). Refused, naming the option.
TEST_CASE("shpb dispersion refuses a list of a/Λ with a table's size or end", "[dispersion][app]") {
  for (const char* option : {"--points", "--max-a-over-lambda"}) {
    INFO(option);
    const auto r = shpb_test::run_shpb(
        {"dispersion", "--poisson", "0.29", "--a-over-lambda", "0.1", option, "5"});
    CHECK(r.code == 2);
    CHECK(r.out.empty());
    CHECK(r.err == std::string("error: ") + option +
                       ": 5: not with --a-over-lambda (the list gives the table's a/Λ)\n");
  }
  // Either alone still sets the table.
  const auto r = shpb_test::run_shpb({"dispersion", "--poisson", "0.29", "--points", "3"});
  CHECK(r.code == 0);
  CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 4);  // the header and 3 rows
}

// `-o -` is standard output, as the shell convention has it (it wrote a file named "-"): the same
// table as with no -o, and no file made in the working folder.
TEST_CASE("shpb dispersion -o - prints the table", "[dispersion][app]") {
  const std::filesystem::path dash_file = std::filesystem::current_path() / "-";
  const bool there_before = std::filesystem::exists(dash_file);
  const auto to_stdout = shpb_test::run_shpb({"dispersion", "--poisson", "0.29"});
  const auto dash = shpb_test::run_shpb({"dispersion", "--poisson", "0.29", "-o", "-"});
  REQUIRE(dash.code == 0);
  CHECK(!dash.out.empty());
  CHECK(dash.out == to_stdout.out);
  CHECK(std::filesystem::exists(dash_file) == there_before);
}

}  // namespace tests_dispersion_test_dispersion_command
