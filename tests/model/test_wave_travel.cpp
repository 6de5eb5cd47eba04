// The default duration and validate's warnings read one set of 1D travel times
// (model/wave_travel.hpp), checked against times worked out by hand for a chain of bars.
#include <catch2/catch.hpp>
#include <string>

#include "chain_bar.hpp"
#include "model/discretization.hpp"
#include "model/scene_checks.hpp"
#include "model/wave_travel.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_model_test_wave_travel {

using namespace shpb;
using shpb_test::bar;

namespace {

// Sums of a few quotients: equal to round-off.
constexpr double kRoundOff = 1e-12;
constexpr double kMarginOfDefault = 1.1;  // docs/scene-format.md: the default duration's 10 %

// Striker 0.5 m; incident bar 2 m with its gauge 0.2 m from the impact end (1.8 m from the
// specimen); specimen 10 mm; transmitter 1 m with its gauge 0.1 m from the specimen. The pulse
// reflected from the specimen passes the incident gauge after the transmitted pulse has passed
// the transmitter gauge.
Scene far_incident_gauge() {
  Scene s;
  s.bars = {bar("striker", 0.5, 10), bar("incident", 2.0), bar("specimen", 0.01),
            bar("transmitter", 1.0)};
  s.bars[1].gauges = {{"I", 0.2}};
  s.bars[3].gauges = {{"T", 0.1}};
  s.specimen = 2;
  return s;
}

}  // namespace

TEST_CASE("Pulses pass the gauges at the 1D travel times, the reflected one included",
          "[model][wave-travel]") {
  const Scene s = far_incident_gauge();
  const double c = 5000, pulse = 2 * 0.5 / c;
  CHECK(striker_bar(s) == std::optional<std::size_t>(0));
  CHECK(travel_time_s(s, 1, 0.2, 3, 0.1) == Approx((1.8 + 0.01 + 0.1) / c).epsilon(kRoundOff));
  // Incident gauge: arrival 0.2/c, back from the specimen face after 2 × 1.8/c, then the pulse.
  const double incident = (0.2 + 2 * 1.8) / c + pulse;
  const double transmitted = (2.0 + 0.01 + 0.1) / c + pulse;
  REQUIRE(incident > transmitted);
  CHECK(pulses_passed_s(s, 0, 1, 0.2) == Approx(incident).epsilon(kRoundOff));
  CHECK(pulses_passed_s(s, 0, 3, 0.1) == Approx(transmitted).epsilon(kRoundOff));
  CHECK(*pulses_passed_s(s) == Approx(incident).epsilon(kRoundOff));
}

TEST_CASE("The default duration covers what validate checks, so it is never warned about",
          "[model][wave-travel]") {
  const Scene s = far_incident_gauge();
  const double d = default_duration_s(s);
  CHECK(d == Approx(kMarginOfDefault * *pulses_passed_s(s)).epsilon(kRoundOff));
  for (const auto& w : scene_warnings(s, d))
    CHECK(w.find("ends before the pulses") == std::string::npos);
  // A duration short of the reflected pulse's passage is warned about.
  bool warned = false;
  for (const auto& w : scene_warnings(s, 0.9 * *pulses_passed_s(s)))
    warned = warned || w.find("ends before the pulses") != std::string::npos;
  CHECK(warned);
}

TEST_CASE("A strain plan with small kinematics is said to do nothing", "[model][scene-checks]") {
  // simulation.max_strain plans the steps of finite-strain bars only (discretization.hpp); with
  // small kinematics it was accepted without a word.
  Scene s = far_incident_gauge();
  const double d = default_duration_s(s);
  auto said = [&] {
    for (const auto& w : scene_warnings(s, d))
      if (w.find("simulation.max_strain has no effect") != std::string::npos) return true;
    return false;
  };
  s.simulation.max_strain = 0.3;
  CHECK_FALSE(said());  // finite strain: it plans the steps
  s.simulation.finite_strain = false;
  CHECK(said());
}

TEST_CASE("A pulse shaper wider than a face it is pressed by is warned about, with its sizes",
          "[model][scene-checks]") {
  // The 1D chain spreads the shaper's force over its own area, but only the contact (the smaller
  // face) carries it: a 25 mm copper disc on 19.05 mm bars shaped nothing (rise 2.4 us for 57 us
  // at 19.05 mm, docs/methods.md §8.4) without a word.
  Scene s = far_incident_gauge();
  s.bars.insert(s.bars.begin() + 1, bar("shaper", 0.003));
  s.specimen = 3;
  auto diameter = [&](std::size_t i, double d) {
    s.bars[i].diameter_m = d;
    s.bars[i].area_m2 = 0.25 * 3.141592653589793 * d * d;
  };
  for (std::size_t i : {0, 2, 4}) diameter(i, 0.01905);
  auto warning = [&]() -> std::string {
    for (const auto& w : scene_warnings(s, default_duration_s(s)))
      if (w.find("pulse shaper") != std::string::npos) return w;
    return {};
  };
  diameter(1, 0.016);  // the usual disc, narrower than the bars
  CHECK(warning().empty());
  diameter(1, 0.01905);  // as wide: the contact is the whole disc
  CHECK(warning().empty());
  diameter(1, 0.025);
  // (25 / 19.05)² = 1.72223: the shaper's stress understated that many times.
  CHECK(warning() ==
        "bars[1].diameter: 25 mm: the pulse shaper \"shaper\" is wider than the face of bar "
        "\"incident\" (19.05 mm) it is pressed by, which alone carries its load; the 1D chain "
        "spreads the load over the shaper's own area, understating its stress 1.72223 times: give "
        "the shaper the contact's size (docs/methods.md §8.4)");
  // A narrower striker is the smaller face; a scene giving areas is answered in areas.
  diameter(1, 0.01905);
  s.bars[0].area_m2 = 1e-4;
  s.bars[0].area_given = true;
  s.bars[1].area_given = true;
  CHECK(warning().find("bars[1].area: 285.023 mm2: the pulse shaper \"shaper\" is wider than "
                       "the face of bar \"striker\" (100 mm2)") == 0);
}

}  // namespace tests_model_test_wave_travel
