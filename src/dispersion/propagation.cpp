#include "dispersion/propagation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "core/interpolation.hpp"
#include "core/interrupt.hpp"

namespace shpb {
namespace {

// The end taper spans at most this many periods of the low-pass cut-off (docs/methods.md §5).
constexpr double kTaperPeriods = 4;
// A viscoelastic bar's transform is padded by this many of its slowest relaxation times (the
// wrapped tail of its kernel then weighs e^−7 < 0.1 % of that arm), but by at most this many record
// lengths: an arm slower than that is nearly flat over the transform's period P, and its wrapped
// tail adds about E_k/E0 × (the pulse's length over P) ≤ 1 % of that arm to the pulse, where
// padding by 7 τ would cost seconds per move of a 1 s arm (docs/methods.md §5.1).
constexpr double kLawMemorySpans = 7;
constexpr double kLawMemoryRecords = 8;
// The frequencies up to a cut-off at which a law's mode reach is bounded: its phase velocity rises
// with frequency (a completely monotone relaxation), so each interval's f·a over the phase velocity
// is at most its upper frequency's f·a over its lower frequency's phase velocity.
constexpr int kReachIntervals = 256;

// 1 below `start`, 0 from `end`, a raised cosine between.
double raised_cosine(double x, double start, double end) {
  if (x <= start) return 1.0;
  if (x >= end) return 0.0;
  const double s = (x - start) / (end - start);
  return 0.5 * (1 + std::cos(std::numbers::pi * s));
}

}  // namespace

std::complex<double> BarWaveguide::relative_modulus(double omega) const {
  std::complex<double> e = long_term_fraction;
  for (const RelaxationArm& a : arms) {
    const std::complex<double> iwt(0, omega * a.relaxation_time_s);
    e += a.fraction * iwt / (1.0 + iwt);
  }
  return e;
}

double BarWaveguide::slowest_speed_fraction() const {
  return viscoelastic() ? std::sqrt(long_term_fraction) : 1.0;
}

double BarWaveguide::mode_reach(double cutoff_fa_over_c0) const {
  if (!viscoelastic()) return cutoff_fa_over_c0;
  // c0/c_phase at f·a/c0 = x: Re(1/√(E*/E0)).
  auto slowness = [&](double x) {
    return (1.0 / std::sqrt(relative_modulus(2 * std::numbers::pi * x * c0_m_s / radius_m))).real();
  };
  double reach = 0;
  for (int j = 0; j < kReachIntervals; ++j) {
    const double lo = cutoff_fa_over_c0 * j / kReachIntervals;
    reach = std::max(reach, cutoff_fa_over_c0 * (j + 1) / kReachIntervals * slowness(lo));
  }
  return reach;
}

double BarWaveguide::attenuation_per_m(double omega) const {
  if (!viscoelastic()) return 0;
  return -omega * (1.0 / (c0_m_s * std::sqrt(relative_modulus(omega)))).imag();
}

double law_band_limit_Hz(const BarWaveguide& bar, double distance_m) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  if (!bar.viscoelastic() || distance_m == 0) return kInfinity;
  // The attenuation rises with frequency to α∞ = Σ(E_k/τ_k)/(2 E0 c0), reached well above the
  // fastest arm's 1/τ: a growth that stays within the limit there never passes it.
  const double exponent = std::log(kMaxLawGain) / std::abs(distance_m);
  double tau_min = kInfinity;
  for (const RelaxationArm& a : bar.arms) tau_min = std::min(tau_min, a.relaxation_time_s);
  auto beyond = [&](double f) {
    return bar.attenuation_per_m(2 * std::numbers::pi * f) > exponent;
  };
  constexpr double kFarAboveFastestArm = 1e6;  // ωτ: α within 10⁻¹² of α∞
  double hi = 1 / (2 * std::numbers::pi * tau_min);
  while (!beyond(hi)) {
    if (hi * 2 * std::numbers::pi * tau_min > kFarAboveFastestArm) return kInfinity;
    hi *= 2;
  }
  double lo = 0;
  for (int i = 0; i < 100 && hi - lo > 1e-9 * hi; ++i)
    (beyond(0.5 * (lo + hi)) ? hi : lo) = 0.5 * (lo + hi);
  return hi;
}

double mode_reach(const BarWaveguide& bar, const PropagationOptions& options) {
  return bar.mode_reach(
      std::min(options.cutoff_fa_over_c0, options.law_cutoff_Hz * bar.radius_m / bar.c0_m_s));
}

