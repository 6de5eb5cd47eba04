#pragma once
// A written CSV file against the output schema (src/core/output_schema.json, docs/outputs.md): the
// one list the C++ writers, the report package and the documentation's tables take their names
// from. Used by the tests that run the command writing the file.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "run_shpb.hpp"

namespace shpb_test {

// The first line of a CSV file, split at its commas (shpb's column names hold none).
inline std::vector<std::string> csv_header(const std::filesystem::path& csv) {
  const std::string text = read_text(csv);
  std::vector<std::string> names;
  std::stringstream in(text.substr(0, text.find('\n')));
  for (std::string name; std::getline(in, name, ',');) names.push_back(name);
  return names;
}

// The schema's entry of one file (by its id).
inline nlohmann::json schema_file(const std::string& id) {
  const auto schema = nlohmann::json::parse(
      read_text(std::filesystem::path(SHPB_SOURCE_DIR) / "src/core/output_schema.json"));
  for (const auto& f : schema.at("files"))
    if (f.at("id") == id) return f;
  FAIL("the output schema has no file " << id);
  return {};
}

// True if `text` is the schema name `name`, a part of it in angle brackets (a gauge, an interface,
// a shot's number) standing for any non-empty text.
inline bool matches_schema_name(const std::string& text, const std::string& name) {
  const std::size_t open = name.find('<');
  if (open == std::string::npos) return text == name;
  if (text.compare(0, open, name, 0, open) != 0) return false;
  const std::string rest = name.substr(name.find('>', open) + 1);
  for (std::size_t from = open + 1; from <= text.size(); ++from)
    if (matches_schema_name(text.substr(from), rest)) return true;
  return false;
}

// Every column of the written file is one of the schema's, and the schema's fixed names appear
// in its order: all of them, but those marked "only" (written under a condition) when absent.
inline void check_schema_columns(const std::filesystem::path& csv, const std::string& id) {
  INFO(csv.string() << " against the schema's " << id);
  const nlohmann::json f = schema_file(id);
  CHECK(matches_schema_name(csv.filename().string(), f.at("file").get<std::string>()));
  const std::vector<std::string> written = csv_header(csv);
  std::vector<std::string> fixed, names;
  for (const auto& c : f.at("columns")) {
    const std::string name = c.at("name");
    const bool present = std::find(written.begin(), written.end(), name) != written.end();
    if (name.find('<') == std::string::npos && (present || !c.contains("only")))
      fixed.push_back(name);
    names.push_back(name);
  }
  std::vector<std::string> written_fixed;
  for (const std::string& column : written) {
    INFO("column " << column);
    bool listed = false;
    for (const auto& n : names) listed = listed || matches_schema_name(column, n);
    CHECK(listed);
    if (std::find(fixed.begin(), fixed.end(), column) != fixed.end())
      written_fixed.push_back(column);
  }
  CHECK(written_fixed == fixed);
}

}  // namespace shpb_test
