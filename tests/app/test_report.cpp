// `shpb report DIR`: every figure of an output folder is a non-empty PNG referenced by
// report.html, and a real browser renders the page to something that is not blank.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../skip.hpp"
#include "run_shpb.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_app_test_report {

namespace fs = std::filesystem;
using shpb_test::read_text;
using shpb_test::run_shpb;
using shpb_test::scratch_dir;

namespace {

const fs::path kClassic = fs::path(SHPB_SOURCE_DIR) / "experiments/classic-al6061/scene.json";

// A PNG file starts with these eight bytes (PNG specification, §5.2).
const std::string kPngSignature = "\x89PNG\r\n\x1a\n";

// Checks one expected figure: exists, is a PNG with content, and report.html links it.
void check_figure(const fs::path& dir, const std::string& html, const std::string& name) {
  INFO("figure " << name);
  const fs::path png = dir / "figures" / name;
  REQUIRE(fs::exists(png));
  CHECK(fs::file_size(png) > 1000);  // a figure with axes and text, not an empty image
  CHECK(read_text(png).substr(0, 8) == kPngSignature);
  CHECK(html.find("figures/" + name) != std::string::npos);
}

// A study folder as `shpb study` writes it (its documented columns): a made-up sweep whose error
// falls as resolution², enough to draw the Pareto chart and a stability map. Global stepping costs
// 8 × the asynchronous run of the same error, so the front is the asynchronous runs.
fs::path write_study_folder(const fs::path& dir) {
  fs::create_directories(dir);
  std::ofstream pareto(dir / "pareto.csv");
  pareto << "method,stepping,resolution,error,wall_time_s,node_updates,stable,"
            "pareto_front_wall_time,pareto_front_node_updates\n";
  for (const char* method : {"penalty", "localized-bipenalty"})
    for (const char* stepping : {"asynchronous", "global"})
      for (double r : {0.5, 1.0, 2.0}) {
        const bool global = stepping[0] == 'g';
        pareto << method << ',' << stepping << ',' << r << ',' << 0.01 / (r * r) << ','
               << 0.01 * r * r * (global ? 8 : 1) << ',' << 1e6 * r * (global ? 8 : 1) << ",1,"
               << !global << ',' << !global << "\n";
      }
  std::ofstream stability(dir / "stability.csv");
  stability << "method,stiffness_factor,courant,mass_ratio,stable\n";
  for (double k : {1e-2, 1.0, 1e2, 1e4})
    for (double c : {0.2, 0.5, 0.9, 1.0})
      stability << "penalty," << k << ',' << c << ",," << (c * c * k <= 2 ? 1 : 0) << '\n';
  std::ofstream(dir / "summary.json") << "{\"reference\": \"exact\"}\n";
  return dir;
}

}  // namespace

TEST_CASE("The report of the default experiment holds every figure, each referenced by the page",
          "[app][report]") {
  if (!shpb_test::have_matplotlib()) {
    SHPB_SKIP("python3 with matplotlib and numpy not installed: report test skipped");
  }
  const fs::path dir = scratch_dir("report_default") / "classic";
  REQUIRE(run_shpb({"simulate", kClassic.string(), "-o", (dir / "simulate").string(), "--quiet"})
              .code == 0);
  REQUIRE(run_shpb({"process", kClassic.string(), "-o", (dir / "process").string(), "--signals",
                    (dir / "simulate" / "gauges.csv").string(), "--quiet"})
              .code == 0);
  const auto r = run_shpb({"report", dir.string()});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const std::string html = read_text(dir / "report.html");
  REQUIRE(html.find("</html>") != std::string::npos);
  for (const char* name :
       {"signals_simulate.png", "wave_diagram_simulate.png", "stress_strain_process.png",
        "rate_equilibrium_process.png", "energy_simulate.png", "pulses_process.png",
        "specimen_stress_strain_simulate.png"})
    check_figure(dir, html, name);
}

TEST_CASE("The report of a study folder shows accuracy against cost and the stability map",
          "[app][report]") {
  if (!shpb_test::have_matplotlib()) {
    SHPB_SKIP("python3 with matplotlib and numpy not installed: report test skipped");
  }
  const fs::path dir = write_study_folder(scratch_dir("report_study") / "study");
  const auto r = run_shpb({"report", dir.string()});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const std::string html = read_text(dir / "report.html");
  check_figure(dir, html, "pareto.png");
  check_figure(dir, html, "stability_penalty.png");
}

TEST_CASE("A folder without shpb outputs is refused with exit 2 and nothing written",
          "[app][report]") {
  if (!shpb_test::have_matplotlib()) {
    SHPB_SKIP("python3 with matplotlib and numpy not installed: report test skipped");
  }
  const fs::path dir = scratch_dir("report_empty");
  std::ofstream(dir / "notes.txt") << "not an output folder\n";
  const auto r = run_shpb({"report", dir.string()});
  CHECK(r.code == 2);
  CHECK(r.err.rfind("error: " + dir.string() + ": ", 0) == 0);
  CHECK_FALSE(fs::exists(dir / "report.html"));
  CHECK_FALSE(fs::exists(dir / "figures"));
}

// docs/commands.md, Exit codes: one line naming the file and what was expected. A missing folder
// was CLI11's "folder: Directory does not exist: …".
TEST_CASE("A report of a folder that is not there names it", "[app][report]") {
  const fs::path dir = scratch_dir("report_missing");
  for (const fs::path& given : {dir / "nothing-here", dir / "a-file.csv"}) {
    if (given.extension() == ".csv") std::ofstream(given) << "x\n";
    const auto r = run_shpb({"report", given.string()});
    INFO(r.err);
    CHECK(r.code == 2);
    CHECK(r.err.rfind("error: " + given.string() + ": ", 0) == 0);
    CHECK(r.err.find("an output folder of simulate") != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
}

TEST_CASE("Headless Chromium renders report.html to a picture that is not blank",
          "[app][report][browser]") {
  if (!shpb_test::have_matplotlib()) {
    SHPB_SKIP("python3 with matplotlib and numpy not installed: browser test skipped");
  }
  if (std::system("command -v chromium >/dev/null 2>&1") != 0) {
    SHPB_SKIP("chromium not installed (make test installs it): browser test skipped");
  }
  const fs::path root = scratch_dir("report_browser");
  const fs::path dir = write_study_folder(root / "study");
  REQUIRE(run_shpb({"report", dir.string()}).code == 0);
  const fs::path shot = root / "screenshot.png";
  const std::string cmd =
      "timeout 60 chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
      "--disable-background-networking --disable-component-update --disable-sync "
      "--user-data-dir=" +
      (root / "profile").string() + " --screenshot=" + shot.string() +
      " --window-size=1200,1600 file://" + (dir / "report.html").string() + " >/dev/null 2>&1";
  REQUIRE(std::system(cmd.c_str()) == 0);
  REQUIRE(fs::exists(shot));
  // Blank means one colour: count the distinct colours of the screenshot. Headings, text and
  // the embedded figures give hundreds; an empty or failed page gives one.
  const fs::path count = root / "colours.txt";
  const std::string py =
      "/usr/bin/python3 -c \"import sys, numpy as n, matplotlib.image as m; "
      "a = m.imread(sys.argv[1]); "
      "print(len(n.unique(a.reshape(-1, a.shape[-1]), axis=0)))\" " +
      shot.string() + " > " + count.string();
  REQUIRE(std::system(py.c_str()) == 0);
  const int colours = std::stoi(read_text(count));
  CHECK(colours > 10);
}

}  // namespace tests_app_test_report
