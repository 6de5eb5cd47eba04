// Striker on a bar of the same material and area (docs/methods.md §4): stress ρc0V/2, strain
// V/(2c0), duration 2L_s/c0, striker ends at rest; and the plateau must not ring (docs/methods.md
// §2).
#include <catch2/catch.hpp>
#include <cmath>

#include "pulse_metrics.hpp"
#include "solver/simulation.hpp"
#include "test_scenes.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_solver_test_striker_on_bar {

using namespace shpb;

namespace {
constexpr double kPlateauTolerance = 0.005;  // a gauge reading of a 1 %-flat plateau
constexpr double kDurationTolerance = 0.01;  // one element of front smearing at each end
constexpr double kRingingLimit = 0.01;       // above the tied-bar floor at C = 0.98 (0.86 %)
constexpr double kEnergyTolerance =
    0.005;  // closing losses are booked; what is left is interpolation at unmatched instants

// The set-up of docs/methods.md §2: steel striker 0.3 m at 10 m/s on a 1.5 m bar, h = 1 mm, point
// gauge at 0.75 m.
Scene striker_on_bar(ContactMethod method, Stepping stepping) {
  const double area = 2.85e-4;
  BarSpec striker = test::bar("striker", test::steel(), 0.3, area, 300, 10.0);
  BarSpec bar = test::bar("bar", test::steel(), 1.5, area, 1500);
  bar.gauges.push_back({"incident", 0.75});
  return test::chain({striker, bar}, 300e-6, method, stepping);
}
}  // namespace

TEST_CASE("A striker on an identical bar gives the exact square pulse without ringing",
          "[solver][contact]") {
  const double c0 = std::sqrt(200e9 / 8000.0), V = 10.0, Ls = 0.3;
  const double expected = -V / (2 * c0);  // compression: negative strain
  for (Stepping stepping : {Stepping::kAsynchronous, Stepping::kGlobal}) {
    DYNAMIC_SECTION("localized-bipenalty, " << to_string(stepping)) {
      const Scene scene = striker_on_bar(ContactMethod::kLocalizedBipenalty, stepping);
      const SimulationResult r = simulate(scene);
      REQUIRE(r.stable);
      const auto p = test::square_pulse(r.gauges.time_s, r.gauges.column("incident"), expected);
      REQUIRE(p.found);
      CHECK(std::abs(p.mean / expected - 1) < kPlateauTolerance);
      CHECK(std::abs(p.duration_s / (2 * Ls / c0) - 1) < kDurationTolerance);
      const double sample = 1.0 / scene.simulation.sample_rate_Hz;
      CHECK(std::abs(p.arrival_s - 0.75 / c0) <= sample);
      CHECK(p.std / std::abs(p.mean) < kRingingLimit);
      CHECK(r.energy_error < kEnergyTolerance);
      // The striker ends at rest (it hands all its momentum to the bar).
      CHECK(std::abs(r.bars[0].final_velocity_m_s) < 0.01 * V);
    }
  }
}

TEST_CASE("A striker flying to the bar over a gap gives the same pulse at the exact arrival",
          "[solver][contact]") {
  // The bars move rigidly, unstrained, until they meet; time zero is that meeting (docs/outputs.md
  // Conventions). So the gauge reads the gap-free pulse, -V/(2 c0) arriving at x/c0 after time
  // zero, whatever the gap. The gap is chosen so that the flight ends 0.9 of a bar step after an
  // instant of the run started at the scene's gaps, where the contact closed almost a step early.
  const double c0 = std::sqrt(200e9 / 8000.0), V = 10.0, Ls = 0.3;
  const double expected = -V / (2 * c0);
  const double step = 0.995 * 1e-3 / c0;  // the bars' step at C = 0.995, h = 1 mm
  const double gap = V * (1000.9 * step);
  constexpr double kArrivalTolerance = 0.02;  // of a step: the gap-free run's own front
  constexpr double kSameRecord = 1e-9;        // of the plateau: round-off of the rigid flight
  for (Stepping stepping : {Stepping::kAsynchronous, Stepping::kGlobal}) {
    DYNAMIC_SECTION(to_string(stepping)) {
      const Scene touching = striker_on_bar(ContactMethod::kLocalizedBipenalty, stepping);
      Scene flying = touching;
      flying.bars[0].gap_m = gap;
      const SimulationResult a = simulate(touching), b = simulate(flying);
      REQUIRE((a.stable && b.stable));
      const auto pa = test::square_pulse(a.gauges.time_s, a.gauges.column("incident"), expected);
      const auto pb = test::square_pulse(b.gauges.time_s, b.gauges.column("incident"), expected);
      REQUIRE((pa.found && pb.found));
      CHECK(std::abs(pb.arrival_s - 0.75 / c0) <
            kArrivalTolerance * step + std::abs(pa.arrival_s - 0.75 / c0));
      CHECK(std::abs(pb.mean / expected - 1) < kPlateauTolerance);
      CHECK(std::abs(pb.duration_s / (2 * Ls / c0) - 1) < kDurationTolerance);
      const std::vector<double>&ga = a.gauges.column("incident"), &gb = b.gauges.column("incident");
      REQUIRE(ga.size() == gb.size());
      double worst = 0;
      for (std::size_t k = 0; k < ga.size(); ++k) worst = std::max(worst, std::abs(ga[k] - gb[k]));
      CHECK(worst < kSameRecord * std::abs(expected));
    }
  }
}

