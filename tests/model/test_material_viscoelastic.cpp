#include <catch2/catch.hpp>
#include <cmath>

#include "material_point.hpp"
#include "model/law_parameters.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_model_test_material_viscoelastic {

using namespace shpb;

namespace {
// The law matches its closed form within 0.1 %.
constexpr double kClosedFormTolerance = 1e-3;
// Energy bookkeeping is exact algebra (trapezoidal work = stored + dissipated), up to round-off.
constexpr double kEnergyTolerance = 1e-9;

// Three-arm Prony series of PMMA-like stiffness (moduli and times spread over three decades).
MaterialSpec three_arm() {
  MaterialSpec spec;
  spec.model = MaterialModel::kViscoelastic;
  spec.density_kg_m3 = 1190;
  spec.viscoelastic.long_term_modulus_Pa = 2.0e9;
  spec.viscoelastic.arms = {{1.0e9, 1e-6}, {0.8e9, 1e-5}, {0.6e9, 1e-4}};
  spec.youngs_modulus_Pa = 4.4e9;
  return spec;
}

// Standard linear solid (one arm) for creep, whose closed form is a single exponential.
MaterialSpec standard_linear_solid() {
  MaterialSpec spec;
  spec.model = MaterialModel::kViscoelastic;
  spec.density_kg_m3 = 1190;
  spec.viscoelastic.long_term_modulus_Pa = 2.0e9;
  spec.viscoelastic.arms = {{1.5e9, 2e-5}};
  spec.youngs_modulus_Pa = 3.5e9;
  return spec;
}

// σ(t) at constant strain rate from rest: E_inf ε̇ t + Σ E_k τ_k ε̇ (1 − e^{−t/τ_k}).
double constant_rate_stress(const MaterialSpec& spec, double rate, double t) {
  double s = spec.viscoelastic.long_term_modulus_Pa * rate * t;
  for (const auto& a : spec.viscoelastic.arms)
    s += a.modulus_Pa * a.relaxation_time_s * rate * -std::expm1(-t / a.relaxation_time_s);
  return s;
}
}  // namespace

TEST_CASE("A viscoelastic point at constant strain rate follows the Prony-series closed form",
          "[model][material][viscoelastic]") {
  const MaterialSpec spec = three_arm();
  for (double rate : {1e1, 1e3, 1e5}) {
    SECTION("rate " + std::to_string(rate) + " /s") {
      test::MaterialPoint point(spec);
      constexpr int kSteps = 500;
      const double duration = 0.02 / rate;  // up to 2 % strain
      const double dt = duration / kSteps;
      for (int i = 1; i <= kSteps; ++i) {
        const double sigma = point.strain_to(-rate * i * dt, dt);
        REQUIRE(-sigma ==
                Approx(constant_rate_stress(spec, rate, i * dt)).epsilon(kClosedFormTolerance));
      }
    }
  }
}

TEST_CASE("A law driven along a processed strain history from rest carries the closed-form stress",
          "[model][material][viscoelastic]") {
  // What `shpb fit` compares a law without a flow stress by (curves.csv): a test's true strain
  // history, positive in compression and in tension alike, and the stress the law carries.
  const MaterialSpec spec = three_arm();
  const double rate = 5e3;  // a Kolsky test's rate, 2 % strain in 4 µs
  constexpr int kSamples = 500;
  std::vector<double> time(kSamples + 1), strain(kSamples + 1);
  for (int i = 0; i <= kSamples; ++i) {
    time[i] = 20e-6 + i * (0.02 / rate) / kSamples;  // the record's clock: any origin
    strain[i] = rate * (time[i] - time[0]);
  }
  for (const bool tension : {false, true}) {
    const std::vector<double> stress = law_stress_along(spec, time, strain, tension);
    for (int i = 1; i <= kSamples; ++i)
      REQUIRE(stress[i] == Approx(constant_rate_stress(spec, rate, time[i] - time[0]))
                               .epsilon(kClosedFormTolerance));
  }
}

