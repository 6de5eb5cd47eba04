// The files shpb writes hold exactly the columns the output schema lists
// (src/core/output_schema.json, docs/outputs.md): the one list the C++ writers, the report package
// and the documentation's tables take their names from. Through the executable, on the experiments.
#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <vector>

#include "run_shpb.hpp"

namespace {

namespace fs = std::filesystem;
using shpb_test::read_text;
using shpb_test::run_shpb;
using shpb_test::ScratchDir;

const fs::path kSource = SHPB_SOURCE_DIR;
const fs::path kExperiments = kSource / "experiments";

std::vector<std::string> header(const fs::path& csv) {
  const std::string text = read_text(csv);
  std::vector<std::string> names;
  std::string line = text.substr(0, text.find('\n')), name;
  std::stringstream in(line);
  while (std::getline(in, name, ',')) names.push_back(name);
  return names;
}

// The schema's entry of one file (by its id).
nlohmann::json schema_file(const std::string& id) {
  const auto schema = nlohmann::json::parse(read_text(kSource / "src/core/output_schema.json"));
  for (const auto& f : schema.at("files"))
    if (f.at("id") == id) return f;
  FAIL("the output schema has no file " << id);
  return {};
}

// A schema name as a pattern: a part in angle brackets (a gauge, an interface) is any text. The
// names hold letters, digits, '_' and '-' only, none of them special in a pattern.
std::regex name_pattern(const std::string& name) {
  return std::regex(std::regex_replace(name, std::regex("<[^>]+>"), ".+"));
}

// Every column of the written file is one of the schema's, and the schema's fixed names appear
// in its order.
void check_columns(const fs::path& csv, const std::string& id) {
  INFO(csv.string() << " against the schema's " << id);
  const nlohmann::json f = schema_file(id);
  CHECK(f.at("file").get<std::string>() == csv.filename().string());
  std::vector<std::string> fixed;
  std::vector<std::regex> patterns;
  for (const auto& c : f.at("columns")) {
    const std::string name = c.at("name");
    if (name.find('<') == std::string::npos) fixed.push_back(name);
    patterns.push_back(name_pattern(name));
  }
  std::vector<std::string> written_fixed;
  for (const std::string& column : header(csv)) {
    INFO("column " << column);
    bool listed = false;
    for (const auto& p : patterns) listed = listed || std::regex_match(column, p);
    CHECK(listed);
    if (std::find(fixed.begin(), fixed.end(), column) != fixed.end())
      written_fixed.push_back(column);
  }
  CHECK(written_fixed == fixed);
}

}  // namespace

TEST_CASE("simulate and process write the columns of the output schema", "[app][schema]") {
  const ScratchDir dir("output_schema");
  const fs::path sim = dir.path() / "sim", proc = dir.path() / "proc";
  const auto s = run_shpb({"simulate", (kExperiments / "classic-al6061/scene.json").string(), "-o",
                           sim.string(), "--quiet"});
  REQUIRE(s.code == 0);
  for (const char* id : {"gauges", "interfaces", "specimen", "energy", "field"})
    check_columns(sim / schema_file(id).at("file").get<std::string>(), id);
  const auto p =
      run_shpb({"process", (kExperiments / "classic-al6061/scene.json").string(), "--signals",
                (sim / "gauges.csv").string(), "-o", proc.string(), "--quiet"});
  REQUIRE(p.code == 0);
  for (const char* id : {"raw_signals", "pulses", "curve"})
    check_columns(proc / schema_file(id).at("file").get<std::string>(), id);
}

TEST_CASE("compare writes the columns of the output schema", "[app][schema]") {
  const ScratchDir dir("output_schema_compare");
  const auto c = run_shpb({"compare", (kExperiments / "lanl-cu-ofe-273k/scene.json").string(), "-o",
                           dir.path().string(), "--quiet"});
  REQUIRE(c.code == 0);
  check_columns(dir.path() / "comparison.csv", "comparison");
  check_columns(dir.path() / "signals.csv", "compare_signals");
}
