#pragma once
// Checks of the recorded signals before a reduction: a record clipped by its amplifier or
// digitizer, too short, or one channel read twice; a gauge's record from its rest level, turned
// when its first pulse has the other polarity; a pulse too long for its round trip (a clock read
// in the wrong unit).
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "analysis/gauge_signals.hpp"
#include "analysis/kolsky_setup.hpp"
#include "analysis/pulse_window.hpp"

namespace shpb {

// A record clipped by its amplifier or digitizer piles up at its extreme level: every sample the
// range cut off lands there, so the level holds at least kClippedPileUp times as many samples as
// the next level inward, and at least kClippedRun of them follow one another. A digitized smooth
// top can do the same (docs/methods.md §9, "A clipped channel"): within one step q it dwells for
// about 2√(2q/κ) samples at curvature κ, so a top whose widths at the next two levels down fit one
// parabola with it is no clip; one that stays flat longer is clipped only when the record's noise
// σ (its baseline's, less the rounding q/√12) could not have held an unclipped signal in one step
// for that run: a sample falls in a step with probability at most P = erf(q/(2√2 σ)), so the run
// of n has at most (N − n + 1) Pⁿ < kClipFalseAlarm. Else it may be clipped (a flat plateau below
// the noise of a step reads the same as a clip): said, not assumed. A record on no grid (computed
// or in floating point) repeats a value at its extreme only when cut. A stated full scale
// (measurement.channels[].range, GaugeSignals::ranges) settles it: an extreme within
// kRangeSteps steps of it is clipped, pile-up or not, and one further inside is not.
// Also warns of a record too short to hold a pulse (fewer than kMinRecordSamples samples,
// core/time_series.hpp), and of
// two gauges whose records are the same up to a scale (one channel read twice, or exported under
// two names): two gauges on a bar record different pulses at different times, each with its own
// noise, so their correlation over a whole record is nowhere near 1 − kCopiedChannelCorrelation,
// which a copy scaled by another bridge factor reaches to round-off.
inline constexpr std::size_t kClippedRun = 5;
inline constexpr double kClippedPileUp = 2.0;
// The chance that an unclipped record's noise holds it on one level as long as its run, above
// which a pile-up is only "may be clipped": one record in a thousand.
inline constexpr double kClipFalseAlarm = 1e-3;
// A digitizer's top code lies a step below its full scale (2^(b−1) − 1 of 2^(b−1) steps), and a
// rounding of half a step more: a level within 1½ steps of the stated range is at it.
inline constexpr double kRangeSteps = 1.5;
// The same for a record on no grid: the 6 printed significant digits of an export.
inline constexpr double kRangePrinted = 1e-6;
inline constexpr double kCopiedChannelCorrelation = 1e-9;
std::vector<std::string> signal_warnings(const GaugeSignals& signals);
// The extreme levels at which a record looks clipped by the rule above (the upper one first; each
// with its longest run there, where it starts, and the counts at that level and the next one
// inward): none, one or both (a range exceeded both ways, by pulses of both signs). `established`:
// clipped; else it may be.
struct ClippedLevel {
  double level = 0;
  std::size_t run = 0, run_start = 0, at_level = 0, at_next = 0;
  bool established = false;
};
using FullScale = std::optional<std::array<double, 2>>;  // [low, high], GaugeSignals::ranges
std::vector<ClippedLevel> clipped_levels(const std::vector<double>& x, const FullScale& range = {});
// A clipped record's samples at its clip levels, and those levels in the units of the record as it
// is used (`from_rest`: the same record less its rest level, turned as its pulses are). The strain
// there reached at least the level: a bound, not a value (fit and calibrate read it so: a
// censored measurement, Tobit 1958).
struct ClippedSamples {
  std::optional<double> upper, lower;  // from rest: the strain reached at least / at most these
  std::vector<signed char> at;         // +1 at the upper level, −1 at the lower, 0 a value
  double noise = 0;  // the record's noise σ (its quiet start's, estimate_baseline)
  // Sample i's residual, model − measured for a value; at a clip level the censored one whose
  // square is −2 ln P(the strain reached the level | the model), P = Φ(±(model − level)/σ)
  // (Tobit 1958): −σ √(−2 ln P), 0 well beyond the level, model − level well short of it (the
  // noiseless limit: 0 beyond, model − level short). With the derivative by the model.
  struct Residual {
    double value = 0, slope = 1;
  };
  Residual residual(std::size_t i, double model, double measured) const;
  // x as the clipped channel records it.
  double clip(double x) const {
    if (upper && x > *upper) return *upper;
    if (lower && x < *lower) return *lower;
    return x;
  }
};
// nullopt when no level of `raw` is established as clipped.
std::optional<ClippedSamples> clipped_samples(const std::vector<double>& raw,
                                              const std::vector<double>& from_rest,
                                              const FullScale& range = {});

// A gauge record from its rest level (rest_signal): less its baseline (estimate_baseline: a
// bridge's offset is no strain), with its first pulse (find_first_pulse). A record whose first
// pulse has the other sign than `expected_sign` (−1: a compression test's, +1: a tension test's) is
// turned over (a bridge wired the other way, docs/commands.md `process`); 0 keeps the record's sign
// (a calibration shot, a bars-together check). Used by `process`, `compare`, `fit` and `calibrate`.
struct RestSignal {
  std::vector<double> x;
  double noise = 0;                  // the baseline's
  std::optional<PulseWindow> first;  // in x, after any turn; nullopt: nothing above the noise
  bool inverted = false;
  RecordStart start;  // how the record starts (record_start)
};

// A record that starts on its first pulse's front (record_start's on_front), or holds
// fewer than kMinRestSamples before its first pulse (a scope's pre-trigger shorter than that;
// where no pulse rises above the noise of its first samples, the pulse against record_start's), or
// starts inside a pulse (record_start's moves_away; rest_elsewhere) has no rest level to read: its
// offset, its polarity and every strain read from them would be the pulse's own (a compressive
// pulse turned over as tensile; on a front, a "noise" so large that no pulse rises above it).
// Refused, exit 2, before a missing pulse is.
void require_rest_before_pulse(const GaugeSignals& signals, const std::string& gauge,
                               const RestSignal& s, const std::string& scene_file);

// `gauge`'s record from its rest level, refused where it has none to read
// (require_rest_before_pulse): how every command reads a measured gauge's record.
RestSignal rest_signal(const GaugeSignals& signals, const std::string& gauge, double expected_sign,
                       const std::string& scene_file);

// What a turned record's gauge is told.
std::string inverted_gauge_warning(const std::string& gauge, bool tension);

// An incident pulse lasting more than this many round trips of its gauge to the specimen and back
// (2d/c0, when its reflection reaches the gauge) would be overlapped by its own reflection many
// times over: no Kolsky record, but a clock read in the wrong unit (a column in ms read as s makes
// every pulse 1000 times longer, which the sample-interval range lets through at 10 MS/s).
inline constexpr double kMaxPulseRoundTrips = 10;
// Refuses (InputError at measurement.time.unit) an incident pulse of `pulse_s` at its gauge longer
// than that. Used by `process`, `compare` and `fit`.
void require_pulse_fits_round_trip(const KolskySetup& setup, double pulse_s,
                                   const std::string& scene_file);
// The same rule for any `pulse` of `gauge` against a round trip of `round_trip_s`, described by
// `round_trip` (a printf format of that time, e.g. "2L/c0 = %.3g s of its bar"): `calibrate`'s
// first pulse against its struck bar's round trip.
void require_pulse_fits_round_trip(const std::string& gauge, const std::string& pulse,
                                   double pulse_s, double round_trip_s,
                                   const std::string& round_trip, const std::string& scene_file);

}  // namespace shpb
