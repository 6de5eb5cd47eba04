// The catalogue of broken inputs: scenes and signal files as people and instruments
// really produce them. Each runs the real executable with a time limit and either works (exit 0,
// with a warning saying what was assumed where something was) or is refused (exit 2, one
// "error:" line naming the file and the place). None may crash, hang, print NaN, write half an
// output folder or leave temporary folders behind.
#include <catch2/catch.hpp>
#include <cctype>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "child_process.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_robustness_test_broken_inputs {

namespace {

using namespace shpb_robust;

// A run that takes longer than this is a hang: the slowest case reads, simulates or processes a
// 0.6 m bar set-up, which takes well under a second in Release and a few under the sanitizers.
constexpr double kHangLimit_s = 30.0;

// A short, fast Kolsky bar: steel bars, a bilinear aluminium specimen, one gauge on each bar.
const char* const kScene = R"({
  "name": "catalogue",
  "bars": [
    {"name": "striker", "material": "steel", "length": "100 mm", "diameter": "12 mm",
     "velocity": "10 m/s"},
    {"name": "incident", "material": "steel", "length": "600 mm", "diameter": "12 mm",
     "gauges": [{"name": "incident", "position": "300 mm"}]},
    {"name": "specimen", "material": "aluminium", "length": "4 mm", "diameter": "8 mm"},
    {"name": "transmitter", "material": "steel", "length": "600 mm", "diameter": "12 mm",
     "gauges": [{"name": "transmitted", "position": "300 mm"}]}
  ],
  "specimen": "specimen",
  "materials": {
    "steel": {"model": "elastic", "density": "7850 kg/m3", "youngs_modulus": "200 GPa",
              "poisson_ratio": 0.29},
    "aluminium": {"model": "bilinear", "density": "2700 kg/m3", "youngs_modulus": "70 GPa",
                  "poisson_ratio": 0.33, "yield_stress": "150 MPa", "tangent_modulus": "700 MPa"}
  },
  "simulation": {"sample_rate": "5 MHz"}
})";

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t p = s.find(from); p != std::string::npos; p = s.find(from, p + to.size()))
    s.replace(p, from.size(), to);
  return s;
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

// prefix + text, written with append: GCC 12 warns falsely (-Wrestrict) on "literal" + string.
std::string prepend(std::string prefix, const std::string& text) { return prefix.append(text); }

std::string join(const std::vector<std::string>& lines, const std::string& eol = "\n") {
  std::string s;
  for (const auto& l : lines) s += l + eol;
  return s;
}

// The gauge signals the simulator writes for kScene: a valid gauges.csv to break.
const std::string& good_signals() {
  static const std::string text = [] {
    ScratchFolder dir("signals");
    write_bytes(dir.path() / "scene.json", kScene);
    const Outcome o = run({"simulate", (dir.path() / "scene.json").string(), "-o",
                           (dir.path() / "sim").string(), "--quiet"},
                          dir.path(), kHangLimit_s);
    INFO(o.err);
    REQUIRE(o.code == 0);
    return read_all(dir.path() / "sim" / "gauges.csv");
  }();
  return text;
}

// Latin-1 / UTF-16 encodings of ASCII text.
std::string utf16le(const std::string& ascii) {
  std::string s = "\xFF\xFE";
  for (char c : ascii) s += std::string{c, '\0'};
  return s;
}

enum class Expect { kWorks, kRefused };

struct Case {
  std::string what;
  std::function<void(const fs::path& dir)> setup;  // writes scene.json, signals.csv, ...
  std::vector<std::string> args;                   // "{dir}" stands for the case folder
  Expect expect;
  std::string needle;  // refused: names file and place; works: the warning (may be empty)
};

std::vector<std::string> validate() { return {"validate", "{dir}/scene.json"}; }
std::vector<std::string> simulate() {
  return {"simulate", "{dir}/scene.json", "-o", "{dir}/out", "--quiet"};
}
std::vector<std::string> process() {
  return {"process", "{dir}/scene.json", "--signals", "{dir}/signals.csv",
          "-o",      "{dir}/out",        "--quiet"};
}

