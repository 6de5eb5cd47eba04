// `shpb simulate` as a user sees it (docs/commands.md, docs/outputs.md): the files of a run, exit 2
// with nothing written for bad input, exit 3 with the outputs up to the failure for a detected
// instability.
#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "run_shpb.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_app_test_simulate_cli {

namespace fs = std::filesystem;
using shpb_test::read_text;
using shpb_test::run_shpb;
using shpb_test::scratch_dir;

namespace {
const fs::path kStrikerOnBar = fs::path(SHPB_SOURCE_DIR) / "experiments/striker-on-bar/scene.json";

std::string first_line(const fs::path& file) {
  const std::string text = read_text(file);
  return text.substr(0, text.find('\n'));
}
}  // namespace

TEST_CASE("Simulating a scene writes every output file with its documented header",
          "[app][simulate]") {
  const fs::path dir = scratch_dir("simulate_ok") / "out";
  const auto r = run_shpb({"simulate", kStrikerOnBar.string(), "-o", dir.string(), "--quiet"});
  REQUIRE(r.code == 0);
  CHECK(r.err.empty());
  CHECK(first_line(dir / "gauges.csv") == "time_s,gauge");
  CHECK(first_line(dir / "interfaces.csv") == "time_s,striker-bar_force_N,striker-bar_gap_m");
  CHECK(first_line(dir / "energy.csv") ==
        "time_s,kinetic_J,strain_J,contact_J,dissipated_J,total_J");
  CHECK(first_line(dir / "field.csv") == "time_s,x_m,stress_Pa");
  CHECK_FALSE(fs::exists(dir / "specimen.csv"));  // the scene has no specimen
  const auto summary = nlohmann::json::parse(read_text(dir / "summary.json"));
  CHECK(summary["stable"] == true);
  REQUIRE(summary["bars"].size() == 2);
  for (const char* key : {"name", "elements", "time_step_s", "steps", "courant", "node_updates"})
    CHECK(summary["bars"][0].contains(key));
  for (const char* key : {"wall_time_s", "energy_error", "max_penetration_m", "version",
                          "node_updates", "node_updates_full_model"})
    CHECK(summary.contains(key));
  // The whole run holds the mesh choice (the default tolerance's search) and the solve.
  const double choice = summary.at("mesh_choice_time_s").get<double>();
  CHECK(choice > 0);
  CHECK(summary.at("run_time_s").get<double>() >= choice + summary["wall_time_s"].get<double>());
}

TEST_CASE("Simulating a scene that cannot be read exits with 2 and writes nothing",
          "[app][simulate]") {
  const fs::path dir = scratch_dir("simulate_missing") / "out";
  const auto r = run_shpb({"simulate", (dir.parent_path() / "no_such_scene.json").string(), "-o",
                           dir.string(), "--quiet"});
  CHECK(r.code == 2);
  CHECK(r.err.rfind("error: ", 0) == 0);
  CHECK_FALSE(fs::exists(dir));
}

TEST_CASE("A detected instability exits with 3 and still writes what was computed",
          "[app][simulate]") {
  // Plain penalty at 1e4 EA/h with the bars' own steps is unstable (docs/methods.md §2).
  const fs::path dir = scratch_dir("simulate_unstable") / "out";
  const auto r = run_shpb(
      {"simulate", kStrikerOnBar.string(), "-o", dir.string(), "--contact", "penalty", "--quiet"});
  CHECK(r.code == 3);
  CHECK(r.err.find("unstable") != std::string::npos);
  const auto summary = nlohmann::json::parse(read_text(dir / "summary.json"));
  CHECK(summary["stable"] == false);
  CHECK(summary["failure"].get<std::string>().find("t = ") != std::string::npos);
  CHECK(fs::exists(dir / "gauges.csv"));
}

}  // namespace tests_app_test_simulate_cli
