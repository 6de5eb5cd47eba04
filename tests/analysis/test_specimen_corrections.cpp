// The inertia correction of the reduced curve (docs/methods.md §8.3) against answers known without
// it: Newton's second law for a specimen that moves as a rigid body, and Davies & Hunter's (1963)
// stress of a specimen with one face at rest (the back face, and its mirror image, the front);
// each face's stress and their average, corrected, return the specimen's own. A density of zero
// changes nothing, bit for bit.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

#include "analysis/reduction.hpp"
#include "analysis/specimen_corrections.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_analysis_test_specimen_corrections {

using namespace shpb;

// A dense specimen, 10 mm × Ø10 mm, sampled at 10 MHz.
constexpr double kDensity = 8000, kLength = 10e-3, kDiameter = 10e-3, kDt = 1e-7;
constexpr std::size_t kSamples = 11;

SpecimenProperties specimen(double density = kDensity) {
  return {kLength, std::numbers::pi * kDiameter * kDiameter / 4, density};
}

// A curve of the given engineering strain, strain rate and faces' velocities, with the face
// stresses P1/A_s, P2/A_s (compression positive) and the reduction's derived columns.
Curve curve_of(const std::vector<double>& strain, const std::vector<double>& rate,
               const std::vector<double>& front_velocity, const std::vector<double>& back_velocity,
               const std::vector<double>& front_Pa, const std::vector<double>& back_Pa) {
  Curve c;
  c.strain = strain;
  c.strain_rate_1_s = rate;
  c.velocity_front_m_s = front_velocity;
  c.velocity_back_m_s = back_velocity;
  c.stress_2wave_Pa = front_Pa;
  c.stress_1wave_Pa = back_Pa;
  for (std::size_t i = 0; i < strain.size(); ++i)
    c.stress_3wave_Pa.push_back(0.5 * (front_Pa[i] + back_Pa[i]));
  true_values(c.strain, c.stress_3wave_Pa, false, c.true_strain, c.true_stress_Pa);
  return c;
}

TEST_CASE("A rigid specimen accelerating: each face's corrected stress is its mean stress",
          "[analysis][inertia]") {
  // No strain: the specimen translates as a rigid body, v(t) = α t² (an acceleration 2αt that
  // grows). Newton's second law on it: its stress is linear along it, P1 − P2 = ρ L A_s v̇, the
  // back face's stress is the mean's less ρ L v̇/2 (the rear half's mass times its acceleration)
  // and the front face's the mean's plus as much. The mean is 50 MPa; at t = 1 µs the faces
  // differ by 16 MPa.
  const double alpha = 1e11, mean = 50e6;
  std::vector<double> zero(kSamples, 0.0), v(kSamples), front(kSamples), back(kSamples);
  for (std::size_t i = 0; i < kSamples; ++i) {
    const double t = static_cast<double>(i) * kDt, accel = 2 * alpha * t;
    v[i] = alpha * t * t;
    front[i] = mean + kDensity * kLength * accel / 2;
    back[i] = mean - kDensity * kLength * accel / 2;
  }
  Curve c = curve_of(zero, zero, v, v, front, back);
  apply_specimen_corrections(c, kDt, specimen(), {std::nullopt, true});
  // Central differences of a quadratic are exact: inside the record, each to rounding (1e-12).
  for (std::size_t i = 1; i + 1 < kSamples; ++i) {
    INFO("sample " << i << ": front face raw " << front[i] << " Pa, back face raw " << back[i]
                   << " Pa");
    CHECK(c.stress_1wave_Pa[i] == Approx(mean).epsilon(1e-12));
    CHECK(c.stress_2wave_Pa[i] == Approx(mean).epsilon(1e-12));
    CHECK(c.stress_3wave_Pa[i] == Approx(mean).epsilon(1e-12));
  }
}

TEST_CASE("One face at rest: the corrected faces' stresses are Davies and Hunter's flow stress",
          "[analysis][inertia]") {
  // Davies & Hunter (1963), J. Mech. Phys. Solids 11:155, for a specimen straining uniformly with
  // its back face at rest: σ_flow = σ_back + ρ (L²/6 − ν² D²/8) ε̈, incompressible (ν = 1/2).
  // The front face moves at v1 = L ė and pushes the whole mass: Newton gives P1 − P2 = ρ L A_s
  // v̇1/2. Its mirror image, the front face at rest and the back face moving at v2 = −L ė: the
  // front face's stress is σ_flow − ρ (L²/6 − D²/32) ε̈ and the back face's above it by
  // ρ L (L ε̈)/2. A constant ε̈ of 1e8 1/s² from rest: over 1 µs ė reaches 100 1/s and e 5e-5,
  // so the terms the closed form leaves out (ė² against ε̈, the length change) are below 1e-4 of
  // its 10.8 MPa: the tolerance, 1e-3 of it.
  const double accel = 1e8, flow = 10e6;
  const double term = kDensity * (kLength * kLength / 6 - kDiameter * kDiameter / 32) * accel;
  constexpr double kLeftOut = 1e-3;
  for (const bool front_at_rest : {false, true}) {
    std::vector<double> strain(kSamples), rate(kSamples), front_v(kSamples), back_v(kSamples),
        front(kSamples), back(kSamples);
    for (std::size_t i = 0; i < kSamples; ++i) {
      const double t = static_cast<double>(i) * kDt;
      strain[i] = accel * t * t / 2;
      rate[i] = accel * t;
      const double push = kDensity * kLength * (kLength * accel) / 2;  // Newton: ρ L v̇/2
      front_v[i] = front_at_rest ? 0 : kLength * rate[i];
      back_v[i] = front_at_rest ? -kLength * rate[i] : 0;
      (front_at_rest ? front : back)[i] = flow - term;
      if (front_at_rest)
        back[i] = front[i] + push;
      else
        front[i] = back[i] + push;
    }
    Curve c = curve_of(strain, rate, front_v, back_v, front, back);
    const Curve raw = c;
    apply_specimen_corrections(c, kDt, specimen(), {std::nullopt, true});
    for (std::size_t i = 1; i + 1 < kSamples; ++i) {
      INFO((front_at_rest ? "front" : "back")
           << " face at rest, sample " << i << ": front face raw " << raw.stress_2wave_Pa[i]
           << " Pa, back face raw " << raw.stress_1wave_Pa[i] << " Pa, 3-wave raw "
           << raw.stress_3wave_Pa[i] << " Pa, closed-form term " << term << " Pa");
      CHECK(c.stress_1wave_Pa[i] * (1 - strain[i]) == Approx(flow).margin(kLeftOut * term));
      CHECK(c.stress_2wave_Pa[i] * (1 - strain[i]) == Approx(flow).margin(kLeftOut * term));
      CHECK(c.true_stress_Pa[i] == Approx(flow).margin(kLeftOut * term));
    }

    // No density, no inertia: the curve exactly as reduced; nor without the correction asked for.
    for (const auto& [density, inertia] : {std::pair{0.0, true}, std::pair{kDensity, false}}) {
      Curve same = raw;
      apply_specimen_corrections(same, kDt, specimen(density), {std::nullopt, inertia});
      CHECK(same.stress_1wave_Pa == raw.stress_1wave_Pa);
      CHECK(same.stress_2wave_Pa == raw.stress_2wave_Pa);
      CHECK(same.stress_3wave_Pa == raw.stress_3wave_Pa);
      CHECK(same.true_stress_Pa == raw.true_stress_Pa);
    }
  }
}

}  // namespace tests_analysis_test_specimen_corrections