Propagator::Propagator(const DispersionTable& table, const BarWaveguide& bar,
                       const PropagationOptions& options, FftPlans* plans)
    : table_(&table), bar_(bar), options_(options), shared_plans_(plans) {
  if (!(bar.radius_m > 0) || !(bar.c0_m_s > 0))
    throw std::invalid_argument("Propagator: bar radius and c0 must be > 0");
  const double pole = table.m1_pole_normalized_frequency();
  const double reach = mode_reach(bar, options_);
  if (options_.dispersion && options_.amplitude != AmplitudeFactor::kNone && pole > 0 &&
      reach >= pole)
    throw std::invalid_argument("Propagator: the cut-off must lie below the pole of m1");
  if (reach > table.max_normalized_frequency())
    throw std::invalid_argument("Propagator: cut-off beyond the dispersion table");
}

Propagator::Propagator(const BarWaveguide& bar, const PropagationOptions& options)
    : table_(nullptr), bar_(bar), options_(options), shared_plans_(nullptr) {
  if (!(bar.radius_m > 0) || !(bar.c0_m_s > 0))
    throw std::invalid_argument("Propagator: bar radius and c0 must be > 0");
  if (options_.dispersion)
    throw std::invalid_argument("Propagator: a dispersion correction needs the mode's table");
}

double Propagator::lowpass_gain(double f) const {
  const double fa = f * bar_.radius_m / bar_.c0_m_s;
  const double cut = options_.cutoff_fa_over_c0;
  return raised_cosine(fa, (1 - options_.rolloff_fraction) * cut, cut);
}

double Propagator::law_gain(double f) const {
  const double cut = options_.law_cutoff_Hz;
  return raised_cosine(f, (1 - options_.rolloff_fraction) * cut, cut);
}

// A harmonic wave e^{i(ωt − kz)} in a 1D bar of complex modulus E*(ω): k = ω/c*, c* = sqrt(E*/ρ)
// = c0 sqrt(E*/E0), so moving it by Δz multiplies it by exp(−iωΔz/c*) (attenuated by Im(1/c*) < 0
// going forward, grown going back: at most by exp(α∞|Δz|), α∞ the attenuation's high-frequency
// limit, so the inverse needs no cut-off). Its particle velocity is −c* ε and its stress E* ε
// (Bacon 1998; Zhao & Gary 1995). With the Pochhammer–Chree correction the phase velocity is also
// scaled by the first mode's c/c0 at f·a over the law's phase velocity.
std::complex<double> Propagator::viscoelastic_transfer(double f, double distance_m) const {
  const double omega = 2 * std::numbers::pi * f;
  const std::complex<double> e = bar_.relative_modulus(omega);
  const std::complex<double> s = std::sqrt(e);  // c*/c0, Im ≥ 0: a passive law attenuates
  std::complex<double> slowness = 1.0 / (bar_.c0_m_s * s);
  double amplitude = law_gain(f);
  if (options_.dispersion) {
    amplitude *= lowpass_gain(f);
    const double fa = f * bar_.radius_m * slowness.real();
    slowness = {slowness.real() / table_->phase_velocity(fa), slowness.imag()};
    if (options_.amplitude == AmplitudeFactor::kStrain) amplitude *= table_->m1(fa);
    if (options_.amplitude == AmplitudeFactor::kStress) amplitude *= table_->m1_m2(fa);
  }
  std::complex<double> factor = amplitude;
  if (options_.quantity == WaveQuantity::kVelocity) factor *= s;
  if (options_.quantity == WaveQuantity::kForce) factor *= e;
  return factor * std::exp(std::complex<double>(0, -omega * distance_m) * slowness);
}

// The slowest phase velocity below the cut-off; a viscoelastic bar's is its static one.
double Propagator::slowest_speed_m_s() const {
  return (options_.dispersion ? table_->phase_velocity(options_.cutoff_fa_over_c0) : 1.0) *
         bar_.c0_m_s * bar_.slowest_speed_fraction();
}

// Over 2 % of the record but at most kTaperPeriods periods of the cut-off: the ramp's own
// spectrum then lies below the cut-off (no ringing), and a long record's pulse near its start (a
// short pre-trigger) is never under it; over 2 % of a 100 000-sample record the taper scaled such
// a pulse down unseen.
std::size_t Propagator::taper_samples(std::size_t samples, double dt) const {
  const double cutoff_period_samples =
      bar_.radius_m / (options_.cutoff_fa_over_c0 * bar_.c0_m_s * dt);
  return std::min(static_cast<std::size_t>(options_.taper_fraction * static_cast<double>(samples)),
                  static_cast<std::size_t>(std::ceil(kTaperPeriods * cutoff_period_samples)));
}

double Propagator::end_reach_s(std::size_t samples, double dt, double distance_m) const {
  if (!options_.dispersion) return 0;
  const double c = table_->phase_velocity(options_.cutoff_fa_over_c0) * bar_.c0_m_s;
  return static_cast<double>(taper_samples(samples, dt)) * dt +
         std::abs(distance_m) * (1 / c - 1 / bar_.c0_m_s);
}