TEST_CASE("A viscoelastic point held at fixed strain relaxes along the sum of exponentials",
          "[model][material][viscoelastic]") {
  const MaterialSpec spec = three_arm();
  test::MaterialPoint point(spec);
  // Ramp to ε0 in t_r at constant rate, then hold: for t > t_r each arm decays from its
  // ramp-end value E_k τ_k (ε0/t_r)(1 − e^{−t_r/τ_k}) with its own τ_k.
  const double eps0 = -0.01, ramp = 1e-7, dt_ramp = ramp / 10;
  for (int i = 1; i <= 10; ++i) point.strain_to(eps0 * i / 10, dt_ramp);
  const double dt = 5e-7;  // 4000 steps: 20 τ_max
  for (int i = 1; i <= 4000; ++i) {
    const double sigma = point.strain_to(eps0, dt);
    const double t = i * dt;  // time since the end of the ramp
    double exact = spec.viscoelastic.long_term_modulus_Pa * eps0;
    for (const auto& a : spec.viscoelastic.arms)
      exact += a.modulus_Pa * a.relaxation_time_s * (eps0 / ramp) *
               -std::expm1(-ramp / a.relaxation_time_s) * std::exp(-t / a.relaxation_time_s);
    REQUIRE(sigma == Approx(exact).epsilon(kClosedFormTolerance));
  }
  // After ≫ τ_max only the long-term spring carries load; everything else was dissipated.
  const MaterialPointState& s = point.state();
  REQUIRE(s.stress_Pa == Approx(spec.viscoelastic.long_term_modulus_Pa * eps0).epsilon(1e-6));
  REQUIRE(point.law().stored_energy_J_m3(s) + s.dissipated_J_m3 ==
          Approx(point.work_J_m3()).epsilon(kEnergyTolerance));
  REQUIRE(point.law().stored_energy_J_m3(s) ==
          Approx(0.5 * spec.viscoelastic.long_term_modulus_Pa * eps0 * eps0).epsilon(1e-6));
}

TEST_CASE("A standard linear solid under constant stress creeps along its retardation exponential",
          "[model][material][viscoelastic]") {
  const MaterialSpec spec = standard_linear_solid();
  const double Einf = spec.viscoelastic.long_term_modulus_Pa;
  const double E0 = spec.youngs_modulus_Pa;
  const double tau = spec.viscoelastic.arms[0].relaxation_time_s;
  // Creep of the Zener solid: ε(t) = σ0 [1/E_inf − (1/E_inf − 1/E0) e^{−t/τ_c}], τ_c = τ E0/E_inf
  // (Findley, Lai & Onaran 1976, "Creep and relaxation of nonlinear viscoelastic materials", §5.4).
  const double retardation = tau * E0 / Einf;
  const double sigma0 = -50e6;
  test::MaterialPoint point(spec);
  REQUIRE(point.stress_to(sigma0, 0.0) == Approx(sigma0 / E0).epsilon(kClosedFormTolerance));
  const double dt = retardation / 1000;
  for (int i = 1; i <= 8000; ++i) {
    const double eps = point.stress_to(sigma0, dt);
    const double t = i * dt;
    const double exact = sigma0 * (1 / Einf - (1 / Einf - 1 / E0) * std::exp(-t / retardation));
    REQUIRE(eps == Approx(exact).epsilon(kClosedFormTolerance));
  }
}

TEST_CASE("A viscoelastic point is stiffest at its instantaneous modulus and never creates energy",
          "[model][material][viscoelastic][energy]") {
  const MaterialSpec spec = three_arm();
  test::MaterialPoint point(spec);
  REQUIRE(point.law().max_tangent_modulus_Pa() == Approx(4.4e9));
  double dissipated = 0;
  const double dt = 1e-7;
  for (int i = 1; i <= 4000; ++i) {
    point.strain_to(-0.01 * std::sin(2 * M_PI * i / 1000.0), dt);  // 10 kHz cycles
    REQUIRE(point.state().dissipated_J_m3 >= dissipated);
    dissipated = point.state().dissipated_J_m3;
  }
  REQUIRE(dissipated > 0);
  REQUIRE(point.law().stored_energy_J_m3(point.state()) + dissipated ==
          Approx(point.work_J_m3()).epsilon(kEnergyTolerance));
}

}  // namespace tests_model_test_material_viscoelastic
