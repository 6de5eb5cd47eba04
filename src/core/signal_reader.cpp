#include "core/signal_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "core/csv_writer.hpp"
#include "core/error.hpp"
#include "core/interpolation.hpp"
#include "core/median.hpp"
#include "core/number_format.hpp"
#include "core/signal_formats.hpp"
#include "core/signal_spreadsheet.hpp"

namespace shpb {
namespace {

// A sampling step may differ from the mean interval by this fraction (time stamps printed with
// a few digits) before the time base counts as non-uniform.
constexpr double kUniformStepTolerance = 0.02;
// A least-squares interval within this fraction of a round value (1, 2, 2.5, 4, 5, 8 × 10^k s)
// is snapped to it: the stamps were rounded, the clock was not.
constexpr double kRoundIntervalTolerance = 5e-3;
// Stamps within this fraction of the interval of their least-squares line are a uniform clock
// printed with too few digits (a 3 MHz record in µs to one decimal steps 0.3, 0.3, 0.4 µs): a
// rounding to q moves a stamp by at most q/2, a quarter of the interval for q up to half of it,
// while a missing or extra sample leaves stamps half an interval or more off any line.
constexpr double kRoundedStampFraction = 0.25;

SignalFormat detect(const DelimitedText& text) {
  auto ext = text.file.extension().string();
  for (auto& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (ext == ".raw") return SignalFormat::kLanlRaw;
  if (!text.rows.empty() && !text.rows[0].fields.empty() &&
      text.rows[0].fields[0] == "Record Length")
    return SignalFormat::kTektronix;
  return SignalFormat::kCsv;
}

double round_interval(double dt) {
  const double decade = std::pow(10.0, std::floor(std::log10(dt)));
  for (double m : {1.0, 2.0, 2.5, 4.0, 5.0, 8.0, 10.0})
    if (std::abs(dt / (m * decade) - 1) < kRoundIntervalTolerance) return m * decade;
  return dt;
}

std::string seconds(double s) { return format_number(s) + " s"; }

// The least-squares line t ≈ t0 + i·dt through the stamps, its interval snapped to a round value
// (round_interval), and the largest distance of a stamp from it.
struct ClockFit {
  double t0 = 0, dt = 0, fitted_dt = 0, largest_off = 0;
};
ClockFit fit_clock(const std::vector<double>& t) {
  const std::size_t n = t.size();
  double si = 0, st = 0, sii = 0, sit = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = static_cast<double>(i);
    si += x, st += t[i], sii += x * x, sit += x * t[i];
  }
  const double dn = static_cast<double>(n);
  ClockFit c;
  c.fitted_dt = (dn * sit - si * st) / (dn * sii - si * si);
  c.dt = round_interval(c.fitted_dt);
  c.t0 = (st - c.dt * si) / dn;
  for (std::size_t i = 0; i < n; ++i)
    c.largest_off = std::max(c.largest_off, std::abs(t[i] - c.t0 - static_cast<double>(i) * c.dt));
  return c;
}

// A few repeated time stamps are repeated rows, not a rounded column: stamps rounded to a step q
// coarser than the sampling interval repeat in a fraction 1 − dt/q of the rows, which is more than
// the 2 % by which the reader lets steps differ from the interval (kUniformStepTolerance) unless q
// is that close to dt. A repeated row whose values read are those of the row before is a row
// exported twice (a known scope-export glitch): it is skipped with a warning naming its line, so
// the samples after it keep their times. One with other values is refused: which of the two is
// the sample at that time cannot be told. The file itself is never changed.
void drop_repeated_rows(const std::filesystem::path& file, const LineMap& lines,
                        SignalColumns& out) {
  std::vector<double>& t = out.time_s;
  std::vector<std::size_t> skipped;
  LineMap kept_lines;
  kept_lines.push_back(lines[0]);
  std::size_t kept = 1;
  for (std::size_t i = 1; i < t.size(); ++i) {
    const bool repeat = t[i] == t[kept - 1];
    bool same = repeat;
    for (const auto& v : out.values) same = same && v[i] == v[kept - 1];
    if (repeat && !same)
      throw input_error(file.string(), "line " + std::to_string(lines[i]) + " (time column)",
                        seconds(t[i]),
                        "the time of line " + std::to_string(kept_lines[kept - 1]) +
                            " again, with other values; expected strictly increasing time (which "
                            "of the two rows is the sample at that time cannot be told)");
    if (repeat) {
      skipped.push_back(lines[i]);
      continue;
    }
    t[kept] = t[i];
    kept_lines.push_back(lines[i]);
    for (auto& v : out.values) v[kept] = v[i];
    ++kept;
  }
  t.resize(kept);
  out.lines = std::move(kept_lines);
  for (auto& v : out.values) v.resize(kept);
  // The first lines by number, then how many more: a file exported with every row twice has
  // thousands.
  constexpr std::size_t kLinesNamed = 10;
  std::string which;
  for (std::size_t k = 0; k < std::min(skipped.size(), kLinesNamed); ++k)
    which += (which.empty() ? "" : ", ") + std::to_string(skipped[k]);
  if (skipped.size() > kLinesNamed)
    which += " and " + std::to_string(skipped.size() - kLinesNamed) + " more";
  out.warnings.push_back(file.string() + ": line" + (skipped.size() > 1 ? "s " : " ") + which +
                         " repeat" + (skipped.size() > 1 ? "" : "s") +
                         " the row before (the same time and values: a row exported twice); "
                         "skipped, so the samples after keep their times");
}

// Whether every repeated time repeats every value of the row before: rows exported twice however
// many there are, since a rounded column repeats the time of other samples, whose values differ
// somewhere.
bool every_repeat_twice(const SignalColumns& out) {
  const std::vector<double>& t = out.time_s;
  for (std::size_t i = 1; i < t.size(); ++i)
    if (t[i] == t[i - 1])
      for (const auto& v : out.values)
        if (v[i] != v[i - 1]) return false;
  return true;
}

// A peak-detect (envelope) acquisition exports a minimum and a maximum per interval, each pair at
// one time stamp (Rohde & Schwarz RTM's CSV): read as samples they interleave the envelope's two
// edges, and their stamps look like a rounded column or a gap. Every row paired with the next at
// one stamp, each pair's first values at most its second's in every column read (and below them
// somewhere): refused by that cause. Stamps rounded to twice the interval repeat in pairs too, but
// noisy samples are not so ordered over thousands of pairs.
void refuse_extreme_pairs(const std::filesystem::path& file, const LineMap& lines,
                          const SignalColumns& out) {
  const std::vector<double>& t = out.time_s;
  constexpr std::size_t kPairsToJudgeBy = 2;
  if (t.size() < 2 * kPairsToJudgeBy || t.size() % 2 != 0) return;
  bool below = false;
  for (std::size_t i = 0; i + 1 < t.size(); i += 2) {
    if (t[i] != t[i + 1]) return;
    for (const auto& v : out.values) {
      if (v[i] > v[i + 1]) return;
      below = below || v[i] < v[i + 1];
    }
  }
  if (!below) return;  // each row twice: rows exported twice (drop_repeated_rows)
  throw input_error(file.string(), "line " + std::to_string(lines[1]) + " (time column)",
                    seconds(t[1]),
                    "the time of line " + std::to_string(lines[0]) +
                        " again, as every row's is its neighbour's, each pair's first values at "
                        "most its second's: a minimum and a maximum per interval (a peak-detect "
                        "or envelope acquisition), not samples; expected one sample per time: "
                        "acquire (or export) the record in sample mode");
}

// The steps of increasing stamps: the median one is the sampling interval, against which a gap or
// jump stands out.
struct StepSurvey {
  double median_step = 0, mean_step = 0;
  std::size_t first_off = 0;  // first sample whose step is off the median (0: none)
  double jitter = 0;          // largest |step − mean| / mean
  double shortest = 0, longest = 0;
};
StepSurvey survey_steps(const std::vector<double>& t) {
  const std::size_t n = t.size();
  std::vector<double> steps(n - 1);
  for (std::size_t i = 1; i < n; ++i) steps[i - 1] = t[i] - t[i - 1];
  StepSurvey s;
  s.median_step = median(std::move(steps));
  s.mean_step = (t.back() - t.front()) / static_cast<double>(n - 1);
  s.shortest = t.back() - t.front();
  for (std::size_t i = 1; i < n; ++i) {
    const double step = t[i] - t[i - 1];
    s.shortest = std::min(s.shortest, step);
    s.longest = std::max(s.longest, step);
    if (!s.first_off && std::abs(step - s.median_step) > kUniformStepTolerance * s.median_step)
      s.first_off = i;
    s.jitter = std::max(s.jitter, std::abs(step - s.mean_step) / s.mean_step);
  }
  return s;
}

// The rounding step of each stamp as printed: the larger of the steps of the two ways a column
// is printed, to D significant digits ("%.2E": 1e-5 at 1.23E-03, 1e-8 at 4.56E-06) and to d
// decimals ("%.1f": 0.1 throughout), D and d the fewest that write every stamp exactly.
std::vector<double> stamp_rounding(const std::vector<double>& t) {
  constexpr int kMaxDigits = 17;     // a double's
  constexpr int kMaxDecimals = 330;  // beyond a double's smallest
  constexpr double kExactly = 1e-9;  // of the step: the stamp is that multiple of it
  const auto exact = [&](double v, double step) {
    return std::abs(v / step - std::round(v / step)) <= kExactly;
  };
  int digits = 1, decimals = -kMaxDigits;
  for (double v : t) {
    if (v == 0) continue;
    const int magnitude = static_cast<int>(std::floor(std::log10(std::abs(v))));
    while (digits < kMaxDigits && !exact(v, std::pow(10.0, magnitude - digits + 1))) ++digits;
    while (decimals < kMaxDecimals &&
           (std::pow(10.0, -decimals) > std::abs(v) || !exact(v, std::pow(10.0, -decimals))))
      ++decimals;
  }
  const double fixed = std::pow(10.0, -decimals);
  std::vector<double> step(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    step[i] =
        t[i] == 0
            ? fixed
            : std::max(fixed, std::pow(10.0, std::floor(std::log10(std::abs(t[i]))) - digits + 1));
  }
  return step;
}

// Rounded stamps lie within half their rounding step of the sampling clock (a line t0 + i·dt);
// one further off by more than kRoundedStampFraction of the interval has samples missing
// before it (a gap) or extra ones, which the rebuilt clock would spread over the record: a gap
// of 200 samples in the epoxy record's 3-digit stamps put them 98 intervals off, 1 sample 0.48.
void refuse_gap_in_rounded_stamps(const std::filesystem::path& file, const LineMap& lines,
                                  const std::vector<double>& t, const ClockFit& c,
                                  const std::string& hint) {
  const std::vector<double> step = stamp_rounding(t);
  // Judged from the clock start that every rounding fits best (the middle of the band the stamps
  // allow), not from the least-squares line: stamps rounded to a multiple of the interval (10 MS/s
  // printed to the µs) round their ties one way, which moves that line up to half an interval.
  double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double residual = t[i] - static_cast<double>(i) * c.dt;
    lowest = std::min(lowest, residual + step[i] / 2);
    highest = std::max(highest, residual - step[i] / 2);
  }
  const double t0 = (lowest + highest) / 2;
  std::size_t worst = 0;
  double worst_off = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double off = std::abs(t[i] - t0 - static_cast<double>(i) * c.dt) - step[i] / 2;
    if (off > worst_off) worst = i, worst_off = off;
  }
  if (worst_off <= kRoundedStampFraction * c.dt) return;
  throw input_error(
      file.string(), "line " + std::to_string(lines[worst]) + " (time column)", seconds(t[worst]),
      seconds(worst_off) + " off the sampling clock of the rounded stamps (" + seconds(c.dt) +
          " per row) beyond its rounding: expected uniform sampling (samples "
          "missing or repeated: a gap or jump in the record)" +
          hint);
}

