#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <numbers>
#include <tuple>
#include <utility>
#include <vector>

#include "dispersion/pochhammer_chree.hpp"
#include "dispersion/propagation.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_dispersion_test_propagation {

using namespace shpb;

namespace {

// A Ti-6Al-4V bar like the LANL one: radius 4.735 mm, c0 = 4975 m/s, ν = 0.33; 10 MHz samples.
const BarWaveguide kBar{4.735e-3, 4975.0, 0.33};
constexpr double kDt = 1e-7;

double rms(const std::vector<double>& a) {
  double s = 0;
  for (double v : a) s += v * v;
  return std::sqrt(s / static_cast<double>(a.size()));
}

// A trapezoid-like compressive pulse with cosine ramps whose spectrum lies below the cut-off
// (rise 8 µs: its content above f·a/c0 ≈ 0.2 is < 1e-4 of the peak).
std::vector<double> smooth_pulse(std::size_t n, double start_s, double rise_s, double flat_s) {
  std::vector<double> x(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * kDt - start_s;
    double v = 0;
    if (t > 0 && t < rise_s)
      v = 0.5 * (1 - std::cos(std::numbers::pi * t / rise_s));
    else if (t >= rise_s && t <= rise_s + flat_s)
      v = 1;
    else if (t > rise_s + flat_s && t < 2 * rise_s + flat_s)
      v = 0.5 * (1 + std::cos(std::numbers::pi * (t - rise_s - flat_s) / rise_s));
    x[i] = -1e-3 * v;
  }
  return x;
}

}  // namespace

TEST_CASE("Moving a pulse forward and back returns it within 0.5 % RMS below the cut-off",
          "[dispersion]") {
  const DispersionTable table(kBar.poisson);
  Propagator p(table, kBar, {});
  const auto x = smooth_pulse(4000, 60e-6, 8e-6, 40e-6);
  const auto there = p.propagate(x, kDt, 1.0);
  REQUIRE(propagate(x, kDt, 1.0, kBar) == there);  // the one-off free function is the same
  const auto back = p.propagate(there, kDt, -1.0);
  std::vector<double> err(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) err[i] = back[i] - x[i];
  constexpr double kRoundTrip =
      5e-3;  // band-limited: the cut-off removes a little of the pulse's spectrum
  CHECK(rms(err) / rms(x) < kRoundTrip);
  // The forward pulse itself is changed by dispersion (and delayed by ~1/c0): the test can fail.
  std::vector<double> moved(x.size());
  delay_by_interpolation(x, 1.0 / (kBar.c0_m_s * kDt), moved);
  for (std::size_t i = 0; i < x.size(); ++i) err[i] = there[i] - moved[i];
  CHECK(rms(err) / rms(x) > 5 * kRoundTrip);
}

