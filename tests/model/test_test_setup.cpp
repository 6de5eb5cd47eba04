// The roles of a chain's bars and the distances pulses travel to the specimen, resolved once for
// every command (model/test_setup.hpp), checked on chains worked out by hand.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>

#include "../scratch.hpp"
#include "chain_bar.hpp"
#include "core/error.hpp"
#include "model/test_setup.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_model_test_test_setup {

using namespace shpb;
using shpb_test::bar;

namespace {

// Sums of a few bar lengths: equal to round-off.
constexpr double kRoundOff = 1e-12;

// Striker 0.3 m, a 3 mm shaper, incident 2 m (gap 0.1 mm to the specimen), specimen 5 mm,
// transmitter 1 m, a second output bar 0.5 m.
Scene shaped_chain(double striker_velocity) {
  Scene s;
  s.bars = {bar("striker", 0.3, striker_velocity),
            bar("shaper", 0.003),
            bar("incident", 2.0),
            bar("specimen", 0.005),
            bar("transmitter", 1.0),
            bar("output", 0.5)};
  s.bars[2].gap_m = 1e-4;
  s.specimen = 3;
  return s;
}

}  // namespace

TEST_CASE("Roles: the moving bar is the striker, the bars up to the incident bar shapers",
          "[model][setup]") {
  const TestRoles r = test_roles(shaped_chain(10));
  CHECK(r.striker == std::optional<std::size_t>(0));
  CHECK(r.shapers == std::vector<std::size_t>{1});
  CHECK(r.incident == std::optional<std::size_t>(2));
  CHECK(r.specimen == std::optional<std::size_t>(3));
  CHECK(r.transmitter == std::optional<std::size_t>(4));
  // A measured test whose bars are at rest: the first bar is the striker compare and fit launch.
  CHECK(test_roles(shaped_chain(0)).striker == std::optional<std::size_t>(0));
  CHECK(!striker_bar(shaped_chain(0)));
}

TEST_CASE("A striker loads the chain moving into it, or pulling it through a bonded interface",
          "[model][setup]") {
  CHECK(striker_bar(shaped_chain(10)) == std::optional<std::size_t>(0));
  Scene away = shaped_chain(-15);
  CHECK(!striker_bar(away));
  CHECK(!any_interface_loaded(away));
  CHECK(striker_direction(away) == -1);
  away.contact.method = ContactMethod::kBonded;  // the bonded tension test
  CHECK(striker_bar(away) == std::optional<std::size_t>(0));
  CHECK(any_interface_loaded(away));
}

TEST_CASE("A gauge's distance to the specimen is its pulse's travel in the bars, gaps excluded",
          "[model][setup]") {
  const Scene s = shaped_chain(10);
  // On the incident bar 0.5 m from its left end: 1.5 m to its right end, the gap not counted.
  CHECK(*distance_to_specimen_m(s, 2, 0.5) == Approx(1.5).epsilon(kRoundOff));
  // On the shaper's left end: the shaper and the whole incident bar.
  CHECK(*distance_to_specimen_m(s, 1, 0.0) == Approx(2.003).epsilon(kRoundOff));
  // On the output bar 0.2 m from its left end: the transmitter and 0.2 m.
  CHECK(*distance_to_specimen_m(s, 5, 0.2) == Approx(1.2).epsilon(kRoundOff));
  CHECK(!distance_to_specimen_m(s, 3, 0.001));
}

TEST_CASE("A scene's distance_to_specimen is the same travel: read back, it is what was given",
          "[model][setup]") {
  // A gauge on the output bar, 1.2 m from the specimen: 0.2 m past the 1 m transmitter.
  const auto dir = shpb_test::scratch_dir("test_setup_distance");
  auto scene_with = [&](const std::string& distance) {
    std::ofstream(dir / "scene.json") << R"({"bars": [
      {"name": "striker", "material": "steel", "length": "0.3 m", "diameter": "20 mm",
       "velocity": "10 m/s"},
      {"name": "incident", "material": "steel", "length": "2 m", "diameter": "20 mm"},
      {"name": "specimen", "material": "steel", "length": "5 mm", "diameter": "10 mm"},
      {"name": "transmitter", "material": "steel", "length": "1 m", "diameter": "20 mm"},
      {"name": "output", "material": "steel", "length": "0.5 m", "diameter": "20 mm",
       "gauges": [{"name": "far", "distance_to_specimen": ")" +
                                             distance + R"("}]}],
      "specimen": "specimen",
      "materials": {"steel": {"model": "elastic", "density": 8000, "youngs_modulus": "200 GPa",
                              "poisson_ratio": 0.29}}})";
    return dir / "scene.json";
  };
  const Scene s = read_scene(scene_with("1.2 m"));
  const GaugeSpec& g = s.bars[4].gauges[0];
  CHECK(g.position_m == Approx(0.2).epsilon(kRoundOff));
  CHECK(*distance_to_specimen_m(s, 4, g.position_m) == Approx(1.2).epsilon(kRoundOff));
  // Closer than the transmitter's far end is not on the output bar.
  std::string error;
  try {
    read_scene(scene_with("0.5 m"));
  } catch (const InputError& e) {
    error = e.what();
  }
  CHECK(error.find("bars[4].gauges[0].distance_to_specimen") != std::string::npos);
}

}  // namespace tests_model_test_test_setup
