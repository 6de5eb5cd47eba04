// The reference documentation lists exactly what the code accepts: every option of every command
// in its section of docs/commands.md, every key of every JSON object the input readers open in its
// table of docs/scene-format.md, and nothing more. The lists are the code's own: the commands'
// CLI11 definitions (app/commands.hpp, add_commands) and the readers' key lists
// (model/input_keys.hpp; fit's nuisance names and the law parameters it may free).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "app/commands.hpp"
#include "core/enum_names.hpp"
#include "model/fit_spec.hpp"
#include "model/input_keys.hpp"
#include "model/law_parameters.hpp"
#include "model/material.hpp"
#include "model/material_reader.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_app_test_docs_complete {

namespace {

namespace fs = std::filesystem;
using Keys = shpb::input_keys::Keys;

std::vector<std::string> doc_lines(const std::string& name) {
  std::ifstream in(fs::path(SHPB_SOURCE_DIR) / "docs" / name);
  REQUIRE(in);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

// The text inside each pair of backticks.
std::vector<std::string> code_spans(const std::string& text) {
  std::vector<std::string> spans;
  for (std::size_t a = text.find('`'); a != std::string::npos; a = text.find('`', a + 1)) {
    const std::size_t b = text.find('`', a + 1);
    if (b == std::string::npos) break;
    spans.push_back(text.substr(a + 1, b - a - 1));
    a = b;
  }
  return spans;
}

// The cells of a table row "| a | b |" (a `\|` inside a cell is not a separator).
std::vector<std::string> cells(const std::string& row) {
  std::vector<std::string> out;
  std::string cell;
  for (std::size_t i = 1; i < row.size(); ++i) {
    if (row[i] == '|' && row[i - 1] != '\\') {
      out.push_back(cell);
      cell.clear();
    } else {
      cell += row[i];
    }
  }
  for (auto& c : out) {
    c.erase(0, c.find_first_not_of(' '));
    c.erase(c.find_last_not_of(' ') + 1);
  }
  return out;
}

bool contains(const std::vector<std::string>& v, const std::string& x) {
  return std::find(v.begin(), v.end(), x) != v.end();
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

// A Markdown table: the label it follows, its header's first cell and its body rows.
struct Table {
  std::string label;
  std::string first_header;
  std::vector<std::string> rows;
};

// Every table of a document, each labelled by what introduces it: the paragraph just before it
// when that paragraph opens with a `code` or **bold** name (`bars[].gauges[]`:, **bilinear** —),
// else the heading of its section (## bars).
std::vector<Table> tables(const std::vector<std::string>& lines) {
  std::vector<Table> out;
  std::string heading, paragraph_start;
  bool in_table = false, after_blank = true;
  for (const auto& l : lines) {
    const bool table_line = l.rfind("|", 0) == 0;
    if (table_line && !in_table) {
      std::string label = heading;
      if (paragraph_start.rfind("`", 0) == 0 && paragraph_start.rfind("``", 0) != 0)
        label = code_spans(paragraph_start).at(0);
      else if (paragraph_start.rfind("**", 0) == 0)
        label = paragraph_start.substr(2, paragraph_start.find("**", 2) - 2);
      out.push_back({label, cells(l).at(0), {}});
    } else if (table_line && l.rfind("|---", 0) != 0) {
      out.back().rows.push_back(l);
    }
    in_table = table_line;
    if (l.rfind("#", 0) == 0) {
      heading = l.substr(l.find_first_not_of('#'));
      heading.erase(0, heading.find_first_not_of(' '));
      paragraph_start = l;
    } else if (l.empty()) {
      after_blank = true;
      continue;
    } else if (after_blank) {
      paragraph_start = l;
    }
    after_blank = false;
  }
  return out;
}

// --- docs/commands.md ------------------------------------------------------------------------

// The option names ("--output", "-o") of a command, without CLI11's own --help.
std::vector<std::string> option_names(const CLI::App& command) {
  std::vector<std::string> names;
  for (const CLI::Option* o : command.get_options()) {
    for (const auto& n : o->get_lnames())
      if (n != "help") names.push_back("--" + n);
    for (const auto& n : o->get_snames())
      if (n != "h") names.push_back("-" + n);
  }
  return names;
}

// The option names in the first column of the option tables ("| option | …") of `lines`.
std::vector<std::string> documented_options(const std::vector<std::string>& lines) {
  std::vector<std::string> names;
  for (const Table& t : tables(lines)) {
    if (t.first_header != "option") continue;
    for (const auto& row : t.rows)
      for (const auto& span : code_spans(cells(row).at(0)))
        if (span.rfind("-", 0) == 0) names.push_back(span.substr(0, span.find(' ')));
  }
  return names;
}

// The lines of each "## " section, by its heading.
std::vector<std::pair<std::string, std::vector<std::string>>> sections(
    const std::vector<std::string>& lines) {
  std::vector<std::pair<std::string, std::vector<std::string>>> out;
  for (const auto& l : lines) {
    if (l.rfind("## ", 0) == 0)
      out.push_back({l.substr(3), {}});
    else if (!out.empty())
      out.back().second.push_back(l);
  }
  return out;
}

std::vector<std::string> commands_doc_mismatches() {
  const std::string doc = "docs/commands.md";
  CLI::App app;
  const std::vector<shpb::Command> commands = shpb::add_commands(app);
  const auto secs = sections(doc_lines("commands.md"));
  // "## Options shared by `simulate`, `compare`, …": that table documents options of each.
  std::vector<std::string> shared_commands, shared_options;
  for (const auto& [heading, body] : secs)
    if (heading.rfind("Options shared by", 0) == 0) {
      shared_commands = code_spans(heading);
      shared_options = documented_options(body);
    }
  std::vector<std::string> bad;
  if (shared_options.empty()) bad.push_back(doc + ": no table of shared options");
  for (const shpb::Command& c : commands) {
    const std::string name = c.app->get_name(), where = doc + ", section \"## " + name + "\"";
    const auto sec =
        std::find_if(secs.begin(), secs.end(), [&](const auto& s) { return s.first == name; });
    if (sec == secs.end()) {
      bad.push_back(doc + ": no section \"## " + name + "\" for the command shpb " + name);
      continue;
    }
    const auto real = option_names(*c.app);
    const auto own = documented_options(sec->second);
    const bool shared = contains(shared_commands, name);
    for (const auto& o : real)
      if (!contains(own, o) && !(shared && contains(shared_options, o)))
        bad.push_back(where + ": option " + o + " of shpb " + name + " is not in its option table");
    for (const auto& o : own)
      if (!contains(real, o))
        bad.push_back(where + ": documents " + o + ", which shpb " + name + " does not have");
    for (const auto& o : shared ? shared_options : std::vector<std::string>{})
      if (!contains(real, o))
        bad.push_back(doc + ", shared options: documents " + o + " for shpb " + name +
                      ", which does not have it");
  }
  for (const auto& s : shared_commands)
    if (std::none_of(commands.begin(), commands.end(),
                     [&](const shpb::Command& c) { return c.app->get_name() == s; }))
      bad.push_back(doc + ", shared options: names `" + s + "`, which is not a command");
  return bad;
}

// --- docs/scene-format.md --------------------------------------------------------------------

// A JSON object a reader opens and the table of docs/scene-format.md that documents it (by its
// label, see tables()). The objects under some of its keys (`measurement.time`, a channel's
// `bridge`) are documented in the same table: as rows `time.interval`, or in the row of their key
// as `"interval"` or `interval` in backticks.
struct DocObject {
  std::string label;
  Keys keys;
  std::vector<std::pair<std::string, Keys>> children = {};
};

// The law parameters a campaign may free (`free`), of every model; a viscoelastic arm's as
// `arms[k].modulus`.
Keys free_parameter_names() {
  Keys names;
  for (const auto& [model_name, model] : shpb::kMaterialModelNames) {
    shpb::MaterialSpec m;
    m.model = model;
    m.viscoelastic.arms.resize(1);
    for (std::string name : shpb::law_parameter_names(m)) {
      if (name.rfind("arms[0]", 0) == 0) name.replace(0, 7, "arms[k]");
      if (!contains(names, name)) names.push_back(name);
    }
  }
  return names;
}

std::vector<DocObject> scene_format_objects() {
  namespace k = shpb::input_keys;
  std::vector<DocObject> objects = {
      {"Top level", k::kScene},
      {"bars", k::kBar},
      {"bars[].gauges[]", k::kGauge},
      {"materials", k::kMaterial, {{"uncertainty", k::kFitInterval}}},
      {"contact", k::kContact},
      {"contact.interfaces[]", k::kInterface},
      {"simulation", k::kSimulation},
      {"measurement",
       k::kMeasurement,
       {{"time", k::kMeasurementTime},
        {"windows", k::kWindows},
        {"rate_window", k::kRateWindow},
        {"corrections", k::kCorrections}}},
      {"measurement.channels[]", k::kChannel, {{"bridge", k::kBridge}}},
      {"measurement.dispersion", k::kDispersion},
      {"measurement.uncertainty",
       k::kUncertainty,
       {{"bars", k::kUncertaintyBar}, {"bars", k::kUncertaintySpecimen}}},
      {"calibration",
       k::kCalibration,
       {{"bars", k::kCalibrationBar},
        {"bars", k::kCalibratedValue},
        {"gauges", k::kCalibrationGauge}}},
      {"Monte Carlo distributions", k::kDistributions, {{"values", k::kDistribution}}},
      {"plan",
       k::kPlan,
       {{"striker", k::kPlanStriker}, {"shaper", k::kPlanShaper}, {"specimen", k::kPlanSpecimen}}},
      {"Campaign files",
       k::kCampaign,
       {{"tests", k::kCampaignTest},
        {"nuisance", shpb::enum_names(shpb::kNuisanceNames)},
        {"free", free_parameter_names()}}}};
  // Each material model's own keys, in the table named after the model (**bilinear** — …).
  for (const auto& [name, model] : shpb::kMaterialModelNames) {
    DocObject o{std::string(name), shpb::material_model_keys(model)};
    if (model == shpb::MaterialModel::kViscoelastic) o.children = {{"arms", k::kMaxwellArm}};
    objects.push_back(o);
  }
  return objects;
}

// The keys a row documents: its first cell's backticked names, `[]` of an array dropped.
std::vector<std::string> row_keys(const std::string& row) {
  std::vector<std::string> keys;
  for (auto span : code_spans(cells(row).at(0))) {
    if (span.size() > 2 && span.substr(span.size() - 2) == "[]") span.resize(span.size() - 2);
    keys.push_back(span);
  }
  return keys;
}

void check_object(const DocObject& o, const Table& t, std::vector<std::string>& bad) {
  const std::string where = "docs/scene-format.md, table \"" + o.label + "\"";
  std::set<std::string> documented;
  for (const auto& row : t.rows) {
    const auto keys = row_keys(row);
    if (keys.empty()) bad.push_back(where + ": a row names no `key`: " + row);
    for (const auto& key : keys) {
      const std::string head = key.substr(0, key.find('.'));
      const std::string rest =
          key.find('.') == std::string::npos ? "" : key.substr(key.find('.') + 1);
      documented.insert(head);
      if (!contains(o.keys, head)) {
        bad.push_back(where + ": documents `" + key +
                      "`, which the reader does not accept (it accepts " + joined(o.keys) + ")");
        continue;
      }
      const bool known =
          rest.empty() || std::any_of(o.children.begin(), o.children.end(), [&](const auto& c) {
            return c.first == head && contains(c.second, rest);
          });
      if (!known)
        bad.push_back(where + ": documents `" + key + "`, which the reader of `" + head +
                      "` does not accept");
    }
  }
  for (const auto& key : o.keys)
    if (!documented.count(key))
      bad.push_back(where + ": key `" + key + "`, which the reader accepts, is not documented");
  for (const auto& [head, keys] : o.children) {
    std::string head_row;
    for (const auto& row : t.rows)
      if (contains(row_keys(row), head)) head_row = row;
    for (const auto& key : keys) {
      const bool as_row = std::any_of(t.rows.begin(), t.rows.end(), [&](const std::string& row) {
        return contains(row_keys(row), head + "." + key);
      });
      const bool in_head_row = head_row.find("`" + key + "`") != std::string::npos ||
                               head_row.find("\"" + key + "\"") != std::string::npos;
      if (!as_row && !in_head_row)
        bad.push_back(where + ": key `" + head + "." + key +
                      "`, which the reader accepts, is documented neither as a row nor in the "
                      "row of `" +
                      head + "`");
    }
  }
}

std::vector<std::string> scene_format_mismatches() {
  const auto objects = scene_format_objects();
  const auto all = tables(doc_lines("scene-format.md"));
  std::vector<std::string> bad;
  for (const DocObject& o : objects) {
    std::vector<const Table*> found;
    for (const Table& t : all)
      if (t.first_header == "key" && t.label == o.label) found.push_back(&t);
    if (found.size() != 1)
      bad.push_back("docs/scene-format.md: " + std::to_string(found.size()) +
                    " key tables labelled \"" + o.label +
                    "\", expected one (its keys: " + joined(o.keys) + ")");
    else
      check_object(o, *found.front(), bad);
  }
  for (const Table& t : all)
    if (t.first_header == "key" &&
        std::none_of(objects.begin(), objects.end(),
                     [&](const DocObject& o) { return o.label == t.label; }))
      bad.push_back("docs/scene-format.md: the key table labelled \"" + t.label +
                    "\" documents no object a reader opens");
  return bad;
}

}  // namespace

TEST_CASE("docs/commands.md lists exactly the options of every command", "[app][cli][docs]") {
  const auto bad = commands_doc_mismatches();
  for (const auto& b : bad) FAIL_CHECK(b);
  CHECK(bad.empty());
}

TEST_CASE("docs/scene-format.md documents exactly the keys the input readers accept",
          "[app][docs]") {
  const auto bad = scene_format_mismatches();
  for (const auto& b : bad) FAIL_CHECK(b);
  CHECK(bad.empty());
}

}  // namespace tests_app_test_docs_complete