TEST_CASE(
    "A tone burst's envelope travels at the group velocity and its carrier at the phase velocity",
    "[dispersion]") {
  const DispersionTable table(kBar.poisson);
  PropagationOptions options;
  options.cutoff_fa_over_c0 = 0.35;  // keep the burst's band (f·a/c0 ≈ 0.16) untouched
  Propagator p(table, kBar, options);
  const double f0 = 170e3;  // f·a/c0 = 0.162: c_g/c0 ≈ 0.85, far from c/c0 ≈ 0.95
  const double fa = f0 * kBar.radius_m / kBar.c0_m_s;
  const double width = 40e-6, t0 = 100e-6;
  const std::size_t n = 8000;
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * kDt - t0;
    x[i] = std::exp(-0.5 * t * t / (width * width / 9)) * std::cos(2 * std::numbers::pi * f0 * t);
  }
  const double dz = 1.5;
  const auto y = p.propagate(x, kDt, dz);
  // Envelope peak from the analytic-signal-free estimate: max of y² smoothed over a period.
  const auto period = static_cast<std::size_t>(1 / (f0 * kDt));
  double best = 0;
  std::size_t at = 0;
  for (std::size_t i = period; i + period < n; ++i) {
    double e = 0;
    for (std::size_t j = i - period / 2; j < i + period / 2; ++j) e += y[j] * y[j];
    if (e > best) best = e, at = i;
  }
  // Solve x with x·c(x) = fa for the exact group velocity.
  double xl = fa, xh = 2 * fa;
  for (int i = 0; i < 60; ++i) {
    const double xm = 0.5 * (xl + xh);
    (xm * phase_velocity(kBar.poisson, xm) < fa ? xl : xh) = xm;
  }
  const double cg =
      group_velocity(kBar.poisson, xl, phase_velocity(kBar.poisson, xl)) * kBar.c0_m_s;
  const double expected = t0 + dz / cg;
  const double found = static_cast<double>(at) * kDt;
  // The envelope peak is resolved to about one carrier period over 4 (1.5 µs).
  constexpr double kEnvelopeTiming = 1.5e-6;
  CHECK(std::abs(found - expected) < kEnvelopeTiming);
  // Non-dispersive arrival would be 1.5 m / c0 = 301 µs, 50 µs earlier: clearly distinguished.
  CHECK(std::abs(found - (t0 + dz / kBar.c0_m_s)) > 20 * kEnvelopeTiming);
}

TEST_CASE("A pulse near the start of a long record is moved as in a short one", "[dispersion]") {
  // A scope triggered with a short pre-trigger: the pulse starts 60 µs into the record. Whether
  // 2 000 or 100 000 quiet samples follow it, the correction moves the same pulse (the record's
  // ends are tapered, never the pulse: on the long record its first 2 % hold the whole pulse).
  const DispersionTable table(kBar.poisson);
  Propagator p(table, kBar, {});
  constexpr std::size_t kShort = 2000, kLong = 100000;
  const auto there_short = p.propagate(smooth_pulse(kShort, 60e-6, 8e-6, 40e-6), kDt, 0.5);
  const auto there_long = p.propagate(smooth_pulse(kLong, 60e-6, 8e-6, 40e-6), kDt, 0.5);
  double peak = 0, worst = 0;
  for (std::size_t i = 0; i < kShort; ++i) {
    peak = std::max(peak, std::abs(there_short[i]));
    worst = std::max(worst, std::abs(there_long[i] - there_short[i]));
  }
  // The two FFT lengths sample the same band-limited kernel at different frequencies: the moved
  // pulses agree to far below a gauge's resolution (1e-4 of the peak), not merely in shape.
  constexpr double kSameMove = 1e-4;
  CHECK(worst < kSameMove * peak);
}

TEST_CASE("A further delay moves the propagated pulse by that time, between samples too",
          "[dispersion]") {
  // A channel's delay (docs/methods.md §11) is a phase: the pulse moved 0.5 m and delayed 0.37 of
  // a sample is the same pulse started 0.37 of a sample later and moved 0.5 m. Interpolating
  // between samples instead low-passes it (here 2e-4 of the peak off at a 2 µs ramp).
  const DispersionTable table(kBar.poisson);
  Propagator p(table, kBar, {});
  constexpr std::size_t kN = 3000;
  constexpr double kDelay = 0.37 * kDt, kStart = 20e-6, kRise = 2e-6, kFlat = 30e-6;
  std::vector<double> delayed(kN);
  p.propagate(smooth_pulse(kN, kStart, kRise, kFlat), kDt, 0.5, delayed, kDelay);
  const auto later = p.propagate(smooth_pulse(kN, kStart + kDelay, kRise, kFlat), kDt, 0.5);
  double worst = 0;
  for (std::size_t i = 0; i < kN; ++i) worst = std::max(worst, std::abs(delayed[i] - later[i]));
  // Both are the same band-limited pulse sampled at the same times: they differ only by what
  // the ramps' kinks alias from beyond the Nyquist frequency, ten times below a gauge's
  // resolution (1e-4 of the peak), which interpolating between samples exceeds.
  constexpr double kSamePulse = 1e-5, kPeak = 1e-3;
  CHECK(worst < kSamePulse * kPeak);
}