void Propagator::propagate(std::span<const double> signal, double dt, double distance_m,
                           std::span<double> out, double delay_s) {
  const std::size_t n = signal.size();
  if (out.size() != n) throw std::invalid_argument("propagate: output length differs");
  if (n == 0) return;
  const bool law = bar_.viscoelastic();
  if (!options_.dispersion && !law) {
    delay_by_interpolation(signal, distance_m / (bar_.c0_m_s * dt) + delay_s / dt, out);
    return;
  }
  // Padding: room for the largest delay of any passed component plus a quarter record, so
  // nothing wraps into the kept samples.
  const double c_min = slowest_speed_m_s();
  const auto shift = static_cast<std::size_t>(
      std::ceil(std::abs(distance_m) / (c_min * dt) + std::abs(delay_s) / dt));
  // A law's transfer remembers as long as its slowest arm: its kernel's tail, wrapped around the
  // transform, falls to e^−kLawMemorySpans of the arm within this much padding.
  double memory_s = 0;
  for (const RelaxationArm& a : bar_.arms) memory_s = std::max(memory_s, a.relaxation_time_s);
  const auto memory = static_cast<std::size_t>(std::min(
      kLawMemorySpans * memory_s / dt, kLawMemoryRecords * static_cast<double>(n + shift)));
  const std::size_t size = fast_fft_size(n + shift + n / 4 + 16 + memory);
  RealFft& fft = (shared_plans_ ? *shared_plans_ : own_plans_).of_size(size);

  std::span<double> x = fft.samples();
  std::copy(signal.begin(), signal.end(), x.begin());
  std::fill(x.begin() + static_cast<std::ptrdiff_t>(n), x.end(), 0.0);
  // Cosine taper of both ends: the record need not start or end at zero.
  const std::size_t taper = taper_samples(n, dt);
  for (std::size_t i = 0; i < taper; ++i) {
    const double w = 0.5 * (1 - std::cos(std::numbers::pi * (static_cast<double>(i) + 0.5) /
                                         static_cast<double>(taper)));
    x[i] *= w;
    x[n - 1 - i] *= w;
  }
  throw_if_interrupted();  // between transforms of a long record
  fft.forward();
  std::span<std::complex<double>> spec = fft.spectrum();
  const double df = 1.0 / (static_cast<double>(size) * dt);
  const double fa_per_hz = bar_.radius_m / bar_.c0_m_s;
  if (law) {  // every bin, the static one too: the law's static modulus scales a velocity or force
    for (std::size_t j = 0; j < spec.size(); ++j) {
      const double f = static_cast<double>(j) * df;
      if ((options_.dispersion && lowpass_gain(f) == 0) || law_gain(f) == 0) {
        std::fill(spec.begin() + static_cast<std::ptrdiff_t>(j), spec.end(), 0.0);
        break;
      }
      spec[j] *= viscoelastic_transfer(f, distance_m);
      if (delay_s != 0) spec[j] *= std::polar(1.0, -2 * std::numbers::pi * f * delay_s);
    }
  }
  for (std::size_t j = 1; j < spec.size() && !law; ++j) {
    const double f = static_cast<double>(j) * df;
    const double gain = lowpass_gain(f);
    if (gain == 0) {  // at the cut-off: this bin and every one above it
      std::fill(spec.begin() + static_cast<std::ptrdiff_t>(j), spec.end(), 0.0);
      break;
    }
    const double fa = f * fa_per_hz;
    const double c = table_->phase_velocity(fa) * bar_.c0_m_s;
    double amplitude = gain;
    if (options_.amplitude == AmplitudeFactor::kStrain) amplitude *= table_->m1(fa);
    if (options_.amplitude == AmplitudeFactor::kStress) amplitude *= table_->m1_m2(fa);
    const double phase =
        -2 * std::numbers::pi * f * distance_m / c - 2 * std::numbers::pi * f * delay_s;
    spec[j] *= std::polar(amplitude, phase);
  }
  fft.inverse();
  std::copy(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(n), out.begin());
}

std::vector<double> Propagator::propagate(std::span<const double> signal, double dt,
                                          double distance_m) {
  std::vector<double> out(signal.size());
  propagate(signal, dt, distance_m, out);
  return out;
}

std::vector<double> propagate(std::span<const double> signal, double dt, double distance_m,
                              const BarWaveguide& bar, const PropagationOptions& options) {
  const DispersionTable table(bar.poisson);
  Propagator p(table, bar, options);
  return p.propagate(signal, dt, distance_m);
}

void delay_by_interpolation(std::span<const double> signal, double delay, std::span<double> out) {
  // out(t_i) = in(t_i − delay), zero outside the record.
  for (std::size_t i = 0; i < signal.size(); ++i)
    out[i] = sample_at(signal, static_cast<double>(i) - delay, 0.0, 0.0);
}

}  // namespace shpb
