#pragma once
// Finding a pulse in a gauge record: baseline and noise from the quiet start of the record, onset
// where the signal leaves the noise before its first large excursion, end where it comes back.
#include <cstddef>
#include <optional>
#include <span>

namespace shpb {

// The fewest samples a rest level is read from: estimate_baseline's smallest quiet segment, and
// what a record must hold at rest before its first pulse (require_rest_before_pulse).
inline constexpr std::size_t kMinRestSamples = 10;

struct Baseline {
  double level = 0;  // median of the quiet segment (of grouped data on a grid: grid_median)
  // 1.4826 × median absolute deviation (σ of Gaussian noise); for a digitized record whose quiet
  // segment reads mostly one level (MAD 0), from the share of samples off it and the rounding
  // error q/√12 of its step (quantization_step); for one whose quiet segment spreads over a few
  // levels, their standard deviation (the MAD, a whole number of steps, misreads it by up to 40 %).
  double noise = 0;
  double step = 0;  // the record's grid step q (quantization_step), 0 on none
};

// Baseline from the first `fraction` of the record (at least 10 samples: baseline_samples). The
// level is the segment's median; on a digitizer's grid (quantization_step) the median of grouped
// data, interpolated between the levels, which does not snap to one of them.
Baseline estimate_baseline(std::span<const double> x, double fraction = 0.05);
std::size_t baseline_samples(std::size_t record, double fraction = 0.05);

// The step q of the grid every sample of x lies on (a digitizer's least significant bit, or an
// export's fixed decimals, times the channel's scale; each value to within the rounding of its 6
// printed significant digits), or 0 when the values lie on no grid of at most 2^24 levels (a
// record recorded or computed in floating point).
double quantization_step(std::span<const double> x);

// Standard deviation of a rest level taken as the median of `samples` samples of white noise of
// standard deviation `noise`: √(π/2) noise/√samples (the median's asymptotic variance). Its error
// is an offset common to every sample later read from that level.
double rest_level_sd(double noise, std::size_t samples);

// The median of x's first `samples` (the record before a pulse, rest_samples_before; up to its
// half-height sample while its onset is not known): the rest level from the whole record before
// the pulse; nullopt when there are fewer samples than estimate_baseline's smallest segment holds.
// On a digitizer's grid, interpolated between its levels as estimate_baseline's.
std::optional<double> rest_level_before(std::span<const double> x, std::size_t samples);

struct PulseWindow {
  std::size_t onset = 0;  // first sample of the pulse
  std::size_t end = 0;    // one past its last sample
  std::size_t half = 0;   // its first sample at half its height
  double sign = -1;       // −1 compressive (strain < 0), +1 tensile
  double peak = 0;        // largest |x − baseline| inside the window
};

// The samples before pulse w that are at rest: those before its onset less one rise (onset to
// half height), at most half of them (a slow transmitted pulse's rise can outlast the rest before
// it, and the level is read from the whole rest for a record settling after its trigger, as
// tests/app/test_compare.cpp checks), and at least kMinRestSamples where the onset leaves that
// many (a sharp front after a short pre-trigger: 10 to 15 samples of rest before a 16-sample rise
// at 100 MS/s, whose foot within the band is a sample or two). Never past the onset: up to its
// half-height sample the median took the rise's samples, all on the pulse's side, and moved the
// level towards the pulse by about n_rise/(2N) √(2π) σ, an offset common to every sample read
// from it that a noise-free record does not show (docs/validation.md, "shpb fit": the Al 6061
// campaign's B 0.5 % low from the noise before the pulses alone), and after a short rest by the
// rise itself (8 % of the peak after 10 samples of rest).
std::size_t rest_samples_before(const PulseWindow& w);

// The band within which a record counts as at rest around a pulse of this peak: max(5σ, 3 % of the
// peak). A pulse is one that rises beyond twice it.
double rest_band(double noise, double peak);

// The least peak of a pulse that follows one of peak `previous_peak` on the same record (the
// reflected pulse after the incident one): twice the band that pulse ended within. A smaller one
// (the incident pulse's ringing tail, or the next to nothing a specimen matched to the bar
// reflects, docs/methods.md §6) cannot be told from that tail.
double following_pulse_min_peak(double noise, double previous_peak);

// The first large pulse of either sign in x − baseline.level: it starts at the first sample beyond
// half the record's largest excursion; the onset is the last sample before that within the
// noise band (max(5σ, 3 % of the peak)), the end the first sample after the pulse's last
// half-peak crossing back inside that band. nullopt if nothing rises above the noise.
std::optional<PulseWindow> find_first_pulse(std::span<const double> x, const Baseline& baseline,
                                            std::size_t from = 0);

// How a record starts. One that starts on its first pulse's front (a scope triggered late on a slow
// rise: a shaped pulse, a polymer bar's) has no rest to read: its first samples are the rise, and
// the baseline read from them is a level on the front with the rise's spread as its "noise". Told
// from a record at rest by the samples before that pulse's onset (the pulse found against the
// median of the first kMinRestSamples, with the noise of the successive differences, which a trend
// leaves): the median of their last third exceeds that of their first third towards the pulse by
// more than kFrontTrendSigmas times what the noise explains, at least kFrontRateFraction of the
// rate at which the pulse goes on rising from its onset to half height (or to its front's first
// top, where the front stops below half height: a pulse shaper's elastic step), and through the
// middle third too (its median at least kFrontEvenness of that change from either end's). A rest's
// level does not move towards its pulse at the pulse's own rate: a drift or an amplifier's
// settling, within the rest band over those samples, runs at a small fraction of it
// (docs/methods.md §6, "From gauges to faces").
struct RecordStart {
  // The first pulse against the median of the first kMinRestSamples, with the noise σ of the
  // successive differences (1.4826 × their MAD / √2; on a grid at least its rounding's q/√12).
  std::optional<PulseWindow> first;
  double noise = 0;
  bool on_front = false;  // by the rule above
  // The level's change across the samples before that onset towards the pulse (from the median of
  // their first third to that of their last), and their mean slope over the rise's.
  double change = 0, rate_fraction = 0;
  // The samples before that onset move away from the pulse (−change) beyond its rest band
  // (rest_band) and beyond kFrontTrendSigmas times what the noise explains: the record starts on
  // another pulse, going on (a pulse shaper's ramp the record started partway down, its end
  // coming back through the start level taken for the first pulse). A rest's drift or an
  // amplifier's settling stays within the band.
  bool moves_away = false;
};
RecordStart record_start(std::span<const double> x, double step);  // step: quantization_step

// A record that starts inside a pulse — high up its front or on its plateau, past what
// record_start tells — reads that pulse's level as its rest: its "first pulse" is the pulse's end,
// back to the true rest, where the record then rests between and after its later pulses. A
// record at rest comes back to its start level after its first pulse and spends most of the rest
// of the record there; one that started inside a pulse never does. Told by the level `x` (from
// its start level) holds longest from the first pulse's onset on (the most samples within the
// rest band, rest_band(noise, first.peak), of one level): where that level lies at least
// kRestElsewhereFraction of the first pulse's peak from the start level, the record reaches it
// from the start in one step (not beyond it by as much first: a pulse that peaks and then settles
// there, as a polymer bar's creep after its pulse does, is a pulse) and rests there
// (kMinRestSamples in a row within the band) before and after a later pulse that leaves it by as
// much, the start lay on a pulse of that height. A rest's own drift or a plateau's ringing
// stays well inside a quarter of the peak; a record started inside its pulse rests the pulse's
// height A from its start, and its later pulse (a reflection, of R ≤ A) reaches that level's
// first peak A + R, so A ≥ half of it and R ≥ a quarter of it for R ≥ A/3.
inline constexpr double kRestElsewhereFraction = 0.25;
struct RestElsewhere {
  double level = 0;                  // from the start level
  std::size_t first = 0, again = 0;  // where the record rests there, before and after a pulse
};
std::optional<RestElsewhere> rest_elsewhere(std::span<const double> x, const PulseWindow& first,
                                            double noise);

// Onset of a pulse of the given sign in [from, to), the same way, and its first half-peak
// sample (onset to half is the front's rise); nullopt if none, or if its peak is not above
// min_peak.
struct Onset {
  std::size_t onset = 0;
  std::size_t half = 0;
};
std::optional<Onset> find_onset(std::span<const double> x, const Baseline& baseline, double sign,
                                std::size_t from, std::size_t to, double min_peak = 0);

// Median over the samples of x[begin, end) that are at least half of their 95th percentile
// (times sign): the plateau of a pulse, insensitive to its ramps and to single spikes.
double plateau_level(std::span<const double> x, std::size_t begin, std::size_t end, double sign);

}  // namespace shpb