// Time stamps too large for a double to hold to their steps: seconds since an epoch (LabVIEW's
// 1904, Unix's 1970), 3.8e9 s at a 1 MS/s record's 1 us steps, are read to 4.77e-7 s, so their
// steps come out 0.95 and 1.43 us. The stamps are right as written; what they are read into cannot
// keep them. Refused by that cause (before the steps are refused as a gap, or repeated stamps
// rebuilt as a rounded column) when a double's spacing at the largest stamp exceeds the
// uniformity tolerance of the mean step: only then can it move a step out of it.
void refuse_unresolved_stamps(const std::filesystem::path& file, const LineMap& lines,
                              const std::vector<double>& t) {
  const std::size_t last = std::abs(t.back()) >= std::abs(t.front()) ? t.size() - 1 : 0;
  const double largest = std::abs(t[last]);
  const double spacing = std::nextafter(largest, HUGE_VAL) - largest;
  const double mean_step = (t.back() - t.front()) / static_cast<double>(t.size() - 1);
  if (!(spacing > kUniformStepTolerance * mean_step)) return;
  char share[32];
  std::snprintf(share, sizeof share, "%.3g %%", 100 * spacing / mean_step);
  throw input_error(
      file.string(), "line " + std::to_string(lines[last]) + " (time column)",
      format_resolved(t[last], mean_step, 6) + " s",
      "time stamps this large are read to " + seconds(spacing) + " (a double's spacing there), " +
          share + " of the mean step " + seconds(mean_step) +
          ": their steps cannot be told from gaps; expected times on the record's own clock "
          "(from its trigger or first sample, as a scope writes them): export them so, or give "
          "measurement.time.interval (and start) and name the channels' columns");
}