// A scene with one edit applied to the text of kScene.
std::function<void(const fs::path&)> scene_with(const std::string& from, const std::string& to) {
  return [=](const fs::path& dir) {
    const std::string text = replace_all(kScene, from, to);
    REQUIRE(text != kScene);
    write_bytes(dir / "scene.json", text);
  };
}
std::function<void(const fs::path&)> scene_bytes(const std::string& bytes) {
  return [=](const fs::path& dir) { write_bytes(dir / "scene.json", bytes); };
}
// The simulated signals, transformed.
std::function<void(const fs::path&)> signals(std::function<std::string(std::string)> edit) {
  return [=](const fs::path& dir) {
    write_bytes(dir / "scene.json", kScene);
    write_bytes(dir / "signals.csv", edit(good_signals()));
  };
}
// The simulated signals with row `row` (0 = header) replaced.
std::function<void(const fs::path&)> signal_row(std::size_t row, const std::string& text) {
  return signals([=](std::string s) {
    auto lines = split_lines(s);
    lines.at(row) = text;
    return join(lines);
  });
}

// "nan", "inf", "-inf", "infinity" as a token (any case); "inferred" or "financial" are words.
bool has_non_finite_number(std::string text) {
  for (auto& ch : text) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  const auto letter = [&](std::size_t i) {
    return i < text.size() && std::isalpha(static_cast<unsigned char>(text[i]));
  };
  for (const std::string token : {"nan", "inf"})
    for (std::size_t p = text.find(token); p != std::string::npos; p = text.find(token, p + 1))
      if ((p == 0 || !letter(p - 1)) && (!letter(p + 3) || text.compare(p, 8, "infinity") == 0))
        return true;
  return false;
}

// Runs one case and checks the rules that hold for every case.
void check(const Case& c) {
  ScratchFolder scratch("case");
  const fs::path& dir = scratch.path();
  c.setup(dir);
  std::vector<std::string> args;
  for (const auto& a : c.args) args.push_back(replace_all(a, "{dir}", dir.string()));
  const bool out_existed = fs::exists(dir / "out");
  const Outcome o = run(args, dir, kHangLimit_s);
  INFO("case: " << c.what << "\nstderr: " << o.err);
  REQUIRE_FALSE(o.timed_out);
  REQUIRE(o.signal == 0);
  CHECK(o.err.find("internal") == std::string::npos);
  CHECK(litter(dir).empty());
  if (c.expect == Expect::kRefused) {
    REQUIRE(o.code == 2);
    CHECK(o.err.rfind("error: ", 0) == 0);
    CHECK(o.err.find('\n') == o.err.size() - 1);  // one line
    CHECK(o.err.find(c.needle) != std::string::npos);
    if (!out_existed) CHECK_FALSE(fs::exists(dir / "out"));
  } else {
    REQUIRE(o.code == 0);
    CHECK(o.err.find(c.needle) != std::string::npos);
    if (fs::exists(dir / "out"))
      for (const auto& e : fs::directory_iterator(dir / "out")) {
        std::string text = read_all(e.path());
        INFO(e.path().filename().string());
        CHECK_FALSE(has_non_finite_number(text));
      }
  }
}

void check_all(const std::vector<Case>& cases) {
  for (const auto& c : cases) {
    DYNAMIC_SECTION(c.what) { check(c); }
  }
}

}  // namespace

