// The measured experiments' records damaged as a lab's files come damaged (a dead channel of a
// gauge read by two, a decimal comma in a Tektronix file, a sample scaled beyond any unit), read
// by `process`, `compare` and `fit`: exit 2, one line on stderr naming the file and the place,
// nothing written (docs/commands.md, Exit codes).
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "run_shpb.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_app_test_measured_record_faults {

namespace fs = std::filesystem;
using nlohmann::json;
using shpb_test::read_text;
using shpb_test::run_shpb;
using shpb_test::scratch_dir;

namespace {

const fs::path kPmma = fs::path(SHPB_SOURCE_DIR) / "experiments/lanl-pmma13-mini-kolsky";

// The PMMA experiment in `d` with its channel file Ch1 (the first of the incident gauge's two)
// rewritten line by line by `edit` (CRLF kept); the other files and the material stay shipped.
fs::path pmma_with_ch1(const fs::path& d,
                       const std::function<std::string(std::size_t, const std::string&)>& edit) {
  json scene = json::parse(read_text(kPmma / "scene.json"));
  scene["bars"][2]["material"] = (kPmma / scene["bars"][2]["material"].get<std::string>()).string();
  for (auto& ch : scene["measurement"]["channels"])
    ch["file"] = (kPmma / ch["file"].get<std::string>()).string();
  scene["measurement"]["channels"][0]["file"] = (d / "Ch1.csv").string();
  std::ofstream(d / "scene.json") << scene.dump(2);
  std::istringstream in(read_text(kPmma / "data/180303_171828_Ch1.csv"));
  std::ofstream out(d / "Ch1.csv", std::ios::binary);
  std::string line;
  for (std::size_t n = 1; std::getline(in, line); ++n) out << edit(n, line) << "\n";
  json campaign = json::parse(read_text(kPmma / "campaign.json"));
  campaign["tests"][0]["scene"] = (d / "scene.json").string();
  std::ofstream(d / "campaign.json") << campaign.dump(2);
  return d / "scene.json";
}

// Line `line` with its fifth field (the volts) replaced by `volts`.
std::string with_volts(const std::string& line, const std::string& volts) {
  const auto fifth = line.find(',', line.find(',', line.find(',', line.find(',') + 1) + 1) + 1);
  const bool crlf = !line.empty() && line.back() == '\r';
  return line.substr(0, fifth + 1) + volts + (crlf ? "\r" : "");
}

// Every command exits 2 with one line that holds each of `expected`, and writes nothing.
void refused_by_all(const fs::path& d, const std::vector<std::string>& expected) {
  for (const std::string command : {"process", "compare", "fit"}) {
    const fs::path out = d / ("out_" + command);
    const std::string input = (d / (command == "fit" ? "campaign.json" : "scene.json")).string();
    std::vector<std::string> args{command, input, "-o", out.string(), "-q"};
    if (command == "fit") args.insert(args.end(), {"--max-iterations", "1", "--threads", "1"});
    const auto r = run_shpb(args);
    INFO(command << ": " << r.err);
    CHECK(r.code == 2);
    CHECK(r.err.rfind("error: ", 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    for (const auto& e : expected) CHECK(r.err.find(e) != std::string::npos);
    CHECK_FALSE(fs::exists(out));
  }
}

}  // namespace

TEST_CASE("A dead channel beside its gauge's other channel is refused, never averaged in",
          "[app][measured-faults]") {
  // Averaged with the live channel, a channel of zeros halved the incident strain and process
  // wrote a curve (exit 0, a warning of 1- and 2-wave stresses in a ratio 0.45).
  const fs::path d = scratch_dir("faults_dead_channel");
  pmma_with_ch1(d, [](std::size_t, const std::string& line) { return with_volts(line, "0"); });
  refused_by_all(d, {(d / "Ch1.csv").string() + ": column index 4 (measurement.channels[0], "
                                                "gauge \"incident\"): with ",
                     "180303_171828_Ch2.csv, column index 4 (measurement.channels[1]",
                     "expected the channels of one gauge"});
}

TEST_CASE("A Tektronix row split by a decimal comma is refused by its line",
          "[app][measured-faults]") {
  // "1,5" in the volts column added a field; its "1" was read as the sample (exit 0).
  const fs::path d = scratch_dir("faults_tek_comma");
  pmma_with_ch1(d, [](std::size_t n, const std::string& line) {
    return n == 301 ? with_volts(line, "1,5") : line;
  });
  refused_by_all(d, {(d / "Ch1.csv").string() + ": line 301: 6 fields: expected at most the 5"});
}

TEST_CASE("A sample scaled beyond any unit slip is refused, not carried to inf",
          "[app][measured-faults]") {
  // The volts of one sample times 1e300: process stopped with exit 3 and inf in summary.json.
  const fs::path d = scratch_dir("faults_huge_sample");
  pmma_with_ch1(d, [](std::size_t n, const std::string& line) {
    return n == 301 ? with_volts(line, "-2.0e+298") : line;
  });
  refused_by_all(
      d, {(d / "Ch1.csv").string() + ": line 301, column index 4", "-2e+298 read as strain"});
}

}  // namespace tests_app_test_measured_record_faults
