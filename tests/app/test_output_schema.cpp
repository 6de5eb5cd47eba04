// The files shpb writes hold exactly the columns the output schema lists
// (src/core/output_schema.json, docs/outputs.md): the one list the C++ writers, the report package
// and the documentation's tables take their names from. Through the executable, on the experiments.
#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "output_schema_check.hpp"
#include "run_shpb.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_app_test_output_schema {

namespace {

namespace fs = std::filesystem;
using shpb_test::check_schema_columns;
using shpb_test::run_shpb;
using shpb_test::schema_file;
using shpb_test::ScratchDir;

const fs::path kExperiments = fs::path(SHPB_SOURCE_DIR) / "experiments";

}  // namespace

TEST_CASE("simulate and process write the columns of the output schema", "[app][schema]") {
  const ScratchDir dir("output_schema");
  const fs::path sim = dir.path() / "sim", proc = dir.path() / "proc";
  const auto s = run_shpb({"simulate", (kExperiments / "classic-al6061/scene.json").string(), "-o",
                           sim.string(), "--quiet"});
  REQUIRE(s.code == 0);
  for (const char* id : {"gauges", "interfaces", "specimen", "energy", "field"})
    check_schema_columns(sim / schema_file(id).at("file").get<std::string>(), id);
  const auto p =
      run_shpb({"process", (kExperiments / "classic-al6061/scene.json").string(), "--signals",
                (sim / "gauges.csv").string(), "-o", proc.string(), "--quiet"});
  REQUIRE(p.code == 0);
  for (const char* id : {"raw_signals", "pulses", "curve"})
    check_schema_columns(proc / schema_file(id).at("file").get<std::string>(), id);
}

TEST_CASE("compare writes the columns of the output schema", "[app][schema]") {
  const ScratchDir dir("output_schema_compare");
  const auto c = run_shpb({"compare", (kExperiments / "lanl-cu-ofe-273k/scene.json").string(), "-o",
                           dir.path().string(), "--quiet"});
  REQUIRE(c.code == 0);
  check_schema_columns(dir.path() / "comparison.csv", "comparison");
  check_schema_columns(dir.path() / "signals.csv", "compare_signals");
}

// Release only: the map's probe runs take a second here, ten under the sanitizers.
TEST_CASE("a stability sweep writes the columns of the output schema",
          "[app][schema][study][release-only]") {
  // Plain penalty only: the smallest of the maps (its writer is every method's).
  const ScratchDir dir("output_schema_stability");
  const auto r = run_shpb({"study", (kExperiments / "classic-al6061/scene.json").string(), "-o",
                           dir.path().string(), "--sweep", "stability", "--contact", "penalty",
                           "--threads", "2", "--quiet"});
  REQUIRE(r.code == 0);
  check_schema_columns(dir.path() / "stability.csv", "stability");
  check_schema_columns(dir.path() / "stability_boundary.csv", "stability_boundary");
}

}  // namespace tests_app_test_output_schema
