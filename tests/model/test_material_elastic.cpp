#include <catch2/catch.hpp>
#include <cmath>

#include "material_point.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_model_test_material_elastic {

using namespace shpb;

namespace {
// Hooke's law is evaluated exactly; only round-off separates the law from σ = E ε.
constexpr double kRoundOff = 1e-12;
constexpr double kZeroStress_Pa = 1e-3;  // near ε = 0 a relative tolerance means nothing
}  // namespace

TEST_CASE("An elastic point follows Hooke's law at any rate and stores all the work put in",
          "[model][material][elastic]") {
  MaterialSpec spec;
  spec.model = MaterialModel::kElastic;
  spec.density_kg_m3 = 8080;
  spec.youngs_modulus_Pa = 200e9;
  test::MaterialPoint point(spec);
  REQUIRE(point.law().max_tangent_modulus_Pa() == spec.youngs_modulus_Pa);
  for (int i = 1; i <= 1000; ++i) {
    const double eps = -2e-3 * std::sin(M_PI * i / 500.0);  // a full cycle
    const double dt = i % 2 ? 1e-8 : 1e-3;                  // the rate does not matter
    REQUIRE(point.strain_to(eps, dt) ==
            Approx(spec.youngs_modulus_Pa * eps).epsilon(kRoundOff).margin(kZeroStress_Pa));
    REQUIRE(point.law().stored_energy_J_m3(point.state()) ==
            Approx(0.5 * spec.youngs_modulus_Pa * eps * eps).epsilon(kRoundOff).margin(kRoundOff));
  }
  REQUIRE(point.state().dissipated_J_m3 == 0);
  // Over a closed cycle the trapezoidal work of a linear spring is exactly zero.
  REQUIRE(point.work_J_m3() == Approx(0).margin(1e-6));
}

}  // namespace tests_model_test_material_elastic
