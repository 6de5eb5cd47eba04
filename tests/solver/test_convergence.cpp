// Convergence of the bar integrator (docs/methods.md §1: linear elements, lumped mass, central
// difference), MFEM-style: the measured order of a gauge's error under mesh refinement, and the
// exactness of the scheme at Courant number 1.
//
// A smooth right-running strain pulse ε(x, t) = ε0(x − c0 t) (Gaussian, width w) crosses a free
// bar; a gauge reads the element strains interpolated linearly between element centres, as the
// recorders do (solver/recorders.cpp). At a Courant number C < 1 the scheme is consistent of
// second order in h and Δt = C h/c0 together: its dispersion relation
// sin(ωΔt/2) = C sin(kh/2) gives a phase velocity c0 (1 − (kh)² (1 − C²)/24 + O(h⁴)), and the
// gauge's interpolation between element centres is second order too, so the error of a smooth
// signal falls as h². What would lower the order: data that are not smooth (the jump of a square
// pulse converges in L2 as h^½), a start that takes the initial velocity as v_{−1/2} instead of
// kicking half a step (first order), a gauge that reads its nearest element (first order). At
// C = 1 the lumped central difference is exact at the nodes for any data (u_i^{n+1} = u_{i+1}^n
// + u_{i−1}^n − u_i^{n−1} holds for every f(x_i − c0 t_n)): only round-off is left.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <vector>

#include "solver/bar.hpp"
#include "solver/bar_integrator.hpp"
#include "test_scenes.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_solver_test_convergence {

using namespace shpb;

namespace {

constexpr double kLength = 1.0, kArea = 2.85e-4;
constexpr double kAmplitude = -1e-3;  // compression, a typical incident pulse
constexpr double kWidth = 0.04;       // e-folding half width w of the Gaussian [m]
constexpr double kStart = 0.3;        // pulse centre at t = 0 [m]
constexpr double kGauge = 0.6;        // gauge position [m]
constexpr double kTravel = 0.45;      // run until the centre has moved this far [m]: the gauge
                                      // sees the whole pulse, the bar's ends see none of it

double strain0(double x) {
  const double s = (x - kStart) / kWidth;
  return kAmplitude * std::exp(-s * s);
}
// Displacement whose derivative is strain0 (zero far left).
double displacement0(double x) {
  return kAmplitude * kWidth * std::sqrt(std::numbers::pi) / 2 *
         (1 + std::erf((x - kStart) / kWidth));
}

// Strain at x between element centres, as a gauge reads it.
double gauge_strain(const BarModel& bar, const BarState& s, double x) {
  const double h = bar.element_length_m;
  const double p = x / h - 0.5;
  const int e = static_cast<int>(std::floor(p));
  const double wt = p - e;
  auto strain = [&](int k) { return (s.w[k + 1] - s.w[k]) / h; };
  return (1 - wt) * strain(e) + wt * strain(e + 1);
}

struct Run {
  BarModel bar;
  BarState state;
};

Run make_run(int elements, double courant) {
  const MaterialSpec steel = test::steel();
  const double h = kLength / elements, c0 = steel.wave_speed_m_s();
  Run r{make_bar_model("bar", steel, kLength, kArea, elements, courant * h / c0, 0.0), {}};
  r.state = make_bar_state(r.bar, true);
  return r;
}

// Relative L2 error of the gauge signal over every step until the pulse has travelled kTravel,
// starting from the exact u and v at t = 0 (the integrator's own start: half a kick first).
double gauge_error(int elements, double courant) {
  Run r = make_run(elements, courant);
  const double h = r.bar.element_length_m, c0 = r.bar.wave_speed_m_s, dt = r.bar.time_step_s;
  for (int i = 0; i < r.bar.nodes; ++i) {
    r.state.w[i] = displacement0(i * h);
    r.state.v[i] = -c0 * strain0(i * h);
  }
  const long steps = std::lround(kTravel / (c0 * dt));
  double diff = 0, norm = 0;
  for (long n = 0;; ++n) {
    const double exact = strain0(kGauge - c0 * n * dt);
    const double e = gauge_strain(r.bar, r.state, kGauge) - exact;
    diff += e * e;
    norm += exact * exact;
    if (n == steps) break;
    assemble_internal_forces(r.bar, r.state);
    advance(r.bar, r.state);
  }
  return std::sqrt(diff / norm);
}

}  // namespace

TEST_CASE("A smooth pulse converges at second order in h at Courant number 0.5",
          "[solver][convergence]") {
  // C = 0.5: far enough below 1 that the dispersion error (∝ 1 − C²) is not hidden by round-off.
  // Four meshes of h = 4, 2, 1 and 0.5 mm: 10 to 80 elements per width w, in the asymptotic
  // range where the next term of the error, O((h/w)²) relative to the first, moves the measured
  // order by less than 0.05.
  constexpr double kCourant = 0.5;
  constexpr double kExpectedOrder = 2.0;  // central difference + lumped mass on smooth data
  constexpr double kOrderTolerance = 0.1;
  std::vector<double> errors;
  for (int elements : {250, 500, 1000, 2000}) errors.push_back(gauge_error(elements, kCourant));
  for (std::size_t k = 0; k + 1 < errors.size(); ++k) {
    const double order = std::log2(errors[k] / errors[k + 1]);
    INFO("h → h/2 from " << 250 * (1 << k) << " elements: error " << errors[k] << " → "
                         << errors[k + 1] << ", measured order " << order);
    CHECK(std::abs(order - kExpectedOrder) < kOrderTolerance);
  }
  CHECK(errors.back() < 1e-3);  // a gauge of 1000 µε reads the pulse to better than 1 µε
}

TEST_CASE("At Courant number 1 the lumped central difference is exact at the nodes",
          "[solver][convergence]") {
  // Started from the exact displacements at t_0 = 0 and t_1 = Δt (the state after one step:
  // u at t_1, v at t_{1/2}), every later nodal displacement is exact, so every element strain
  // equals the exact strain averaged over the element. What is left is round-off: about 1e-16
  // relative per operation over some 10³ steps.
  constexpr double kRoundOff = 1e-10;
  constexpr int kElements = 500;
  Run r = make_run(kElements, 1.0);
  const double h = r.bar.element_length_m, c0 = r.bar.wave_speed_m_s, dt = r.bar.time_step_s;
  REQUIRE(r.bar.courant == Approx(1.0).epsilon(1e-15));
  for (int i = 0; i < r.bar.nodes; ++i) {
    r.state.w[i] = displacement0(i * h - c0 * dt);
    r.state.v[i] = (r.state.w[i] - displacement0(i * h)) / dt;
  }
  r.state.step = 1;
  r.state.dt_prev = dt;  // the step that led to t_1 (the kick is ½(Δt_0 + Δt_1))
  const long steps = std::lround(kTravel / (c0 * dt));
  double worst = 0;
  for (long n = 1; n <= steps; ++n) {
    if (n > 1) {
      assemble_internal_forces(r.bar, r.state);
      advance(r.bar, r.state);
    }
    const double shift = c0 * n * dt;
    for (int e = 0; e < kElements; ++e) {
      const double exact = (displacement0((e + 1) * h - shift) - displacement0(e * h - shift)) / h;
      worst = std::max(worst, std::abs((r.state.w[e + 1] - r.state.w[e]) / h - exact));
    }
  }
  INFO("largest element strain error " << worst << " over " << steps << " steps");
  CHECK(worst / std::abs(kAmplitude) < kRoundOff);
}

}  // namespace tests_solver_test_convergence
