// Stability maps (docs/methods.md §2): the measured boundary of plain penalty against the
// exact critical Courant number of the discrete system, bipenalty holding below
// R_crit, and the 2/√R limit above it. Tiny probes (two bars of 20 elements), so each point takes
// ~1 ms.
#include <catch2/catch.hpp>
#include <cmath>

#include "../solver/test_scenes.hpp"
#include "study/stability_probe.hpp"
#include "study/sweep.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_study_test_stability {

using namespace shpb;

namespace {
// Boundaries within 5 % of the closed forms (derived for a continuum bar end; the grid is
// discrete).
constexpr double kBoundaryTolerance = 0.05;

Scene steel_probe() {
  const double area = 2.85e-4;
  Scene s = test::chain({test::bar("striker", test::steel(), 0.1, area, 20, 10.0),
                         test::bar("bar", test::steel(), 0.5, area, 100)},
                        1e-4, ContactMethod::kPenalty, Stepping::kAsynchronous);
  return stability_probe_scene(s);
}
}  // namespace

TEST_CASE(
    "Plain penalty becomes unstable at the exact critical Courant number of the discrete system",
    "[study][stability]") {
  const Scene probe = steel_probe();
  for (double s : {1.0, 10.0, 100.0, 1e3, 1e4}) {
    StabilityPoint tied{ContactMethod::kPenalty, s, 0, 1, true};
    const double measured = measured_critical_courant(probe, tied);
    const double exact = penalty_critical_courant(s);
    INFO("eps_s/k = " << s << ": measured " << measured << ", exact " << exact);
    CHECK(std::abs(measured / exact - 1) < kBoundaryTolerance);
  }
}

TEST_CASE("Bipenalty with R at most R_crit is stable at every stiffness up to C = 0.98",
          "[study][stability]") {
  const Scene probe = steel_probe();
  // Localized bipenalty as used (unilateral); node-to-node bipenalty tied (its textbook
  // switching injects ½ ε_m ġ² at activation, which is not a step limit).
  const StabilityPoint methods[] = {{ContactMethod::kLocalizedBipenalty, 1, 1, 1, false},
                                    {ContactMethod::kBipenalty, 1, 1, 1, true}};
  for (const StabilityPoint& method : methods)
    for (double ratio : {0.25, 0.5, 1.0})
      for (double s : {1e-2, 1.0, 1e2, 1e4, 1e6})
        for (double c : {0.3, 0.9, 0.98}) {
          const StabilityVerdict v =
              judge_stability(probe, {method.method, s, ratio, c, method.tied});
          INFO(to_string(method.method)
               << (method.tied ? " (tied)" : "") << ", R/R_crit = " << ratio << ", eps_s/k = " << s
               << ", C = " << c << ": energy growth " << v.energy_growth);
          CHECK(v.stable);
        }
}

TEST_CASE("Above R_crit the tied bipenalty step follows 2/sqrt(R)", "[study][stability]") {
  const Scene probe = steel_probe();
  for (double ratio : {1.5, 2.0, 3.0, 4.0}) {
    StabilityPoint tied{ContactMethod::kBipenalty, 1e4, ratio, 1, true};
    const double measured = measured_critical_courant(probe, tied, 0.1, 1.1);
    const double expected = bipenalty_critical_courant(ratio);
    INFO("R/R_crit = " << ratio << ": measured " << measured << ", 2/sqrt(R) gives " << expected);
    CHECK(std::abs(measured / expected - 1) < kBoundaryTolerance);
  }
}

TEST_CASE(
    "Finite localized links with R at most R_crit are stable at asynchronous steps of "
    "ratio 1, pi and pi^2 at every stiffness up to C = 0.98",
    "[study][stability][finite]") {
  const Scene probe = steel_probe();
  for (double q : {1.0, M_PI, M_PI * M_PI})
    for (double ratio : {0.25, 0.5, 0.9, 1.0})
      for (double s : kStiffnessFactors)
        for (double c : {0.3, 0.9, 0.98}) {
          StabilityPoint point{ContactMethod::kLocalizedBipenalty, s, ratio, c};
          point.step_ratio = q;
          const StabilityVerdict v = judge_stability(probe, point);
          INFO("step ratio " << q << ", R/R_crit = " << ratio << ", eps_s/k = " << s
                             << ", C = " << c << ": energy growth " << v.energy_growth);
          CHECK(v.stable);
        }
}

TEST_CASE(
    "The rigid-link limit is stable up to C = 1 at step ratios 1, 2, pi, 9.95 and 10, and the "
    "map counts its closings after the release",
    "[study][stability][rigid]") {
  const Scene probe = steel_probe();
  const std::vector<StabilityPoint> grid = stability_grid({ContactMethod::kLocalizedBipenalty});
  std::size_t rigid_rows = 0;
  for (const StabilityPoint& p : grid) {
    if (p.stiffness_factor != 0 || !(p.courant >= 0.98 && p.courant <= 1)) continue;
    ++rigid_rows;
    const StabilityVerdict v = judge_stability(probe, p);
    INFO("step ratio " << p.step_ratio << ", C = " << p.courant << ": energy growth "
                       << v.energy_growth << ", closings after release " << v.closings_after_release
                       << ", force after the unloading " << v.force_after_unloading_share);
    CHECK(v.stable);
    // Equal bars of one length: the striker stops at 2L/c and the bar leaves at its velocity, so
    // the probe's contact is unloaded then and neither meets nor presses again (the map's
    // meetings_after_unloading and force_after_unloading_share).
    CHECK(v.meetings_after_unloading == 0);
    CHECK(v.force_after_unloading_share == 0);
  }
  // 0.98, 0.995, 0.9995, 0.9999 and 1 at each of the five step ratios.
  CHECK(rigid_rows == 25);
}

}  // namespace tests_study_test_stability