TEST_CASE("Plain penalty at 1e4 EA/h and the bars' own steps is detected as unstable",
          "[solver][contact]") {
  const SimulationResult r =
      simulate(striker_on_bar(ContactMethod::kPenalty, Stepping::kAsynchronous));
  CHECK_FALSE(r.stable);
  CHECK(r.failure.find("unstable") != std::string::npos);
  // What was computed before the failure is finite.
  for (const auto& column : r.gauges.values)
    for (double x : column) REQUIRE(std::isfinite(x));
}

TEST_CASE("Node-to-node bipenalty at the same stiffness stays stable and keeps the plateau mean",
          "[solver][contact]") {
  const double c0 = std::sqrt(200e9 / 8000.0), V = 10.0;
  const double expected = -V / (2 * c0);
  const SimulationResult r =
      simulate(striker_on_bar(ContactMethod::kBipenalty, Stepping::kAsynchronous));
  INFO(r.failure << "; energy error " << r.energy_error);
  REQUIRE(r.stable);
  const auto p = test::square_pulse(r.gauges.time_s, r.gauges.column("incident"), expected);
  REQUIRE(p.found);
  // It rings (that is the point of the comparison) but carries the right momentum.
  CHECK(std::abs(p.mean / expected - 1) < kPlateauTolerance);
}

TEST_CASE("Node-to-node contacts count their closings and openings as the localized ones do",
          "[solver][contact]") {
  // The striker comes to rest and the bar moves off at V/2 (docs/methods.md §4): the interface
  // ends open, so it closed at least once and opened after every closing (summary.json
  // interfaces[].activations and releases, docs/outputs.md). Plain penalty at 0.1 EA/h, within
  // its stable range at C ≈ 1 (docs/methods.md §2).
  for (ContactMethod method : {ContactMethod::kPenalty, ContactMethod::kBipenalty}) {
    DYNAMIC_SECTION(to_string(method)) {
      Scene scene = striker_on_bar(method, Stepping::kAsynchronous);
      if (method == ContactMethod::kPenalty) scene.contact.penalty.stiffness_factor = 0.1;
      const SimulationResult r = simulate(scene);
      REQUIRE(r.stable);
      REQUIRE(r.interface_statistics.size() == 1);
      const InterfaceStatistics& s = r.interface_statistics[0];
      CHECK(s.activations >= 1);
      CHECK(s.releases == s.activations);
    }
  }
}

TEST_CASE("A coarse striker on an identical bar keeps the central difference's discrete energy",
          "[solver][contact][energy]") {
  // The central difference conserves ½ v_{n−1/2}·M v_{n+1/2} + U(u_n) exactly on a linear chain;
  // the activation loss is booked as contact dissipation. What is left is round-off over ~10³
  // steps. (½ v_n·M v_n + U, the naive measure, is off by a front element's energy: ~1/(4N) of
  // the striker's energy for N striker elements, 0.7 % here.)
  constexpr double kDiscreteEnergyTolerance = 1e-9;
  const double area = 2.85e-4;
  for (Stepping stepping : {Stepping::kAsynchronous, Stepping::kGlobal}) {
    DYNAMIC_SECTION(to_string(stepping)) {
      BarSpec striker = test::bar("striker", test::steel(), 0.026, area, 26, 10.0);
      BarSpec bar = test::bar("bar", test::steel(), 0.3, area, 300);
      const SimulationResult r = simulate(
          test::chain({striker, bar}, 150e-6, ContactMethod::kLocalizedBipenalty, stepping));
      REQUIRE(r.stable);
      CHECK(r.energy_error < kDiscreteEnergyTolerance);
    }
  }
}

}  // namespace tests_solver_test_striker_on_bar
