// The command line as users meet it (docs/commands.md): `shpb --help` and `shpb <command> --help`
// describe every subcommand and option; usage errors exit 2 with one "error:" line.
#include <catch2/catch.hpp>
#include <cctype>
#include <filesystem>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "run_shpb.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_app_test_cli {

namespace fs = std::filesystem;

namespace {

using shpb_test::run_shpb;

// Splits a command line at spaces (the tests' arguments contain none inside one argument).
shpb_test::RunResult shpb(const std::string& args) {
  std::vector<std::string> v;
  std::stringstream s(args);
  for (std::string a; s >> a;) v.push_back(a);
  return run_shpb(v);
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> v;
  std::stringstream s(text);
  for (std::string l; std::getline(s, l);) v.push_back(l);
  return v;
}

// Every entry of the "Options:", "Positionals:" and "Subcommands:" lists carries a description,
// on its own line (after two spaces) or, for long signatures, on the next, indented line.
std::vector<std::string> undescribed_entries(const std::string& help) {
  std::vector<std::string> bad;
  const auto ls = lines(help);
  bool in_list = false;
  for (std::size_t i = 0; i < ls.size(); ++i) {
    const auto& l = ls[i];
    if (l == "Options:" || l == "Positionals:" || l == "Subcommands:") {
      in_list = true;
      continue;
    }
    if (l.empty() || l[0] != ' ') {
      in_list = false;
      continue;
    }
    if (!in_list || l.rfind("  ", 0) != 0 || l.size() < 3 || l[2] == ' ') continue;
    const auto gap = l.find("  ", 2);
    const bool same_line =
        gap != std::string::npos && l.find_first_not_of(' ', gap) != std::string::npos;
    const bool next_line = i + 1 < ls.size() && ls[i + 1].rfind("          ", 0) == 0 &&
                           ls[i + 1].find_first_not_of(' ') != std::string::npos;
    if (!same_line && !next_line) bad.push_back(l);
  }
  return bad;
}

const std::vector<std::string> kCommands = {"simulate", "process", "compare", "dispersion", "study",
                                            "validate", "report",  "fit",     "calibrate",  "plan"};

// Decimal numbers printed with a double's round-off left in ("3.5000000000000004",
// "0.30000000000000004"): the fraction digits of each number holding six equal zeros or nines
// followed by a further digit.
std::vector<std::string> round_off_numbers(const std::string& text) {
  std::vector<std::string> found;
  for (std::size_t i = text.find('.'); i != std::string::npos; i = text.find('.', i + 1)) {
    std::size_t end = i + 1;
    while (end < text.size() && std::isdigit(static_cast<unsigned char>(text[end]))) ++end;
    const std::string fraction = text.substr(i + 1, end - i - 1);
    for (const char* run : {"000000", "999999"}) {
      const auto at = fraction.find(run);
      if (at != std::string::npos && at + 6 < fraction.size()) found.push_back(fraction);
    }
  }
  return found;
}

}  // namespace

TEST_CASE("shpb --help lists every subcommand with a description", "[app][cli]") {
  const auto r = shpb("--help");
  REQUIRE(r.code == 0);
  for (const auto& c : kCommands) {
    INFO(c);
    CHECK(r.out.find("\n  " + c + " ") != std::string::npos);
  }
  CHECK(undescribed_entries(r.out).empty());
}

TEST_CASE("Every subcommand's --help describes every option", "[app][cli]") {
  for (const auto& c : kCommands) {
    INFO(c);
    const auto r = shpb(c + " --help");
    CHECK(r.code == 0);
    CHECK(r.out.find("Usage:") != std::string::npos);
    CHECK(r.out.find("Options:") != std::string::npos);
    const auto bad = undescribed_entries(r.out);
    for (const auto& b : bad) INFO("undescribed: " << b);
    CHECK(bad.empty());
    // A default is printed as a user would write it, not with a double's round-off.
    CHECK(round_off_numbers(r.out).empty());
  }
}

TEST_CASE("The documented run options are on simulate, compare, study and validate", "[app][cli]") {
  for (const char* c : {"simulate", "compare", "study", "validate"}) {
    INFO(c);
    const auto r = shpb(std::string(c) + " --help");
    for (const char* option : {"--contact", "--stepping", "--courant", "--threads", "--quiet"}) {
      INFO(option);
      CHECK(r.out.find(option) != std::string::npos);
    }
  }
  const auto v = shpb("validate --help");
  CHECK(v.out.find("--json") != std::string::npos);
  CHECK(v.out.find("localized-bipenalty") != std::string::npos);
}

TEST_CASE("Usage errors exit 2 with one error line", "[app][cli]") {
  for (const char* args : {"", "validate", "validate --bogus scene.json", "frobnicate",
                           "validate scene.json --contact springs", "simulate scene.json"}) {
    INFO("shpb " << args);
    const auto r = shpb(args);
    CHECK(r.code == 2);
    CHECK(r.err.rfind("error: ", 0) == 0);
    CHECK(lines(r.err).size() == 1);
    CHECK(r.out.empty());
  }
}