TEST_CASE("Without dispersion a pulse is only delayed by distance over c0", "[dispersion]") {
  const DispersionTable table(kBar.poisson);
  PropagationOptions options;
  options.dispersion = false;
  Propagator p(table, kBar, options);
  const auto x = smooth_pulse(3000, 20e-6, 5e-6, 30e-6);
  const double dz = 100 * kDt * kBar.c0_m_s;  // exactly 100 samples
  const auto y = p.propagate(x, kDt, dz);
  for (std::size_t i = 100; i < x.size(); ++i) REQUIRE(y[i] == Approx(x[i - 100]).margin(1e-15));
}

TEST_CASE("The low-pass is one below the roll-off and zero from the cut-off on", "[dispersion]") {
  const DispersionTable table(kBar.poisson);
  Propagator p(table, kBar, {});
  const double f_cut = kDefaultCutoffFaOverC0 * kBar.c0_m_s / kBar.radius_m;
  CHECK(p.lowpass_gain(0.7 * f_cut) == 1.0);
  CHECK(p.lowpass_gain(0.875 * f_cut) == Approx(0.5));
  CHECK(p.lowpass_gain(1.01 * f_cut) == 0.0);
  // With amplitude factors the cut-off must stay below the m1 pole.
  PropagationOptions bad;
  bad.amplitude = AmplitudeFactor::kStrain;
  bad.cutoff_fa_over_c0 = 0.4;
  CHECK_THROWS(Propagator(table, kBar, bad));
}

TEST_CASE("Tyas-Pope factors scale a narrow-band burst by m1 (strain) and m1 m2 (stress)",
          "[dispersion]") {
  const DispersionTable table(kBar.poisson);
  const double f0 = 150e3;  // f·a/c0 ≈ 0.143: m1 ≈ 1.1, clearly above 1
  const double fa = f0 * kBar.radius_m / kBar.c0_m_s;
  const std::size_t n = 8000;
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * kDt - 300e-6;
    x[i] = std::exp(-0.5 * t * t / (100e-6 * 100e-6 / 9)) * std::cos(2 * std::numbers::pi * f0 * t);
  }
  auto peak = [](const std::vector<double>& v) {
    double m = 0;
    for (double y : v) m = std::max(m, std::abs(y));
    return m;
  };
  // Zero distance isolates the amplitude factor; the burst's band (±3.4 kHz) makes the peak
  // ratio equal to the factor at f0 within about 0.5 %.
  constexpr double kNarrowBand = 5e-3;
  for (auto [factor, expected] : {std::pair{AmplitudeFactor::kStrain, table.m1(fa)},
                                  std::pair{AmplitudeFactor::kStress, table.m1_m2(fa)}}) {
    PropagationOptions o;
    o.amplitude = factor;
    Propagator p(table, kBar, o);
    const double ratio = peak(p.propagate(x, kDt, 0.0)) / peak(x);
    CHECK(ratio == Approx(expected).epsilon(kNarrowBand));
    CHECK(std::abs(expected - 1) > 5 * kNarrowBand);  // the factor is not trivially 1 here
  }
}

TEST_CASE("Corrections sharing their FFT plans give the same pulses as with plans of their own",
          "[dispersion]") {
  const DispersionTable table = DispersionTable::up_to(kBar.poisson, kDefaultCutoffFaOverC0);
  const std::vector<double> x = smooth_pulse(6000, 50e-6, 8e-6, 100e-6);
  FftPlans shared;
  for (const double d : {1.0, -1.0, -0.5}) {  // two padded lengths: both planned once, reused
    PropagationOptions o;
    o.amplitude = AmplitudeFactor::kStrain;
    Propagator own(table, kBar, o), sharing(table, kBar, o, &shared);
    CHECK(own.propagate(x, kDt, d) == sharing.propagate(x, kDt, d));
  }
}

}  // namespace tests_dispersion_test_propagation