// What a refusal of the time stamps adds when the first column was taken as the time column by
// default and does not show itself one (RawSignalColumns::time_column_shown): a file without a
// time column reads its first channel there. A time column the scene did not name is refused as
// a named one is.
std::string no_time_column_hint(const SignalRequest& request, const RawSignalColumns& raw) {
  if (!request.time_column.name.empty() || request.time_column.index || raw.time_column_shown)
    return "";
  return "; a file without a time column needs its time base: measurement.time.interval (and "
         "start)";
}

// Checks the time stamps: increasing and uniform. Repeated stamps throughout (rounded to fewer
// digits than the sampling needs) are not an error: the base is rebuilt from a least-squares fit
// of t against the sample index, with a warning; a few are repeated rows (drop_repeated_rows).
void check_time_base(const std::filesystem::path& file, RawSignalColumns& raw,
                     const SignalRequest& request, SignalColumns& out) {
  const auto& t = out.time_s;
  if (t.size() < 2)
    throw input_error(file.string(), "", std::to_string(t.size()) + " samples",
                      "expected at least 2");
  if (raw.time_from_header) {
    out.dt_s = raw.header_dt;
    out.lines = std::move(raw.lines);
    return;
  }
  std::size_t repeats = 0;
  for (std::size_t i = 1; i < t.size(); ++i) {
    if (t[i] < t[i - 1])
      throw input_error(file.string(), "line " + std::to_string(raw.lines[i]) + " (time column)",
                        seconds(t[i]),
                        "time goes backwards (previous sample " + seconds(t[i - 1]) +
                            "); expected increasing time" + no_time_column_hint(request, raw));
    repeats += t[i] == t[i - 1];
  }
  if (repeats > 0) refuse_extreme_pairs(file, raw.lines, out);
  if (repeats > 0 &&
      (static_cast<double>(repeats) <= kUniformStepTolerance * static_cast<double>(t.size() - 1) ||
       every_repeat_twice(out))) {
    drop_repeated_rows(file, raw.lines, out);  // the line of each sample kept
    repeats = 0;
  } else {
    out.lines = std::move(raw.lines);
  }
  const LineMap& lines = out.lines;
  const std::size_t n = t.size();
  const double span = t.back() - t.front();
  if (!(span > 0))
    throw input_error(file.string(), "line " + std::to_string(lines.back()) + " (time column)",
                      seconds(t.back()),
                      "time does not advance" + no_time_column_hint(request, raw));
  // The base rebuilt on the stamps' least-squares line, with a warning saying why.
  auto rebuild = [&](const ClockFit& c, const std::string& why) {
    for (std::size_t i = 0; i < n; ++i) out.time_s[i] = c.t0 + static_cast<double>(i) * c.dt;
    out.dt_s = c.dt;
    char msg[500];
    std::snprintf(msg, sizeof msg,
                  "%s: %s; time base rebuilt from the sample interval %.6g s (%.6g MHz, "
                  "least-squares fit %.6g s) starting at %s s",
                  file.string().c_str(), why.c_str(), c.dt, 1e-6 / c.dt, c.fitted_dt,
                  format_resolved(c.t0, c.dt, 6).c_str());
    out.warnings.push_back(msg);
  };
  if (repeats > 0) {
    refuse_unresolved_stamps(file, lines, t);
    std::size_t distinct = 1;
    for (std::size_t i = 1; i < n; ++i) distinct += t[i] != t[i - 1];
    const ClockFit c = fit_clock(t);
    refuse_gap_in_rounded_stamps(file, lines, t, c, no_time_column_hint(request, raw));
    rebuild(c, "time stamps repeat (" + std::to_string(distinct) + " distinct values in " +
                   std::to_string(n) + " rows: the column was rounded)");
    return;
  }
  const auto [median_step, mean_step, first_off, jitter, shortest, longest] = survey_steps(t);
  const TimeResampling& r = request.resample;
  const bool resample =
      r.mode == TimeResample::kAlways
          ? first_off || r.interval_s
          : first_off && r.mode == TimeResample::kAuto && jitter <= kAutoResampleJitter;
  if (first_off && !resample) refuse_unresolved_stamps(file, lines, t);
  if (first_off && !resample && r.mode == TimeResample::kAuto) {
    // Steps too uneven to resample that differ only because the stamps were printed with too few
    // digits: the clock was uniform (a digitizer's crystal), its stamps were not.
    const ClockFit c = fit_clock(t);
    if (c.largest_off <= kRoundedStampFraction * c.dt) {
      char why[200];
      std::snprintf(why, sizeof why,
                    "time steps vary (%s to %s) but every stamp lies within %s of a uniform "
                    "clock: the column was rounded",
                    seconds(shortest).c_str(), seconds(longest).c_str(),
                    seconds(c.largest_off).c_str());
      rebuild(c, why);
      return;
    }
  }
  if (first_off && !resample) {
    const std::size_t i = first_off;
    char hint[200];
    std::snprintf(hint, sizeof hint,
                  "; steps vary by up to %.3g %% of the mean interval %s: \"time\": "
                  "{\"resample\": true} resamples the record onto a uniform grid (linear)",
                  100 * jitter, seconds(mean_step).c_str());
    throw input_error(file.string(), "line " + std::to_string(lines[i]) + " (time column)",
                      "step " + seconds(t[i] - t[i - 1]),
                      "expected uniform sampling at " + seconds(median_step) +
                          " (gap or jump in the record)" + hint +
                          no_time_column_hint(request, raw));
  }
  if (!resample) {
    out.dt_s = mean_step;
    return;
  }
  // Linear resampling (core/interpolation.hpp) onto t0 + k·dt over the record's span.
  const double dt = r.interval_s.value_or(mean_step);
  const auto m = static_cast<std::size_t>(std::floor(span / dt * (1 + 1e-12))) + 1;
  std::vector<double> grid(m);
  for (std::size_t k = 0; k < m; ++k) grid[k] = t.front() + static_cast<double>(k) * dt;
  for (auto& v : out.values) {
    std::vector<double> y(m);
    for (std::size_t k = 0; k < m; ++k) y[k] = interpolate(t, v, grid[k]);
    v = std::move(y);
  }
  char msg[500];
  std::snprintf(msg, sizeof msg,
                "%s: time base not uniform (steps %s to %s, up to %.3g %% off the mean interval "
                "%s); %zu samples resampled (linear) onto a uniform grid of %zu at %.6g s "
                "(%.6g MHz)%s",
                file.string().c_str(), seconds(shortest).c_str(), seconds(longest).c_str(),
                100 * jitter, seconds(mean_step).c_str(), n, m, dt, 1e-6 / dt,
                r.mode == TimeResample::kAlways ? " as measurement.time.resample asks" : "");
  out.warnings.push_back(msg);
  out.time_s = std::move(grid);
  out.dt_s = dt;
  out.lines.clear();
}

}  // namespace

