#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "../app/run_shpb.hpp"
#include "model/material_law.hpp"
#include "model/scene.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_model_test_material_params {

using namespace shpb;
namespace fs = std::filesystem;

namespace {
// A valid scene whose specimen is the named material "spec" (Johnson-Cook Al 6061-T6).
nlohmann::json scene_with(const nlohmann::json& specimen_material) {
  const nlohmann::json steel = {{"model", "elastic"},
                                {"density", 8080},
                                {"youngs_modulus", "200 GPa"},
                                {"poisson_ratio", 0.29}};
  return {{"name", "material parameter check"},
          {"bars",
           {{{"name", "striker"},
             {"material", "steel"},
             {"length", "300 mm"},
             {"diameter", "19.05 mm"},
             {"velocity", "10 m/s"}},
            {{"name", "incident"},
             {"material", "steel"},
             {"length", "1 m"},
             {"diameter", "19.05 mm"},
             {"gauges", {{{"name", "incident"}, {"position", "0.5 m"}}}}},
            {{"name", "specimen"}, {"material", "spec"}, {"length", "5 mm"}, {"diameter", "10 mm"}},
            {{"name", "transmitter"},
             {"material", "steel"},
             {"length", "1 m"},
             {"diameter", "19.05 mm"},
             {"gauges", {{{"name", "transmitted"}, {"position", "0.5 m"}}}}}}},
          {"specimen", "specimen"},
          {"materials", {{"steel", steel}, {"spec", specimen_material}}}};
}

nlohmann::json al6061() {
  return {{"model", "johnson-cook"},
          {"density", 2703},
          {"youngs_modulus", "69 GPa"},
          {"poisson_ratio", 0.33},
          {"A", "324 MPa"},
          {"B", "114 MPa"},
          {"n", 0.42},
          {"C", 0.002},
          {"m", 1.34},
          {"melting_temperature", "925 K"},
          {"specific_heat", 885}};
}

struct Run {
  int exit_code;
  std::string stderr_text;
};

// The folder of this test process, removed when the process ends.
const shpb_test::ScratchDir scratch("material_params");

// Runs `shpb validate` on the scene written to the scratch folder; returns exit code and stderr.
Run validate(const nlohmann::json& scene) {
  const fs::path file = scratch.path() / "scene.json";
  std::ofstream(file) << scene.dump(2);
  const auto r = shpb_test::run_shpb({"validate", file.string()});
  return {r.code, r.err};
}
}  // namespace

TEST_CASE("A valid Johnson-Cook specimen passes validation", "[model][material][params]") {
  const Run run = validate(scene_with(al6061()));
  INFO(run.stderr_text);
  REQUIRE(run.exit_code == 0);
}

TEST_CASE("Bad material parameters exit with code 2 and name the JSON path",
          "[model][material][params]") {
  struct Case {
    const char* what;
    const char* key;  // the parameter changed (erased if value is null)
    nlohmann::json value;
    nlohmann::json base;
  };
  nlohmann::json bilinear = {{"model", "bilinear"},         {"density", 8960},
                             {"youngs_modulus", "124 GPa"}, {"poisson_ratio", 0.34},
                             {"yield_stress", "100 MPa"},   {"tangent_modulus", "1 GPa"}};
  nlohmann::json maxwell = {{"model", "viscoelastic"},
                            {"density", 1190},
                            {"poisson_ratio", 0.35},
                            {"long_term_modulus", "3 GPa"},
                            {"arms", {{{"modulus", "1 GPa"}, {"relaxation_time", "10 us"}}}}};
  nlohmann::json nine_arms = nlohmann::json::array();
  for (int k = 0; k < 9; ++k)
    nine_arms.push_back({{"modulus", "1 GPa"}, {"relaxation_time", "1 us"}});
  const Case cases[] = {
      {"negative A", "A", "-10 MPa", al6061()},
      {"negative B", "B", -1e6, al6061()},
      {"n above 1", "n", 1.5, al6061()},
      {"n below 0", "n", -0.1, al6061()},
      {"m zero", "m", 0, al6061()},
      {"m negative", "m", -1.34, al6061()},
      {"missing B", "B", nullptr, al6061()},
      {"missing m", "m", nullptr, al6061()},
      {"missing melting temperature", "melting_temperature", nullptr, al6061()},
      {"melting below room temperature", "melting_temperature", "250 K", al6061()},
      {"Taylor-Quinney above 1", "taylor_quinney", 1.2, al6061()},
      {"negative specific heat", "specific_heat", -885, al6061()},
      {"negative strain-rate filter", "strain_rate_filter", "-0.2 us", al6061()},
      {"Poisson ratio 0.5", "poisson_ratio", 0.5, al6061()},
      {"zero density", "density", 0, al6061()},
      {"missing yield stress", "yield_stress", nullptr, bilinear},
      {"tangent modulus above E", "tangent_modulus", "200 GPa", bilinear},
      {"negative yield stress", "yield_stress", "-1 MPa", bilinear},
      {"negative relaxation time",
       "arms",
       {{{"modulus", "1 GPa"}, {"relaxation_time", "-1 us"}}},
       maxwell},
      {"nine Maxwell arms", "arms", nine_arms, maxwell},
      {"missing long-term modulus", "long_term_modulus", nullptr, maxwell},
  };
  for (const Case& c : cases) {
    SECTION(c.what) {
      nlohmann::json material = c.base;
      if (c.value.is_null())
        material.erase(c.key);
      else
        material[c.key] = c.value;
      const Run run = validate(scene_with(material));
      INFO(run.stderr_text);
      REQUIRE(run.exit_code == 2);
      REQUIRE(run.stderr_text.rfind("error: ", 0) == 0);
      REQUIRE(run.stderr_text.find(std::string("materials.spec.") + c.key) != std::string::npos);
    }
  }
}

TEST_CASE("Every specimen file validates, cites its source and builds its law",
          "[model][material][params]") {
  const fs::path folder = fs::path(SHPB_SOURCE_DIR) / "specimens";
  int files = 0;
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (entry.path().extension() != ".json") continue;
    ++files;
    SECTION(entry.path().filename().string()) {
      nlohmann::json scene = scene_with(al6061());
      scene["bars"][2]["material"] = entry.path().string();
      const Run run = validate(scene);
      INFO(run.stderr_text);
      REQUIRE(run.exit_code == 0);
      std::ifstream in(entry.path());
      const nlohmann::json j = nlohmann::json::parse(in);
      REQUIRE(j.at("source").get<std::string>().size() > 40);  // paper and table, not a stub
      const Scene parsed = read_scene(scratch.path() / "scene.json");
      const MaterialSpec& spec = parsed.bars[2].material;
      const auto law = make_material_law(spec);
      REQUIRE(law->max_tangent_modulus_Pa() == Approx(spec.youngs_modulus_Pa));
    }
  }
  REQUIRE(files >= 5);
}

}  // namespace tests_model_test_material_params