TEST_CASE("Broken scene files are refused with file and place, or read with what was assumed",
          "[robustness]") {
  check_all({
      {"an empty scene file", scene_bytes(""), validate(), Expect::kRefused, "scene.json"},
      {"a scene of blanks and newlines only", scene_bytes("  \n\r\n \t\n"), validate(),
       Expect::kRefused, "scene.json"},
      {"a UTF-8 byte order mark", scene_bytes(std::string("\xEF\xBB\xBF") + kScene), validate(),
       Expect::kWorks, ""},
      {"CRLF line ends", scene_bytes(replace_all(kScene, "\n", "\r\n")), validate(), Expect::kWorks,
       ""},
      {"a Latin-1 byte in a name",
       scene_with("\"catalogue\"",
                  "\"Pr\xFC"
                  "fung\""),
       validate(), Expect::kRefused, "scene.json"},
      {"UTF-16 text", scene_bytes(utf16le(kScene)), validate(), Expect::kRefused,
       "scene.json: line 1: UTF-16"},
      {"a decimal comma in a length", scene_with("\"100 mm\"", "\"0,1 m\""), validate(),
       Expect::kRefused, "scene.json: bars[0].length"},
      {"a bare decimal comma (invalid JSON)", scene_with("0.29", "0,29"), validate(),
       Expect::kRefused, "scene.json: line"},
      {"text in a number",
       scene_with("\"600 mm\", \"diameter\": \"12 mm\",\n     \"gauges\": [{\"name\": \"incident\"",
                  "\"six hundred mm\", \"diameter\": \"12 mm\",\n     \"gauges\": [{\"name\": "
                  "\"incident\""),
       validate(), Expect::kRefused, "scene.json: bars[1].length"},
      {"NaN written as a bare word", scene_with("0.33", "NaN"), validate(), Expect::kRefused,
       "scene.json: line"},
      {"nan as a quantity", scene_with("\"4 mm\"", "\"nan mm\""), validate(), Expect::kRefused,
       "scene.json: bars[2].length"},
      {"inf as a quantity", scene_with("\"10 m/s\"", "\"inf m/s\""), validate(), Expect::kRefused,
       "scene.json: bars[0].velocity"},
      {"a number beyond double range", scene_with("\"8 mm\"", "1e999"), validate(),
       Expect::kRefused, "scene.json: bars[2].diameter"},
      {"a duplicate key",
       scene_with("\"velocity\": \"10 m/s\"", "\"velocity\": \"10 m/s\", \"velocity\": \"12 m/s\""),
       validate(), Expect::kRefused, "scene.json"},
      {"truncated JSON", scene_bytes(std::string(kScene).substr(0, 300)), validate(),
       Expect::kRefused, "scene.json: line"},
      {"a negative duration",
       scene_with("\"sample_rate\": \"5 MHz\"",
                  "\"sample_rate\": \"5 MHz\", \"duration\": \"-400 us\""),
       validate(), Expect::kRefused, "scene.json: simulation.duration"},
      {"a gauge beyond its bar",
       scene_with("\"position\": \"300 mm\"}]}\n  ]", "\"position\": \"700 mm\"}]}\n  ]"),
       validate(), Expect::kRefused, "scene.json: bars[3].gauges[0].position"},
      {"a gigabyte-sized bar length",
       scene_with(
           "\"600 mm\", \"diameter\": \"12 mm\",\n     \"gauges\": [{\"name\": \"incident\"",
           "\"1000 km\", \"diameter\": \"12 mm\",\n     \"gauges\": [{\"name\": \"incident\""),
       simulate(), Expect::kRefused, "memory"},
      {"an absurd element count",
       scene_with("\"length\": \"4 mm\"", "\"length\": \"4 mm\", \"elements\": 100000000"),
       simulate(), Expect::kRefused, "memory"},
      {"an absurd duration",
       scene_with("\"sample_rate\": \"5 MHz\"",
                  "\"sample_rate\": \"5 MHz\", \"duration\": \"1000 s\""),
       validate(), Expect::kRefused, "scene.json: simulation"},
      {"a missing scene file", [](const fs::path&) {}, validate(), Expect::kRefused, "scene.json"},
      {"a folder given as the scene",
       [](const fs::path& dir) { fs::create_directory(dir / "scene.json"); }, validate(),
       Expect::kRefused, "scene.json"},
      {"a missing material file",
       scene_with("\"material\": \"aluminium\"", "\"material\": \"no-such-specimen.json\""),
       validate(), Expect::kRefused, "no-such-specimen.json"},
  });
}