// docs/commands.md, Exit codes: a misspelt command or option is named with the closest one, as a
// misspelt scene key is; an unknown one with the list to choose from.
TEST_CASE("A misspelt command or option is named, with the one meant", "[app][cli]") {
  for (const auto& [args, says] : std::vector<std::pair<std::string, std::string>>{
           {"simulat scene.json",
            "simulat: unknown command; did you mean \"simulate\"? (see shpb "
            "--help)"},
           {"frobnicate", "frobnicate: unknown command; expected one of: simulate, process, "},
           {"validate scene.json --tolerence 1%",
            "--tolerence: unknown option of shpb validate; did you mean \"--tolerance\"? (see "
            "shpb validate --help)"},
           {"plan scene.json --rat=100 -o out",
            "--rat: unknown option of shpb plan; did you mean \"--rate\"?"},
           {"validate scene.json --bogus",
            "--bogus: unknown option of shpb validate; expected one of: --json, --contact, "},
           // Before any command: shpb's own options and the commands are the candidates.
           {"--bogus", "--bogus: unknown option of shpb; expected one of: --version, simulate, "},
           {"--versoin",
            "--versoin: unknown option of shpb; did you mean \"--version\"? (see "
            "shpb --help)"},
           {"--versoin validate scene.json",
            "--versoin: unknown option of shpb; did you mean \"--version\"?"},
           {"--simulate scene.json",
            "--simulate: unknown option of shpb; did you mean \"simulate\"?"}}) {
    INFO("shpb " << args);
    const auto r = shpb(args);
    CHECK(r.code == 2);
    CHECK(r.err.rfind("error: " + says, 0) == 0);
    CHECK(lines(r.err).size() == 1);
  }
}

// Seeds and thread counts are checked where the options are declared (app/cli_options.hpp), the
// other ranges by the library (each command's IsValid), all before any file is read: "-1" is not
// wrapped to 2^64 - 1 nor taken as "all cores", a seed past 2^64 - 1 is not saturated, NaN and
// inf are no size.
TEST_CASE("Numeric options refuse a sign, a fraction, NaN, inf or an overflow", "[app][cli]") {
  const std::string missing = "/nonexistent/input.json";
  const std::string out = (shpb_test::scratch_dir("cli_numbers") / "out").string();
  for (const auto& [args, says] : std::vector<std::pair<std::string, std::string>>{
           {"study " + missing + " -o " + out + " --seed -1",
            "--seed: -1: expected a whole number"},
           {"process " + missing + " -o " + out + " --seed 18446744073709551616",
            "--seed: 18446744073709551616: expected a whole number"},
           {"fit " + missing + " -o " + out + " --seed 1.5",
            "--seed: 1.5: expected a whole number"},
           {"process " + missing + " -o " + out + " --threads -1",
            "--threads: -1: expected a whole number"},
           {"simulate " + missing + " -o " + out + " --threads nan",
            "--threads: nan: expected a whole number"},
           {"dispersion --poisson 0.3 --max-a-over-lambda inf",
            "--max-a-over-lambda: inf: must be in (0, 1000]"},
           // A count's sign, before its range; the ranges are the library's, as Python's.
           {"process " + missing + " -o " + out + " --draws -1",
            "--draws: -1: expected a whole number"},
           {"process " + missing + " -o " + out + " --draws 1", "--draws: 1: expected 2 to "},
           {"study " + missing + " -o " + out + " --refine 0", "--refine: 0: expected 1 to 64"},
           {"fit " + missing + " -o " + out + " --bootstrap -1",
            "--bootstrap: -1: expected 0 to 100000"},
           {"simulate " + missing + " -o " + out + " --contact bonded",
            "--contact: \"bonded\": expected penalty, bipenalty or localized-bipenalty"},
           // The largest seed is a seed: the error is then the missing file's.
           {"process " + missing + " -o " + out + " --seed 18446744073709551615",
            missing + ": no such file"}}) {
    INFO("shpb " << args);
    const auto r = shpb(args);
    CHECK(r.code == 2);
    CHECK(r.err.rfind("error: " + says, 0) == 0);
    CHECK(lines(r.err).size() == 1);
    CHECK_FALSE(fs::exists(out));
  }
}

TEST_CASE("A scene file that does not exist is an input error naming it", "[app][cli]") {
  const auto r = shpb("validate /nonexistent/scene.json");
  CHECK(r.code == 2);
  CHECK(r.err == "error: /nonexistent/scene.json: no such file: expected an existing JSON file\n");
}

TEST_CASE("shpb --version names the program", "[app][cli]") {
  const auto r = shpb("--version");
  CHECK(r.code == 0);
  CHECK(r.out.rfind("shpb ", 0) == 0);
}

}  // namespace tests_app_test_cli
