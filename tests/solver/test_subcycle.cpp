// The scheduler's tight loop for a lone fast bar (rule 2 of scheduler.hpp): the specimen's
// instants between two bar instants run without the search. It is the same schedule, so every
// output must equal the plain rule-2 loop's (run_schedule with subcycle = false) to round-off.
#include <catch2/catch.hpp>
#include <cmath>

#include "solver/simulation.hpp"
#include "test_scenes.hpp"

using namespace shpb;

namespace {
// Both loops perform the same operations in the same order: any difference beyond round-off
// would be a changed schedule.
constexpr double kSameSchedule = 1e-12;

// Largest |a − b| over a column, relative to the largest |a| (or absolute if a is all zero).
double max_relative_difference(const TimeSeries& a, const TimeSeries& b) {
  REQUIRE(a.columns == b.columns);
  REQUIRE(a.samples() == b.samples());
  double worst = 0;
  for (std::size_t c = 0; c < a.values.size(); ++c) {
    double scale = 0, diff = 0;
    for (std::size_t k = 0; k < a.samples(); ++k) {
      scale = std::max(scale, std::abs(a.values[c][k]));
      diff = std::max(diff, std::abs(a.values[c][k] - b.values[c][k]));
    }
    worst = std::max(worst, scale > 0 ? diff / scale : diff);
  }
  return worst;
}

MaterialSpec johnson_cook_aluminium() {
  // Al 6061-T6 (Johnson & Cook 1985, as in specimens/al6061-t6.json).
  MaterialSpec m = test::elastic(68.9e9, 2700, "al6061");
  m.model = MaterialModel::kJohnsonCook;
  m.johnson_cook.A_Pa = 324e6;
  m.johnson_cook.B_Pa = 114e6;
  m.johnson_cook.n = 0.42;
  m.johnson_cook.C = 0.002;
  m.johnson_cook.m = 1.34;
  m.johnson_cook.melting_temperature_K = 925;
  return m;
}
}  // namespace

TEST_CASE("A specimen sub-cycled between its bars' instants gives the plain schedule's outputs",
          "[scheduler]") {
  const double A = 2.85e-4, Lb = 0.3;
  for (const bool plastic : {false, true}) {
    DYNAMIC_SECTION((plastic ? "Johnson-Cook" : "elastic") << " specimen") {
      const MaterialSpec soft =
          plastic ? johnson_cook_aluminium() : test::elastic(70e9, 2700, "al");
      BarSpec striker = test::bar("striker", test::steel(), 0.1, A, 100, plastic ? 15.0 : 5.0);
      BarSpec incident = test::bar("incident", test::steel(), Lb, A, 300);
      incident.gauges.push_back({"incident", 0.15});
      // 5 mm in 23 elements: a step that is a non-integer fraction of the bars' step.
      BarSpec specimen = test::bar("specimen", soft, 5e-3, 7.85e-5, 23);
      BarSpec transmitter = test::bar("transmitter", test::steel(), Lb, A, 300);
      transmitter.gauges.push_back({"transmitted", 0.15});
      Scene scene = test::chain({striker, incident, specimen, transmitter}, 200e-6,
                                ContactMethod::kLocalizedBipenalty, Stepping::kAsynchronous);
      scene.specimen = 2;

      SimulationOptions plain;
      plain.subcycle = false;
      const SimulationResult a = simulate(scene, plain);
      const SimulationResult b = simulate(scene);
      REQUIRE((a.stable && b.stable));
      const double ratio = a.bars[1].time_step_s / a.bars[2].time_step_s;
      INFO("step ratio bar/specimen " << ratio);
      REQUIRE(ratio > 2);
      REQUIRE(std::abs(ratio - std::round(ratio)) > 0.1);
      REQUIRE(a.bars[2].steps == b.bars[2].steps);
      REQUIRE(a.node_updates == b.node_updates);
      CHECK(max_relative_difference(a.gauges, b.gauges) <= kSameSchedule);
      CHECK(max_relative_difference(a.specimen, b.specimen) <= kSameSchedule);
      CHECK(max_relative_difference(a.interfaces, b.interfaces) <= kSameSchedule);
      CHECK(max_relative_difference(a.energy, b.energy) <= kSameSchedule);
      // The pulse did reach the transmitter: the comparison is not one of zeros.
      const auto& tr = b.gauges.column("transmitted");
      double peak = 0;
      for (double e : tr) peak = std::max(peak, std::abs(e));
      CHECK(peak > 1e-5);
      if (plastic) {  // the Johnson-Cook section exercises the return mapping: the specimen yields
        double strain = 0;
        for (double e : b.specimen.column("strain")) strain = std::max(strain, e);
        CHECK(strain > 2 * soft.johnson_cook.A_Pa / soft.youngs_modulus_Pa);
      }
    }
  }
}
