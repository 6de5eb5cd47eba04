// The energy record (bar_energy) sums its nodes' and elements' terms in four lanes
// (bar_integrator.cpp, vectorised): it must equal the plain node-by-node sum of the discrete
// kinetic energy ½ m v_{n−1/2} v_{n+1/2} (docs/methods.md §1), with a constant step and where the
// step changes, and the element-by-element sum of ½ EA/h Δw², to round-off.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>

#include "solver/bar_integrator.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_solver_test_energy_record {

using namespace shpb;

namespace {
// A sum of N terms in another order differs by at most ~N ε of the sum of their magnitudes; the
// terms here are all positive (v_{n−1/2} and v_{n+1/2} of one sign), so relative to the sum.
constexpr double kReorderedSumTolerance = 1e3 * std::numeric_limits<double>::epsilon();
}  // namespace

TEST_CASE("The energy record's kinetic and strain energies equal the plain sums", "[solver]") {
  MaterialSpec steel;
  steel.density_kg_m3 = 8000;
  steel.youngs_modulus_Pa = 200e9;
  const BarModel bar = make_bar_model("bar", steel, 0.5, 2.85e-4, 501, 1e-7, 5.0);
  BarState s = make_bar_state(bar, true);
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int i = 0; i < bar.nodes; ++i) {
    s.v[i] = 3 * unit(random);                // relative velocities, all forward
    s.force[i] = 1e3 * (unit(random) - 0.5);  // small accelerations: v_{n±1/2} keep their sign
    s.w[i] = 1e-6 * (unit(random) - 0.5);
  }
  for (const double dt_prev : {1e-7, 0.8e-7}) {  // the same step; a changed step
    for (const auto& [lo, hi] : {std::pair{0, bar.nodes - 1}, std::pair{7, 300}, std::pair{5, 7}}) {
      s.dt = 1e-7;
      s.dt_prev = dt_prev;
      s.step = 10;
      s.lo = lo;
      s.hi = hi;
      double plain = 0, moving_mass = bar.total_mass_kg(), plain_strain = 0;
      for (int e = std::max(lo - 1, 0); e <= std::min(hi, bar.nodes - 2); ++e)
        plain_strain += 0.5 * bar.stiffness_N_m * (s.w[e + 1] - s.w[e]) * (s.w[e + 1] - s.w[e]);
      for (int i = lo; i <= hi; ++i) {
        const double a = s.force[i] * bar.inverse_mass[i];
        const double v_before = bar.initial_velocity_m_s + s.v[i];     // v_{n−1/2}
        const double v_after = v_before + 0.5 * (dt_prev + s.dt) * a;  // v_{n+1/2}
        plain += 0.5 * bar.mass_kg[i] * v_before * v_after;
        moving_mass -= bar.mass_kg[i];
      }
      plain += 0.5 * moving_mass * bar.initial_velocity_m_s * bar.initial_velocity_m_s;
      const BarEnergy recorded = bar_energy(bar, s);
      INFO("dt_prev " << dt_prev << ", nodes " << lo << ".." << hi << ": " << recorded.kinetic_J
                      << " against " << plain << ", strain " << recorded.strain_J << " against "
                      << plain_strain);
      CHECK(std::abs(recorded.kinetic_J / plain - 1) <= kReorderedSumTolerance);
      CHECK(std::abs(recorded.strain_J / plain_strain - 1) <= kReorderedSumTolerance);
    }
  }
}

}  // namespace tests_solver_test_energy_record
