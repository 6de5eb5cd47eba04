// Every experiment shipped in experiments/ runs as its README says, from the repository alone:
// `validate` on each scene, `process` and `compare` where it has a measured (or recorded) record,
// `process --campaign` on each campaign file and `fit` on each campaign that names a law to fit.
// Runs are kept short (fit takes one solver iteration): what is checked is that each command
// accepts the experiment as shipped and writes its outputs.
#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "run_shpb.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_app_test_experiments {

namespace fs = std::filesystem;
using nlohmann::json;
using shpb_test::read_text;
using shpb_test::run_shpb;
using shpb_test::scratch_dir;

namespace {

const fs::path kExperiments = fs::path(SHPB_SOURCE_DIR) / "experiments";

void expect_success(const std::vector<std::string>& args, const fs::path& written) {
  std::string line = "shpb";
  for (const auto& a : args) line += " " + a;
  INFO(line);
  const auto r = run_shpb(args);
  INFO(r.err);
  CHECK(r.code == 0);
  CHECK(fs::exists(written));
}

}  // namespace

// Release only: a repeat per command of paths the sanitized suite runs once elsewhere (every
// experiment's validate and simulate are their own CTest entries in both builds; process, compare
// and fit run sanitized in their own tests), at 23 s under the sanitizers.
TEST_CASE("Every shipped experiment runs validate, process, compare and fit from the repository",
          "[app][experiments][release-only]") {
  const fs::path d = scratch_dir("experiments");
  std::vector<fs::path> scenes, campaigns;
  for (const auto& e : fs::directory_iterator(kExperiments)) {
    if (e.is_directory() && fs::exists(e.path() / "scene.json"))
      scenes.push_back(e.path() / "scene.json");
    if (e.is_directory() && fs::exists(e.path() / "campaign.json"))
      campaigns.push_back(e.path() / "campaign.json");
    if (e.is_regular_file() && e.path().extension() == ".json") campaigns.push_back(e.path());
  }
  REQUIRE(scenes.size() >= 7);
  REQUIRE(campaigns.size() >= 2);
  std::size_t measured = 0;
  for (const fs::path& scene : scenes) {
    const std::string name = scene.parent_path().filename().string();
    const json s = json::parse(read_text(scene));
    const auto r = run_shpb({"validate", scene.string()});
    INFO(scene.string() << "\n" << r.err);
    CHECK(r.code == 0);
    if (!s.contains("measurement") || !s["measurement"].contains("channels")) continue;
    ++measured;
    const fs::path out = d / name;
    expect_success({"process", scene.string(), "-o", (out / "process").string(), "--quiet"},
                   out / "process/curve.csv");
    expect_success({"compare", scene.string(), "-o", (out / "compare").string(), "--quiet"},
                   out / "compare/comparison.csv");
  }
  CHECK(measured >= 4);  // the three lab records and the recorded tension test
  for (const fs::path& campaign : campaigns) {
    const std::string name =
        campaign.parent_path().filename().string() + "-" + campaign.stem().string();
    const json c = json::parse(read_text(campaign));
    if (c.contains("material")) {
      expect_success({"fit", campaign.string(), "-o", (d / name / "fit").string(),
                      "--max-iterations", "1", "--bootstrap", "0", "--quiet"},
                     d / name / "fit/fit.json");
    } else {
      expect_success({"process", "--campaign", campaign.string(), "-o",
                      (d / name / "campaign").string(), "--quiet"},
                     d / name / "campaign/campaign.csv");
    }
  }
}

}  // namespace tests_app_test_experiments