std::string_view to_string(SignalFormat f) { return enum_name(kSignalFormatNames, f); }

namespace {

// The file's columns as found, in `format` (detected when asked). The text (the file's bytes, a
// deep record's largest part) is let go on return, before the time base is checked.
RawSignalColumns read_raw_columns(const SignalRequest& request, SignalFormat& format) {
  const DelimitedText text = is_spreadsheet(request.file)
                                 ? read_spreadsheet(request.file, request.sheet)
                                 : read_delimited_text(request.file);
  format = request.format == SignalFormat::kAuto ? detect(text) : request.format;
  // A format whose files carry their own time base has no use for the scene's.
  if (request.clock && format != SignalFormat::kCsv)
    throw input_error(
        request.file.string(), "measurement.time.interval",
        format_number(request.clock->interval_s) + " s",
        "a " + std::string(to_string(format)) + " file carries its own time base (" +
            (format == SignalFormat::kLanlRaw ? "each signal's start time and sample interval"
                                              : "its time column") +
            "); drop measurement.time.interval, which is for files without one");
  switch (format) {
    case SignalFormat::kLanlRaw:
      return read_lanl_raw_columns(text, request);
    case SignalFormat::kTektronix:
      return read_tektronix_columns(text, request);
    default:
      return read_csv_columns(text, request);
  }
}

}  // namespace

SignalColumns read_signal_columns(const SignalRequest& request) {
  SignalColumns out;
  out.file = request.file;
  RawSignalColumns raw = read_raw_columns(request, out.format);
  out.time_s = std::move(raw.time);
  if (!raw.time_from_header)
    for (double& v : out.time_s) v *= request.time_unit_s;
  out.names = raw.names;
  out.warnings = std::move(raw.warnings);
  out.values = std::move(raw.values);
  check_time_base(request.file, raw, request, out);
  return out;
}

}  // namespace shpb