namespace tests_dispersion_test_propagation {

// A PMMA-like bar, 20 mm, instantaneous modulus E0 = 5.7 GPa at 1190 kg/m³, with one Maxwell arm.
BarWaveguide polymer_bar(double relaxed_fraction, double relaxation_time_s) {
  BarWaveguide w{0.01, std::sqrt(5.7e9 / 1190), 0.35};
  w.long_term_fraction = relaxed_fraction;
  w.arms = {{1 - relaxed_fraction, relaxation_time_s}};
  return w;
}

double peak(const std::vector<double>& x) {
  double p = 0;
  for (double v : x) p = std::max(p, std::abs(v));
  return p;
}

TEST_CASE(
    "A viscoelastic bar's pulse: its front at c0, back where it came from, and the relaxed "
    "and unrelaxed limits of its velocity and stress",
    "[dispersion][polymer]") {
  PropagationOptions o;
  o.dispersion = false;  // the law's own propagation only
  SECTION("causal at the instantaneous wave speed, and back again") {
    const BarWaveguide bar = polymer_bar(0.5, 20e-6);
    Propagator p(bar, o);
    const auto x = smooth_pulse(20000, 100e-6, 5e-6, 60e-6);
    const double d = 0.5;
    const auto there = p.propagate(x, kDt, d);
    // Nothing arrives before the front, which travels at c0 (the transform's leakage aside).
    const auto front = static_cast<std::size_t>((100e-6 + d / bar.c0_m_s) / kDt) - 20;
    double before = 0;
    for (std::size_t i = 0; i < front; ++i) before = std::max(before, std::abs(there[i]));
    constexpr double kLeakage = 1e-3;  // of the pulse's peak
    CHECK(before < kLeakage * peak(x));
    CHECK(peak(there) < 0.9 * peak(x));  // attenuated: the test can fail
    const auto back = p.propagate(there, kDt, -d);
    std::vector<double> err(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) err[i] = back[i] - x[i];
    constexpr double kRoundTrip = 1e-6;  // no cut-off: only round-off and the end tapers
    CHECK(rms(err) / rms(x) < kRoundTrip);
  }
  SECTION("a pulse slow against the arm meets the relaxed modulus, a fast one the instantaneous") {
    constexpr double kRelaxed = 0.5;
    // Slow: 200 µs ramps and a 600 µs plateau against τ = 2 µs: stress E∞ ε, velocity c∞ ε.
    // Fast: a 40 µs pulse against τ = 1 s: the law has no time to relax, E0 ε and c0 ε.
    for (const auto& [tau, expected_stress, expected_velocity] :
         {std::tuple{2e-6, kRelaxed, std::sqrt(kRelaxed)}, std::tuple{1.0, 1.0, 1.0}}) {
      const bool slow = tau < 1e-3;
      const auto x = slow ? smooth_pulse(20000, 100e-6, 200e-6, 600e-6)
                          : smooth_pulse(4000, 50e-6, 5e-6, 30e-6);
      for (const auto& [quantity, expected] :
           {std::pair{WaveQuantity::kForce, expected_stress},
            std::pair{WaveQuantity::kVelocity, expected_velocity}}) {
        PropagationOptions q = o;
        q.quantity = quantity;
        Propagator p(polymer_bar(kRelaxed, tau), q);
        const auto y = p.propagate(x, kDt, 0.0);
        constexpr double kLimit = 0.01;  // the limits hold to the ratio of the times, ≤ 1 %
        INFO("tau " << tau << " quantity " << static_cast<int>(quantity));
        CHECK(peak(y) / peak(x) == Approx(expected).epsilon(kLimit));
      }
    }
  }
}

}  // namespace tests_dispersion_test_propagation

