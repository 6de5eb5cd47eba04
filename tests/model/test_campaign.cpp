// Campaign files (src/model/campaign.hpp): the list of tests shared by `process` and `fit`, read
// with the same one-line errors as scenes.

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>

#include "../scratch.hpp"
#include "core/error.hpp"
#include "model/campaign.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_model_test_campaign {

using namespace shpb;
namespace fs = std::filesystem;

namespace {
struct Scratch {
  Scratch() : folder("campaign"), dir(folder.path()) {
    fs::create_directories(dir / "a");
    fs::create_directories(dir / "b");
    std::ofstream(dir / "a" / "scene.json") << "{}";
    std::ofstream(dir / "b" / "fast.json") << "{}";
  }
  fs::path write(const std::string& text) const {
    const fs::path f = dir / "campaign.json";
    std::ofstream(f) << text;
    return f;
  }
  shpb_test::ScratchDir folder;
  fs::path dir;
};

std::string error_of(const fs::path& file) {
  try {
    read_campaign(file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("A campaign lists its tests relative to the campaign file", "[campaign]") {
  Scratch s;
  const auto c = read_campaign(s.write(R"({"name": "cu", "tests": [
      {"scene": "a/scene.json"}, {"scene": "b/fast.json", "name": "4000 per s", "weight": "2"}],
      "material": {"model": "elastic", "density": 2700, "youngs_modulus": "70 GPa",
                   "poisson_ratio": 0.33},
      "free": {"youngs_modulus": ["60 GPa", "80 GPa"]}})"));
  REQUIRE(c.name == "cu");
  REQUIRE(c.tests.size() == 2);
  CHECK(c.tests[0].name == "a");  // a scene.json is named by its folder, as scenes are
  CHECK(c.tests[0].weight == 1.0);
  CHECK(fs::equivalent(c.tests[0].scene, s.dir / "a" / "scene.json"));
  CHECK(c.tests[1].name == "4000 per s");
  CHECK(c.tests[1].weight == 2.0);
  // The fit's keys, read with the file for every command.
  REQUIRE(c.fit);
  REQUIRE(c.fit->free.size() == 1);
  CHECK(c.fit->free[0].lower == 60e9);
}

TEST_CASE("A campaign's fit keys are read with the file, for every command", "[campaign]") {
  // A file is judged the same by `process --campaign` and `fit`: a campaign without fit keys has
  // none; one with any has them all read, as fit reads them (before, read by fit alone).
  Scratch s;
  CHECK_FALSE(read_campaign(s.write(R"({"tests": [{"scene": "a/scene.json"}]})")).fit);
  const auto file = s.write(R"({"tests": [{"scene": "a/scene.json"}], "loss": "huber"})");
  CHECK(error_of(file) == file.string() +
                              ": material: (missing): required: the starting material file (the "
                              "law to fit)");
}

TEST_CASE("Bad campaigns name the file, the JSON path and what was expected", "[campaign]") {
  Scratch s;
  CHECK_THAT(error_of(s.write(R"({"tests": [{"scene": "a/scene.json"}], "tets": 1})")),
             Catch::Contains("tets") && Catch::Contains("did you mean"));
  CHECK_THAT(error_of(s.write(R"({"tests": []})")),
             Catch::Contains("tests") && Catch::Contains("at least one"));
  CHECK_THAT(error_of(s.write(R"({"tests": [{"scene": "missing.json"}]})")),
             Catch::Contains("tests[0].scene") && Catch::Contains("no such file"));
  CHECK_THAT(error_of(s.write(R"({"tests": [{"scene": "a"}]})")),
             Catch::Contains("tests[0].scene") && Catch::Contains("not a regular file"));
  CHECK_THAT(error_of(s.write(R"({"tests": [{"scene": "a/scene.json", "name": "x"},
                                            {"scene": "b/fast.json", "name": "x"}]})")),
             Catch::Contains("tests[1].name") && Catch::Contains("unique"));
  CHECK_THAT(error_of(s.write(R"({"tests": [{"scene": "a/scene.json", "weight": 0}]})")),
             Catch::Contains("tests[0].weight") && Catch::Contains("> 0"));
  // A key of the file's other object is named there (before: the keys of this one were listed).
  const auto file = s.write(R"({"tests": [{"scene": "a/scene.json"}], "weight": 2})");
  CHECK(error_of(file) ==
        file.string() + ": weight: unknown key: not here; \"weight\" is a key of tests[]");
  const auto misplaced = s.write(R"({"tests": [{"scene": "a/scene.json", "stages": []}]})");
  CHECK(error_of(misplaced) ==
        misplaced.string() +
            ": tests[0].stages: unknown key: not here; \"stages\" is a key of the top level");
  // The fit's objects are the file's too (before: the keys of the object were listed).
  const auto nuisance =
      s.write(R"({"tests": [{"scene": "a/scene.json", "rise_time": ["1 us", "2 us"]}]})");
  CHECK(error_of(nuisance) ==
        nuisance.string() +
            ": tests[0].rise_time: unknown key: not here; \"rise_time\" is a key of nuisance");
  const auto misspelt =
      s.write(R"({"tests": [{"scene": "a/scene.json"}], "striker_velocty": "5 %"})");
  CHECK(
      error_of(misspelt) ==
      misspelt.string() +
          ": striker_velocty: unknown key: did you mean \"striker_velocity\", a key of nuisance?");
  const auto freed = s.write(R"({"tests": [{"scene": "a/scene.json"}],
      "material": {"model": "elastic", "density": 2700, "youngs_modulus": "70 GPa",
                   "poisson_ratio": 0.33},
      "free": {"striker_velocity": ["5 m/s", "6 m/s"]}})");
  CHECK(error_of(freed) == freed.string() +
                               ": free.striker_velocity: \"striker_velocity\": not a parameter of "
                               "the elastic law; not here; \"striker_velocity\" is a key of "
                               "nuisance");
  // A material file the campaign names says where its keys belong, as a scene's materials do.
  std::ofstream(s.dir / "law.json") << R"({"model": "elastic", "density": 2700,
      "youngs_modulus": "70 GPa", "poisson_ratio": 0.33, "A": "90 MPa"})";
  const auto law = s.write(R"({"tests": [{"scene": "a/scene.json"}], "material": "law.json",
      "free": {"youngs_modulus": ["60 GPa", "80 GPa"]}})");
  CHECK(error_of(law) == (s.dir / "law.json").string() +
                             ": A: unknown key: not here; \"A\" is a key of a johnson-cook "
                             "material");
}

// A test name names the test's output folder (docs/scene-format.md, campaign files), so it must
// be one a file system can create: NAME_MAX, 255 bytes (before: a 256-byte name was accepted,
// every test processed, then the folder refused with a message blaming an input). A scene path
// with a line break is named within the message's one line.
TEST_CASE("A campaign's test name fits a folder name; a bad scene path stays on one line",
          "[campaign]") {
  Scratch s;
  const auto named = [&](const std::string& name) {
    return error_of(
        s.write(R"({"tests": [{"scene": "a/scene.json", "name": ")" + name + R"("}]})"));
  };
  CHECK(named(std::string(255, 'n')).empty());
  CHECK_THAT(named(std::string(256, 'n')),
             Catch::Contains("tests[0].name") && Catch::Contains("at most 255 bytes"));
  const std::string line_break = error_of(s.write(R"({"tests": [{"scene": "a/scene.json\nx"}]})"));
  CHECK_THAT(line_break, Catch::Contains("tests[0].scene") && Catch::Contains("no such file"));
  CHECK(line_break.find('\n') == std::string::npos);
}

}  // namespace tests_model_test_campaign