TEST_CASE("Broken signal files are refused with file, line and column, or read with a warning",
          "[robustness]") {
  const auto rows = [] { return split_lines(good_signals()); };
  check_all({
      {"the simulated signals as written", signals([](std::string s) { return s; }), process(),
       Expect::kWorks, ""},
      {"an empty signal file", signals([](std::string) { return ""; }), process(), Expect::kRefused,
       "signals.csv"},
      {"a header only", signals([rows](std::string) { return rows()[0] + "\n"; }), process(),
       Expect::kRefused, "signals.csv"},
      {"a single sample", signals([rows](std::string) {
         return join({rows()[0], rows()[1]});
       }),
       process(), Expect::kRefused, "signals.csv"},
      {"a UTF-8 byte order mark", signals([](std::string s) { return prepend("\xEF\xBB\xBF", s); }),
       process(), Expect::kWorks, ""},
      {"CRLF line ends", signals([](std::string s) { return replace_all(s, "\n", "\r\n"); }),
       process(), Expect::kWorks, ""},
      {"old Mac CR line ends", signals([](std::string s) { return replace_all(s, "\n", "\r"); }),
       process(), Expect::kWorks, ""},
      {"a Latin-1 comment line above the header", signals([](std::string s) {
         return prepend(
             "# Pr\xFC"
             "fstand, 20 \xB0"
             "C\n",
             s);
       }),
       process(), Expect::kWorks, ""},
      {"a Latin-1 footer line after the data (its warning in summary.json)",
       signals([](std::string s) { return s + "Ende der Messung (Messger\xE4t 1)\n"; }), process(),
       Expect::kWorks, ""},
      {"UTF-16 text (Excel's \"Unicode Text\")", signals([](std::string s) { return utf16le(s); }),
       process(), Expect::kWorks, ""},
      {"UTF-16 text cut inside a character",
       signals([](std::string s) { return utf16le(s).substr(0, 2 * s.size() + 1); }), process(),
       Expect::kRefused, "an odd number of bytes"},
      {"semicolons and decimal commas",
       signals([](std::string s) { return replace_all(replace_all(s, ",", ";"), ".", ","); }),
       process(), Expect::kWorks, ""},
      {"tabs as separators", signals([](std::string s) { return replace_all(s, ",", "\t"); }),
       process(), Expect::kWorks, ""},
      {"quoted fields", signals([](std::string s) {
         auto lines = split_lines(s);
         for (auto& l : lines) l = prepend("\"", replace_all(l, ",", "\",\"")) + "\"";
         return join(lines);
       }),
       process(), Expect::kWorks, ""},
      {"text in a number", signal_row(5, "8e-07,abc,0"), process(), Expect::kRefused,
       "signals.csv: line 6, column 2"},
      {"NaN in a sample", signal_row(7, "1.2e-06,NaN,0"), process(), Expect::kRefused,
       "signals.csv: line 8, column 2"},
      {"NaN in the first sample", signal_row(1, "0,NaN,0"), process(), Expect::kRefused,
       "signals.csv: line 2, column 2"},
      {"a scope's OVER in a column not read, in the first samples", signals([](std::string s) {
         auto lines = split_lines(s);
         lines[0] += ",trigger";
         for (std::size_t i = 1; i < lines.size(); ++i) lines[i] += i <= 3 ? ",OVER" : ",0";
         return join(lines);
       }),
       process(), Expect::kWorks, ""},
      {"inf in a sample", signal_row(7, "1.2e-06,0,inf"), process(), Expect::kRefused,
       "signals.csv: line 8, column 3"},
      {"a number beyond double range", signal_row(7, "1.2e-06,1e999,0"), process(),
       Expect::kRefused, "signals.csv: line 8, column 2"},
      {"a NUL byte on line 1002", signal_row(1001, std::string("2e-04,0\0,0", 10)), process(),
       Expect::kRefused, "signals.csv: line 1002: UTF-16 or binary data (a NUL byte)"},
      {"an empty field", signal_row(9, "1.6e-06,,0"), process(), Expect::kRefused,
       "signals.csv: line 10, column 2"},
      {"a missing column", signals([](std::string s) {
         auto lines = split_lines(s);
         for (auto& l : lines) l = l.substr(0, l.rfind(','));
         return join(lines);
       }),
       process(), Expect::kRefused, "signals.csv: line 1"},
      {"a duplicate column", signals([](std::string s) {
         auto lines = split_lines(s);
         lines[0] = "time_s,incident,incident";
         return join(lines);
       }),
       process(), Expect::kRefused, "signals.csv: line 1"},
      {"time going backwards", signal_row(20, "1e-06,0,0"), process(), Expect::kRefused,
       "signals.csv: line 21"},
      {"a gap in the time stamps", signals([](std::string s) {
         auto lines = split_lines(s);
         lines.erase(lines.begin() + 100, lines.begin() + 110);
         return join(lines);
       }),
       process(), Expect::kRefused, "signals.csv: line 101"},
      {"time stamps rounded so that they repeat", signals([](std::string s) {
         auto lines = split_lines(s);
         for (std::size_t i = 1; i < lines.size(); ++i) {
           const auto comma = lines[i].find(',');
           const double t = std::stod(lines[i].substr(0, comma));
           char b[32];
           std::snprintf(b, sizeof b, "%.2e", t);  // 3 digits: 1.20e-05, 1.20e-05, 1.21e-05
           lines[i] = b + lines[i].substr(comma);
         }
         return join(lines);
       }),
       process(), Expect::kWorks, "time base rebuilt"},
      {"all time stamps equal", signals([](std::string s) {
         auto lines = split_lines(s);
         for (std::size_t i = 1; i < lines.size(); ++i)
           lines[i] = prepend("0", lines[i].substr(lines[i].find(',')));
         return join(lines);
       }),
       process(), Expect::kRefused, "signals.csv"},
      {"a truncated last line", signals([](std::string s) {
         auto lines = split_lines(s);
         lines.back() = lines.back().substr(0, lines.back().find(',') + 3);
         return join(lines, "\n").substr(0, join(lines).size() - 1);
       }),
       process(), Expect::kRefused, "signals.csv: line"},
      {"a last line cut inside a number", signals([](std::string s) {
         return s.substr(0, s.size() - 1).substr(0, s.rfind('\n', s.size() - 2) + 6);
       }),
       process(), Expect::kRefused, "signals.csv: line"},
      {"binary garbage", signals([](std::string) {
         std::string g;
         for (int i = 0; i < 4096; ++i) g += static_cast<char>((i * 7919 + 13) % 256);
         return g;
       }),
       process(), Expect::kRefused, "signals.csv"},
      {"a missing signal file",
       [](const fs::path& dir) { write_bytes(dir / "scene.json", kScene); }, process(),
       Expect::kRefused, "signals.csv"},
      {"a folder given as the signal file",
       [](const fs::path& dir) {
         write_bytes(dir / "scene.json", kScene);
         fs::create_directory(dir / "signals.csv");
       },
       process(), Expect::kRefused, "signals.csv"},
  });
}

