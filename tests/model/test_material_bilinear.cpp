#include <catch2/catch.hpp>
#include <cmath>

#include "material_point.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_model_test_material_bilinear {

using namespace shpb;

namespace {
// The law matches its closed form within 0.1 %.
constexpr double kClosedFormTolerance = 1e-3;
// Energy bookkeeping is exact algebra (trapezoidal work = stored + dissipated), up to round-off.
constexpr double kEnergyTolerance = 1e-10;

MaterialSpec annealed_copper_like() {
  MaterialSpec spec;
  spec.model = MaterialModel::kBilinear;
  spec.density_kg_m3 = 8940;
  spec.youngs_modulus_Pa = 117e9;
  spec.bilinear = {.yield_stress_Pa = 70e6, .tangent_modulus_Pa = 0.8e9};
  return spec;
}

// Monotonic uniaxial curve of the bilinear law: E ε up to σ_y, then σ_y + E_t (ε − σ_y/E).
double bilinear_closed_form(const MaterialSpec& spec, double strain) {
  const double E = spec.youngs_modulus_Pa, sy = spec.bilinear.yield_stress_Pa;
  const double a = std::abs(strain);
  const double s = a <= sy / E ? E * a : sy + spec.bilinear.tangent_modulus_Pa * (a - sy / E);
  return std::copysign(s, strain);
}
}  // namespace

TEST_CASE("A bilinear point loaded at constant strain rate follows the bilinear curve at any rate",
          "[model][material][bilinear]") {
  const MaterialSpec spec = annealed_copper_like();
  const double final_strain = -0.25;  // compression, as in a Kolsky bar test
  constexpr int kSteps = 2500;
  for (double rate : {1e-3, 1e3, 1e4}) {
    SECTION("rate " + std::to_string(rate) + " /s") {
      test::MaterialPoint point(spec);
      const double dt = std::abs(final_strain) / rate / kSteps;
      for (int i = 1; i <= kSteps; ++i) {
        const double eps = final_strain * i / kSteps;
        const double sigma = point.strain_to(eps, dt);
        REQUIRE(sigma == Approx(bilinear_closed_form(spec, eps)).epsilon(kClosedFormTolerance));
      }
      // Plastic strain is what is left after elastic unloading: ε − σ/E.
      const double sigma = point.state().stress_Pa;
      REQUIRE(point.state().back_strain ==
              Approx(final_strain - sigma / spec.youngs_modulus_Pa).epsilon(kClosedFormTolerance));
    }
  }
}

TEST_CASE("A bilinear point unloads elastically and yields again in reverse at the hardened stress",
          "[model][material][bilinear]") {
  const MaterialSpec spec = annealed_copper_like();
  const double E = spec.youngs_modulus_Pa, Et = spec.bilinear.tangent_modulus_Pa;
  const double H = E * Et / (E - Et);  // plastic modulus of isotropic hardening
  test::MaterialPoint point(spec);
  constexpr int kSteps = 1000;
  const double dt = 1e-8;
  for (int i = 1; i <= kSteps; ++i) point.strain_to(0.1 * i / kSteps, dt);
  const double p = point.state().plastic_strain;
  const double peak = point.state().stress_Pa;
  REQUIRE(peak == Approx(spec.bilinear.yield_stress_Pa + H * p).epsilon(kClosedFormTolerance));
  // Reverse loading: elastic over a stress range of 2 × peak, then yield at −(σ_y + H p).
  const double reverse_yield_strain = 0.1 - 2 * peak / E;
  point.strain_to(reverse_yield_strain + 1e-9, dt);
  REQUIRE(point.state().plastic_strain == p);
  REQUIRE(point.state().stress_Pa == Approx(-peak).epsilon(kClosedFormTolerance));
  point.strain_to(reverse_yield_strain - 0.01, dt);
  REQUIRE(point.state().plastic_strain > p);
  REQUIRE(point.state().stress_Pa ==
          Approx(-(spec.bilinear.yield_stress_Pa + H * point.state().plastic_strain))
              .epsilon(kClosedFormTolerance));
}

TEST_CASE("Work put into a bilinear point equals its stored plus dissipated energy over a cycle",
          "[model][material][bilinear][energy]") {
  const MaterialSpec spec = annealed_copper_like();
  test::MaterialPoint point(spec);
  constexpr int kSteps = 400;
  const double dt = 1e-8;
  double dissipated = 0;
  for (int i = 1; i <= 4 * kSteps; ++i) {
    const double eps = -0.05 * std::sin(0.5 * M_PI * i / kSteps);  // load, unload, reverse, back
    point.strain_to(eps, dt);
    REQUIRE(point.state().dissipated_J_m3 >= dissipated);  // second law: never negative
    dissipated = point.state().dissipated_J_m3;
  }
  const double balance = point.law().stored_energy_J_m3(point.state()) + dissipated;
  REQUIRE(balance == Approx(point.work_J_m3()).epsilon(kEnergyTolerance));
  // The cycle 0 → −0.05 → +0.05 → 0 strains plastically by more than 0.05 − σ_y/E in total, always
  // at |σ| ≥ σ_y: a lower bound on the dissipation that does not come from the code.
  const double sy = spec.bilinear.yield_stress_Pa;
  REQUIRE(dissipated > sy * (0.05 - sy / spec.youngs_modulus_Pa));
}

}  // namespace tests_model_test_material_bilinear