namespace tests_dispersion_test_propagation {

TEST_CASE("A viscoelastic bar whose arms vanish disperses as the elastic bar",
          "[dispersion][polymer]") {
  // The law's path with the Pochhammer–Chree correction: arms of 10⁻⁹ of the modulus leave the
  // geometry's dispersion alone, which the elastic path computes on its own.
  BarWaveguide polymer = kBar;
  polymer.long_term_fraction = 1 - 1e-9;
  polymer.arms = {{1e-9, 20e-6}};
  const DispersionTable table(kBar.poisson);
  const auto x = smooth_pulse(4000, 60e-6, 8e-6, 40e-6);
  for (const auto amplitude : {AmplitudeFactor::kNone, AmplitudeFactor::kStress}) {
    PropagationOptions o;
    o.amplitude = amplitude;
    const auto elastic = Propagator(table, kBar, o).propagate(x, kDt, 1.0);
    const auto law = Propagator(table, polymer, o).propagate(x, kDt, 1.0);
    std::vector<double> err(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) err[i] = law[i] - elastic[i];
    constexpr double kSame = 1e-6;  // the arms' 10⁻⁹ and round-off
    CHECK(rms(err) / rms(x) < kSame);
  }
}

}  // namespace tests_dispersion_test_propagation

namespace tests_dispersion_test_propagation {

TEST_CASE("A polymer bar's law is read up to its phase velocity at the cut-off",
          "[dispersion][polymer]") {
  // f·a over the phase velocity is what the first mode's table is read at: an elastic bar's
  // cut-off itself; a law relaxed over the whole band (τ = 1 ns) at its static speed c0 √e∞; a
  // law glassy over it (τ = 1 s) at c0, however soft its static modulus.
  constexpr double kCut = kDefaultCutoffFaOverC0;
  CHECK(kBar.mode_reach(kCut) == kCut);
  constexpr double kBandEdge = 1e-3;  // ωτ at the cut-off, 4·10⁻⁴ and 1/(4·10⁵): e within that
  CHECK(polymer_bar(0.5, 1e-9).mode_reach(kCut) ==
        Approx(kCut / std::sqrt(0.5)).epsilon(kBandEdge));
  CHECK(polymer_bar(0.5, 1.0).mode_reach(kCut) == Approx(kCut).epsilon(kBandEdge));
}

TEST_CASE("A polymer bar's band limit is where moving a pulse back grows it kMaxLawGain times",
          "[dispersion][polymer]") {
  // One Maxwell arm (a standard linear solid): a harmonic wave e^{i(ωt − kz)}, k = ω/c*,
  // c* = c0 √(e∞ + e1 iωτ/(1 + iωτ)), grows by e^{−Im k |Δz|} moved back by Δz; its limit
  // −Im k → α∞ = e1/(2 τ c0) = 5.7 /m for e1 = 0.5, τ = 20 µs.
  const BarWaveguide bar = polymer_bar(0.5, 20e-6);
  const double alpha_inf = 0.5 / (2 * 20e-6 * bar.c0_m_s);
  auto growth = [&](double f, double d) {
    const std::complex<double> iwt(0, 2 * std::numbers::pi * f * 20e-6);
    const auto c = bar.c0_m_s * std::sqrt(0.5 + 0.5 * iwt / (1.0 + iwt));
    return std::exp(-(2 * std::numbers::pi * f / c).imag() * d);
  };
  // 0.5 m: at most e^{α∞ 0.5} = 17: nothing is cut.
  CHECK(std::exp(alpha_inf * 0.5) < kMaxLawGain);
  CHECK(std::isinf(law_band_limit_Hz(bar, -0.5)));
  // 2 m: up to e^{11.4}; the limit lies where the growth reaches kMaxLawGain.
  const double f = law_band_limit_Hz(bar, -2.0);
  REQUIRE(std::isfinite(f));
  constexpr double kBisection = 1e-6;  // the search stops within 10⁻⁹ of the frequency
  CHECK(growth(f, 2.0) == Approx(kMaxLawGain).epsilon(kBisection));
  // An elastic bar grows nothing.
  CHECK(std::isinf(law_band_limit_Hz(kBar, -2.0)));
}

}  // namespace tests_dispersion_test_propagation