TEST_CASE("An output folder that cannot be written is refused before anything is computed",
          "[robustness]") {
  const auto with_scene = [](const fs::path& dir) { write_bytes(dir / "scene.json", kScene); };
  check_all({
      {"an output folder inside a file",
       with_scene,
       {"simulate", "{dir}/scene.json", "-o", "{dir}/scene.json/out", "--quiet"},
       Expect::kRefused,
       "scene.json"},
      {"an output folder in a read-only file system",
       with_scene,
       {"simulate", "{dir}/scene.json", "-o", "/proc/shpb-robust-out", "--quiet"},
       Expect::kRefused,
       "/proc"},
      {"an output path that is a file",
       [](const fs::path& dir) {
         write_bytes(dir / "scene.json", kScene);
         write_bytes(dir / "out", "not a folder");
       },
       simulate(), Expect::kRefused, "out: exists and is not a folder"},
      {"an output folder holding someone else's files",
       [](const fs::path& dir) {
         write_bytes(dir / "scene.json", kScene);
         fs::create_directory(dir / "out");
         write_bytes(dir / "out" / "thesis.tex", "\\documentclass{article}");
       },
       simulate(), Expect::kRefused, "shpb replaces only folders it wrote"},
  });
}

TEST_CASE("Files the program did not write are never deleted or modified", "[robustness]") {
  ScratchFolder scratch("keep");
  const fs::path& dir = scratch.path();
  write_bytes(dir / "scene.json", kScene);
  fs::create_directory(dir / "out");
  write_bytes(dir / "out" / "thesis.tex", "mine");
  write_bytes(dir / "signals.csv", good_signals());
  const Outcome refused =
      run({"simulate", (dir / "scene.json").string(), "-o", (dir / "out").string(), "--quiet"}, dir,
          kHangLimit_s);
  CHECK(refused.code == 2);
  CHECK(read_all(dir / "out" / "thesis.tex") == "mine");
  const Outcome processed =
      run({"process", (dir / "scene.json").string(), "--signals", (dir / "signals.csv").string(),
           "-o", (dir / "p").string(), "--quiet"},
          dir, kHangLimit_s);
  CHECK(processed.code == 0);
  CHECK(read_all(dir / "signals.csv") == good_signals());  // the measured file is untouched
}

}  // namespace tests_robustness_test_broken_inputs
