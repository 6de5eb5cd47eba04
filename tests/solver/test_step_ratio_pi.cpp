// The non-integer step-ratio benchmark of docs/methods.md §3: bar L (c = 50 m/s, 300 elements)
// joined to bar S (c = 157.08 m/s, same h), so Δt_L/Δt_S = π; a square pulse crosses the joint.
// Transmitted and reflected amplitudes 2Z2/(Z1+Z2) and (Z2−Z1)/(Z1+Z2); energy conserved.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "pulse_metrics.hpp"
#include "solver/simulation.hpp"
#include "test_scenes.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_solver_test_step_ratio_pi {

using namespace shpb;

namespace {
constexpr double kAmplitudeTolerance = 0.01;  // front smearing at the unmatched step ratio
constexpr double kEnergyTolerance =
    0.005;  // closing losses are booked; what is left is interpolation at unmatched instants
}  // namespace

TEST_CASE("A pulse crosses a joint with step ratio pi with exact transmission and reflection",
          "[solver][asynchronous]") {
  const double pi = std::numbers::pi, A = 1e-4, V = 0.02, cL = 50.0;
  const MaterialSpec L = test::elastic(0.02e9, 8000, "L");
  const double rhoS = 8000;  // the benchmark's equal-density case
  const MaterialSpec S = test::elastic(std::pow(pi / 0.02, 2) * rhoS, rhoS, "S");
  // A 12.5 mm striker of bar L's material at 0.02 m/s: a 0.5 ms square pulse of 0.01 m/s.
  BarSpec striker = test::bar("striker", L, 0.0125, A, 75, V);
  BarSpec bl = test::bar("L", L, 0.05, A, 300);
  bl.gauges.push_back({"gL", 0.0125});
  BarSpec bs = test::bar("S", S, 0.3, A, 1800);
  bs.gauges.push_back({"gS", 0.01});
  for (Stepping stepping : {Stepping::kAsynchronous, Stepping::kGlobal}) {
    DYNAMIC_SECTION(to_string(stepping)) {
      const Scene scene =
          test::chain({striker, bl, bs}, 2.2e-3, ContactMethod::kLocalizedBipenalty, stepping, 1e6);
      const SimulationResult r = simulate(scene);
      REQUIRE(r.stable);
      const double ZL = 8000 * cL * A, ZS = rhoS * S.wave_speed_m_s() * A;
      const double T = 2 * ZS / (ZL + ZS), R = (ZS - ZL) / (ZL + ZS);
      const double incident = -V / (2 * cL);
      const double transmitted = T * L.youngs_modulus_Pa * incident / S.youngs_modulus_Pa;
      const auto& t = r.gauges.time_s;
      const auto pI = test::square_pulse(t, r.gauges.column("gL"), incident);
      const auto pR = test::square_pulse(t, r.gauges.column("gL"), R * incident, 1.5e-3);
      const auto pT = test::square_pulse(t, r.gauges.column("gS"), transmitted);
      REQUIRE((pI.found && pR.found && pT.found));
      CHECK(std::abs(pI.mean / incident - 1) < kAmplitudeTolerance);
      CHECK(std::abs(pT.mean / transmitted - 1) < kAmplitudeTolerance);
      CHECK(std::abs(pR.mean / (R * incident) - 1) < kAmplitudeTolerance);
      CHECK(r.energy_error < kEnergyTolerance);
    }
  }
}

}  // namespace tests_solver_test_step_ratio_pi
