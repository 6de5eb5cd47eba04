// The scheduler's tight loop for a lone fast bar (rule 2 of scheduler.hpp): the specimen's
// instants between two bar instants run without the search. It is the same schedule, so every
// output must equal the plain rule-2 loop's (run_schedule with subcycle = false) to round-off.
#include <catch2/catch.hpp>
#include <cmath>

#include "solver/simulation.hpp"
#include "test_scenes.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_solver_test_subcycle {

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

}  // namespace

TEST_CASE("A specimen sub-cycled between its bars' instants gives the plain schedule's outputs",
          "[scheduler]") {
  for (const bool plastic : {false, true}) {
    DYNAMIC_SECTION((plastic ? "Johnson-Cook" : "elastic") << " specimen") {
      // A specimen step that is a non-integer fraction of the bars' step: 23 elements for the
      // Johnson–Cook specimen (its step planned for e_max), 22 for the elastic one (at C 0.95,
      // model/discretization.hpp kElasticSpecimenCourant, 23 give a ratio of 4.91).
      Scene scene = test::short_kolsky(plastic, Stepping::kAsynchronous);
      if (!plastic) scene.bars[2].elements = 22;

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
        const MaterialSpec& soft = scene.bars[2].material;
        CHECK(strain > 2 * soft.johnson_cook.A_Pa / soft.youngs_modulus_Pa);
      }
    }
  }
}

}  // namespace tests_solver_test_subcycle
