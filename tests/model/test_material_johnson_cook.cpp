#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "johnson_cook_tables.hpp"
#include "material_point.hpp"
#include "model/laws/johnson_cook_law.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_model_test_material_johnson_cook {

using namespace shpb;
using test::al6061;
using test::ofhc_copper;

namespace {
// The law matches its closed form within 0.1 %.
constexpr double kClosedFormTolerance = 1e-3;
// Energy bookkeeping is exact algebra (trapezoidal work = stored + dissipated), up to round-off.
constexpr double kEnergyTolerance = 1e-10;
// τ = L/(2 c0) is a product, a quotient and a square root: equal to round-off.
constexpr double kTransitRoundOff = 1e-14;
// Fine reference for the adiabatic ODE: RK4 steps in plastic strain (error ≪ 1e-6 relative).
constexpr double kReferenceStep = 2e-6;

// Johnson & Cook (1983) eq. 1 written out independently of the law under test: rate term floored
// at the reference rate, thermal term 1 below room temperature.
double reference_flow_stress(const JohnsonCookParams& jc, double p, double rate, double T) {
  const double rate_term = 1 + jc.C * std::log(std::max(rate / jc.reference_strain_rate_1_s, 1.0));
  const double homologous = std::max(
      0.0, (T - jc.room_temperature_K) / (jc.melting_temperature_K - jc.room_temperature_K));
  return (jc.A_Pa + jc.B_Pa * std::pow(p, jc.n)) * rate_term * (1 - std::pow(homologous, jc.m));
}

// The monotonic constant-rate response as a curve parametrised by plastic strain p: σ(p) is the
// flow stress at the (constant) rate and at the temperature T(p) of dT/dp = β σ / (ρ c_p)
// (T constant when isothermal), and the total strain is ε(p) = p + σ(p)/E.
struct ReferenceCurve {
  std::vector<double> strain, stress, temperature;
};

ReferenceCurve reference_curve(const MaterialSpec& spec, double rate, double max_plastic) {
  const JohnsonCookParams& jc = spec.johnson_cook;
  const double heat =
      jc.adiabatic ? jc.taylor_quinney / (spec.density_kg_m3 * jc.specific_heat_J_kgK) : 0.0;
  auto sigma = [&](double p, double T) { return reference_flow_stress(jc, p, rate, T); };
  auto dTdp = [&](double p, double T) { return heat * sigma(p, T); };
  ReferenceCurve c;
  double T = jc.initial_temperature_K;
  const double h = kReferenceStep;
  for (double p = 0; p <= max_plastic; p += h) {
    c.strain.push_back(p + sigma(p, T) / spec.youngs_modulus_Pa);
    c.stress.push_back(sigma(p, T));
    c.temperature.push_back(T);
    const double k1 = dTdp(p, T), k2 = dTdp(p + h / 2, T + h / 2 * k1);
    const double k3 = dTdp(p + h / 2, T + h / 2 * k2), k4 = dTdp(p + h, T + h * k3);
    T += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  return c;
}

// Linear interpolation of a monotonic table column at total strain eps.
double at_strain(const ReferenceCurve& c, const std::vector<double>& column, double eps) {
  std::size_t j = 1;
  while (j + 1 < c.strain.size() && c.strain[j] < eps) ++j;
  const double w = (eps - c.strain[j - 1]) / (c.strain[j] - c.strain[j - 1]);
  return column[j - 1] + w * (column[j] - column[j - 1]);
}

// Drives a point in compression to strain −final_strain at the given rate; checks every step past
// yield against the reference curve (compression positive in the comparison).
void check_constant_rate(const MaterialSpec& spec, double rate, double final_strain) {
  constexpr int kSteps = 3000;
  const ReferenceCurve ref = reference_curve(spec, rate, final_strain);
  test::MaterialPoint point(spec);
  const double dt = final_strain / rate / kSteps;
  for (int i = 1; i <= kSteps; ++i) {
    const double eps = final_strain * i / kSteps;
    const double sigma = -point.strain_to(-eps, dt);
    if (eps <= ref.strain.front()) {
      REQUIRE(sigma == Approx(spec.youngs_modulus_Pa * eps).epsilon(kClosedFormTolerance));
    } else {
      REQUIRE(sigma == Approx(at_strain(ref, ref.stress, eps)).epsilon(kClosedFormTolerance));
    }
  }
  REQUIRE(point.state().temperature_K ==
          Approx(at_strain(ref, ref.temperature, final_strain)).epsilon(kClosedFormTolerance));
}
}  // namespace

TEST_CASE("A Johnson-Cook point at constant strain rate follows its isothermal closed form",
          "[release-only][model][material][johnson-cook]") {
  // Rates below (floored to ε̇0), above and far above the reference rate.
  for (double rate : {1e-3, 1e2, 5e3}) {
    SECTION("Al 6061-T6 at " + std::to_string(rate) + " /s") {
      check_constant_rate(al6061(false), rate, 0.3);
    }
    SECTION("OFHC copper at " + std::to_string(rate) + " /s") {
      check_constant_rate(ofhc_copper(false), rate, 0.3);
    }
  }
}

TEST_CASE("A Johnson-Cook point heated adiabatically follows the fine ODE solution",
          "[release-only][model][material][johnson-cook]") {
  for (double rate : {1e-3, 1e2, 5e3}) {
    SECTION("Al 6061-T6 at " + std::to_string(rate) + " /s") {
      check_constant_rate(al6061(true), rate, 0.3);
    }
    SECTION("OFHC copper at " + std::to_string(rate) + " /s") {
      check_constant_rate(ofhc_copper(true), rate, 0.3);
    }
  }
}

TEST_CASE("The Johnson-Cook rate term is floored at the reference rate and grows as ln(rate)",
          "[model][material][johnson-cook]") {
  const JohnsonCookParams jc = ofhc_copper(false).johnson_cook;
  REQUIRE(johnson_cook_rate_factor(jc, 1e-6) == 1.0);
  REQUIRE(johnson_cook_rate_factor(jc, -0.5) == 1.0);
  REQUIRE(johnson_cook_rate_factor(jc, -1e3) == Approx(1 + 0.025 * std::log(1e3)));
  // Thermal factor: 1 at and below room temperature, 0 at melting, 1 − T*^m between.
  REQUIRE(johnson_cook_thermal_factor(jc, 250) == 1.0);
  REQUIRE(johnson_cook_thermal_factor(jc, 1356) == 0.0);
  REQUIRE(johnson_cook_thermal_factor(jc, 0.5 * (294 + 1356)) == Approx(1 - std::pow(0.5, 1.09)));
}

TEST_CASE("The Johnson-Cook strain-rate filter follows the first-order response to a rate step",
          "[model][material][johnson-cook]") {
  // Perfectly plastic (B = 0) and isothermal: once yielding, σ = A (1 + C ln(ε̇_f/ε̇0)) exactly,
  // so the stress shows the filtered rate. Loaded at R1 from rest, then at R2: for a rate held
  // over each step the filter's exact solution is ε̇_f = R + (ε̇_f(t0) − R) e^{−(t − t0)/τ}.
  // Round-off only: the law's series for ln are exact to ~1e-16 of the rate factor.
  constexpr double kRoundOff = 1e-12;
  MaterialSpec spec = ofhc_copper(false);
  JohnsonCookParams& jc = spec.johnson_cook;
  jc.B_Pa = 0;
  jc.strain_rate_filter_s = 0.2e-6;
  const double dt = 0.01e-6, r1 = 100, r2 = 5000;
  const int steps1 = 1000, steps2 = 400;  // 10 µs at R1 (yields at ~8 µs), 20 τ at R2
  test::MaterialPoint point(spec);
  double eps = 0, filtered = 0, phase_value = 0;  // ε̇_f now and at the start of the phase
  int phase_step = 0, plastic_steps = 0;
  for (int k = 1; k <= steps1 + steps2; ++k) {
    const double rate = k <= steps1 ? r1 : r2;
    if (k == steps1 + 1) phase_step = steps1, phase_value = filtered;
    eps += rate * dt;
    filtered =
        rate + (phase_value - rate) * std::exp(-(k - phase_step) * dt / *jc.strain_rate_filter_s);
    const double p_before = point.state().plastic_strain;
    const double sigma = -point.strain_to(-eps, dt);
    if (point.state().plastic_strain > p_before) {
      ++plastic_steps;
      INFO("step " << k << " filtered rate " << filtered);
      REQUIRE(sigma ==
              Approx(jc.A_Pa * (1 + jc.C * std::log(filtered / jc.reference_strain_rate_1_s)))
                  .epsilon(kRoundOff));
    }
  }
  // Plastic through the step and after it (the flow stress rises slower than the elastic load).
  REQUIRE(plastic_steps > steps2);
  // Off by default: the same path without the filter flows at the step's own rate R2 (once the
  // elastic reloading from R1's flow stress is over), where the filtered point has just caught up.
  MaterialSpec plain = spec;
  plain.johnson_cook.strain_rate_filter_s = 0;
  test::MaterialPoint unfiltered(plain);
  eps = 0;
  double sigma = 0;
  for (int k = 1; k <= steps1 + steps2; ++k) {
    eps += (k <= steps1 ? r1 : r2) * dt;
    sigma = -unfiltered.strain_to(-eps, dt);
  }
  REQUIRE(sigma == Approx(jc.A_Pa * (1 + jc.C * std::log(r2))).epsilon(kRoundOff));
}

TEST_CASE(
    "The specimen's Johnson-Cook law sees the rate through half its elastic transit unless "
    "the material gives a filter",
    "[material][johnson-cook]") {
  // docs/scene-format.md, strain_rate_filter: the scene's specimen defaults to L/(2 c0); a filter
  // the material gives, 0 s (off) included, is kept.
  const double length = 5e-3;
  MaterialSpec spec = ofhc_copper(true);
  const double half_transit = 0.5 * length / std::sqrt(spec.youngs_modulus_Pa / spec.density_kg_m3);
  REQUIRE(*specimen_law_material(spec, length).johnson_cook.strain_rate_filter_s ==
          Approx(half_transit).epsilon(kTransitRoundOff));
  for (const double given : {0.0, 1e-6}) {
    spec.johnson_cook.strain_rate_filter_s = given;
    REQUIRE(*specimen_law_material(spec, length).johnson_cook.strain_rate_filter_s == given);
  }
}

TEST_CASE("Adiabatic heating of a Johnson-Cook point turns beta of the plastic work into heat",
          "[model][material][johnson-cook][energy]") {
  const MaterialSpec spec = ofhc_copper(true);
  test::MaterialPoint point(spec);
  constexpr int kSteps = 2000;
  const double rate = 2000, dt = 0.2 / rate / kSteps;
  for (int i = 1; i <= kSteps; ++i) point.strain_to(-0.2 * i / kSteps, dt);
  for (int i = 1; i <= kSteps / 10; ++i) point.strain_to(-0.2 + 0.01 * i * 10 / kSteps, dt);
  const MaterialPointState& s = point.state();
  const double balance = point.law().stored_energy_J_m3(s) + s.dissipated_J_m3;
  REQUIRE(balance == Approx(point.work_J_m3()).epsilon(kEnergyTolerance));
  REQUIRE(s.heat_J_m3 == Approx(0.9 * s.dissipated_J_m3).epsilon(kEnergyTolerance));
  const double rise = s.heat_J_m3 / (spec.density_kg_m3 * spec.johnson_cook.specific_heat_J_kgK);
  REQUIRE(s.temperature_K - 294 == Approx(rise).epsilon(kEnergyTolerance));
  // Copper at 0.2 strain heats by about 0.9 · 0.2 · ~300 MPa / (ρ c_p) ≈ 16 K: a physical range.
  REQUIRE(rise > 10);
  REQUIRE(rise < 25);
}

TEST_CASE("A Johnson-Cook point tested above room temperature is softer by the thermal factor",
          "[model][material][johnson-cook]") {
  MaterialSpec spec = al6061(false);
  spec.johnson_cook.initial_temperature_K = 500;
  const double factor = johnson_cook_thermal_factor(spec.johnson_cook, 500);
  REQUIRE(factor < 1);
  check_constant_rate(spec, 1e3, 0.2);
  test::MaterialPoint hot(spec);
  hot.strain_to(-0.02, 1e-5);  // well past yield in one step: σ = A · rate factor · thermal factor
  REQUIRE(-hot.state().stress_Pa ==
          Approx(reference_flow_stress(spec.johnson_cook, hot.state().plastic_strain, 2e3, 500))
              .epsilon(kClosedFormTolerance));
}

}  // namespace tests_model_test_material_johnson_cook
