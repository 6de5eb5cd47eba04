#include "fit/calibration.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <mutex>

#include "analysis/dispersion_cutoff.hpp"
#include "analysis/gauge_signals.hpp"
#include "analysis/pulse_window.hpp"
#include "analysis/signal_checks.hpp"
#include "core/error.hpp"
#include "core/median.hpp"
#include "core/number_format.hpp"
#include "dispersion/dispersion_table.hpp"
#include "dispersion/propagation.hpp"
#include "fit/least_squares.hpp"

namespace shpb {
namespace {

// The compared windows reach this fraction of the source pulse's length beyond both of its ends
// (the same margin as the bars-together check of `process`, analysis/bar_check.cpp).
constexpr double kWindowMargin = 0.2;
// A gauge's record is compared over the source's first returns only: a pulse dispersed over more
// than three passes of a bar is spread far beyond its window.
constexpr std::size_t kMaxArrivals = 3;

// The parameters, by name, with their nominal values.
class Parameters {
 public:
  std::size_t add(const std::string& name, double nominal, double lower, double upper,
                  double scale) {
    if (auto it = index_.find(name); it != index_.end()) return it->second;
    index_[name] = list_.size();
    list_.push_back({name, nominal, lower, upper, scale});
    return list_.size() - 1;
  }
  const std::vector<LsParameter>& list() const { return list_; }

 private:
  std::vector<LsParameter> list_;
  std::map<std::string, std::size_t> index_;
};

// A distance in a bar: constant + Σ coefficient · θ[parameter] (gauge positions are fitted).
struct Segment {
  std::size_t bar = 0;  // index into Shot::bars
  double constant = 0;
  std::vector<std::pair<std::size_t, double>> terms;
  double length(const std::vector<double>& theta) const {
    double d = constant;
    for (const auto& [p, k] : terms) d += k * theta[p];
    return d;
  }
};

struct Arrival {
  double sign = 1;  // −1 per reflection at a free end
  std::vector<Segment> way;
};

struct ShotBar {
  double radius_m = 0, density_kg_m3 = 0;
  std::size_t c = 0, nu = 0;  // parameter indices
};

struct Target {
  std::string gauge;
  std::optional<std::size_t> gain, delay;
  std::vector<Arrival> arrivals;
  std::vector<double> measured;
  std::vector<std::size_t> samples;       // the compared samples
  double level_sd = 0;                    // its record's removed baseline level's (rest_level_sd)
  std::optional<ClippedSamples> clipped;  // a clipped channel's samples at its clip level
  // The share of a white noise's power its low-passed record keeps (low_pass_as_modelled): its
  // residuals count as that many independent ones each.
  double noise_share = 1;

  // The residual of compared sample i over the shot's peak; at a clip level the censored one (the
  // strain there reached at least that level: a bound, not a value).
  double residual(std::size_t i, double model, double peak) const {
    return (clipped ? clipped->residual(i, model, measured[i]).value : model - measured[i]) / peak;
  }
};

struct Shot {
  std::string scene, kind, source_gauge;
  std::vector<double> time_s, source;
  double dt = 0, peak = 0, cutoff_Hz = 0;
  double source_level_sd = 0;        // the source record's removed baseline level's
  double source_noise = 0;           // the source record's noise per sample (its baseline's)
  std::size_t keep0 = 0, keep1 = 0;  // the source's kept samples (SourceWindow::end)
  std::vector<ShotBar> bars;
  std::vector<Target> targets;
  // A measured striker velocity: the source's plateau (as recorded) and the strain the striker
  // gives the struck bar per unit of its wave speed, v Z_s / (Z_s + Z_b) (docs/methods.md §11).
  std::optional<double> plateau, strain_times_c;
  double plateau_sd = 0;              // its standard error from the noise over the plateau
  std::vector<std::string> warnings;  // what reading its record assumed (a rebuilt time base, ...)
};

// Dispersion tables by Poisson ratio, shared by the parallel evaluations.
class Tables {
 public:
  explicit Tables(double fa_over_c0) : fa_(fa_over_c0) {}
  const DispersionTable& of(double nu) {
    const std::lock_guard lock(m_);
    auto& t = tables_[nu];
    if (!t) t = std::make_unique<DispersionTable>(DispersionTable::up_to(nu, fa_));
    return *t;
  }

 private:
  double fa_;
  std::mutex m_;
  std::map<double, std::unique_ptr<DispersionTable>> tables_;
};

// The strain a pulse carries into bar `to` across its interface with bar `from`, per unit of its
// strain in `from`, at θ's wave speeds: the particle velocity's transmission 2 Z_f/(Z_f + Z_t),
// Z = ρ c A, times c_f/c_t (v = c ε). Bars of one impedance pass the strain whole; an incident bar
// 1 % faster than a transmitter of its density and size passes it 1.5 % larger, which the
// transmitter channel's gain took for its own (docs/methods.md §11).
double strain_transmission(const ShotBar& from, const ShotBar& to,
                           const std::vector<double>& theta) {
  const double cf = theta[from.c], ct = theta[to.c];
  const double zf = from.density_kg_m3 * cf * from.radius_m * from.radius_m,
               zt = to.density_kg_m3 * ct * to.radius_m * to.radius_m;
  return 2 * zf / (zf + zt) * cf / ct;
}

// The model of one target's record at θ.
std::vector<double> model_of(const Shot& s, const Target& t, const std::vector<double>& theta,
                             Tables& tables) {
  const std::size_t n = s.source.size();
  std::vector<double> sum(n, 0.0), x, y(n);
  FftPlans plans;
  // The channel's delay as a phase in each pulse's last leg: interpolated between samples, it
  // low-passed the model too (at 1 MS/s, 0.7 samples late: 4 % at 100 kHz), and on noise-free
  // shots at 500 kS/s the transmitter's gain came out 0.08 % high and its delay 33 ns early.
  const double delay = t.delay ? theta[*t.delay] : 0.0;
  for (const Arrival& a : t.arrivals) {
    x = s.source;
    for (std::size_t k = 0; k < a.way.size(); ++k) {
      const Segment& seg = a.way[k];
      const ShotBar& b = s.bars[seg.bar];
      const double c0 = theta[b.c], nu = theta[b.nu];
      PropagationOptions po;
      po.cutoff_fa_over_c0 = s.cutoff_Hz * b.radius_m / c0;
      Propagator p(tables.of(nu), {b.radius_m, c0, nu}, po, &plans);
      p.propagate(x, s.dt, seg.length(theta), y, k + 1 == a.way.size() ? delay : 0.0);
      x.swap(y);
    }
    // A way from the struck bar into the transmitter crosses the interface once (a tensile
    // return opens it: reflected whole).
    const double crossing =
        a.way.front().bar != a.way.back().bar
            ? strain_transmission(s.bars[a.way.front().bar], s.bars[a.way.back().bar], theta)
            : 1.0;
    for (std::size_t i = 0; i < n; ++i) sum[i] += a.sign * crossing * x[i];
  }
  const double gain = t.gain ? theta[*t.gain] : 1.0;
  for (double& v : sum) v *= gain;
  return sum;
}

std::string bar_key(const BarSpec& b) { return "bars." + b.name; }
std::string gauge_key(const GaugeSpec& g) { return "gauges." + g.name; }

// ---- One shot's model (docs/methods.md §11, "The model"), stage by stage ----

// The scene is a calibration shot: no specimen, and measured gauges.
void check_shot_scene(const Scene& scene, const std::string& file) {
  if (scene.specimen)
    throw input_error(file, "specimen", "\"" + scene.bars[*scene.specimen].name + "\"",
                      "a calibration shot has no specimen (bars apart, or bars together)");
  if (!scene.measurement || scene.measurement->channels.empty())
    throw input_error(file, "measurement", "(missing)",
                      "a calibration shot needs the measured signals of its gauges");
}

// The gauged bars, left to right: one (bars apart) or two neighbours in contact (bars together).
std::vector<std::size_t> gauged_bars(const Scene& scene, const GaugeSignals& signals,
                                     const std::string& file) {
  std::vector<std::size_t> gauged;
  for (std::size_t b = 0; b < scene.bars.size(); ++b)
    for (const auto& g : scene.bars[b].gauges)
      if (signals.find(g.name) && (gauged.empty() || gauged.back() != b)) gauged.push_back(b);
  if (gauged.empty() || gauged.size() > 2)
    throw input_error(file, "measurement.channels", std::to_string(gauged.size()) + " gauged bars",
                      "a calibration shot records one bar (bars apart) or two bars in contact "
                      "(bars together)");
  // The returns are modelled by an elastic bar's dispersion (methods.md §11): a polymer bar's law
  // would be fitted as a wrong wave speed and Poisson ratio.
  for (std::size_t b : gauged)
    if (!scene.bars[b].material.is_elastic())
      throw input_error(
          file, "bars",
          "\"" + scene.bars[b].name + "\" of a " +
              std::string(enum_name(kMaterialModelNames, scene.bars[b].material.model)) +
              " material",
          "an elastic gauged bar: calibrate fits an elastic bar's wave speed and "
          "Poisson ratio; a polymer bar's law is given in the scene (its relaxation "
          "spectrum measured apart, e.g. by DMA), not calibrated from shots");
  if (gauged.size() == 2 && gauged[1] != gauged[0] + 1)
    throw input_error(file, "bars", "\"" + scene.bars[gauged[1]].name + "\"",
                      "bars together: the two gauged bars must be neighbours");
  return gauged;
}

// Each gauged bar's wave speed (within ±kWaveSpeedRange) and Poisson ratio as parameters.
std::vector<ShotBar> bar_parameters(const Scene& scene, const std::vector<std::size_t>& gauged,
                                    Parameters& params) {
  std::vector<ShotBar> bars;
  for (std::size_t b : gauged) {
    const BarSpec& bar = scene.bars[b];
    const double c = bar.material.wave_speed_m_s();
    ShotBar sb;
    sb.radius_m = 0.5 * bar.diameter_m;
    sb.density_kg_m3 = bar.material.density_kg_m3;
    sb.c = params.add(bar_key(bar) + ".wave_speed_m_s", c, (1 - kWaveSpeedRange) * c,
                      (1 + kWaveSpeedRange) * c, c);
    const double nu = bar.material.poisson_ratio;
    sb.nu = params.add(bar_key(bar) + ".poisson_ratio", nu, 0.05, 0.45, 0.3);
    bars.push_back(sb);
  }
  return bars;
}

// A gauge's position as a parameter, anywhere on its bar.
std::size_t position_parameter(Parameters& params, const BarSpec& bar, const GaugeSpec& g) {
  return params.add(gauge_key(g) + ".position_m", g.position_m, 0.0, bar.length_m,
                    std::max(bar.length_m, 0.1));
}

// The source gauge: the first measured gauge the pulse passes (the leftmost on the struck bar).
const GaugeSpec& source_gauge(const BarSpec& struck, const GaugeSignals& signals) {
  const GaugeSpec* src = nullptr;
  for (const auto& g : struck.gauges)
    if (signals.find(g.name) && (!src || g.position_m < src->position_m)) src = &g;
  return *src;
}

// The source's first pulse, its window [keep0, keep1) (the compared windows are this one moved)
// and the source's kept samples, [keep0, end).
struct SourceWindow {
  PulseWindow pulse;
  std::size_t keep0 = 0, keep1 = 0, end = 0;
};

// The source (docs/methods.md §11): the first pulse of the source gauge's record, widened by
// kWindowMargin of its length at both ends, with the dispersive tail that trails it up to the
// earliest return to the gauge, `return_samples` after the window's start; the record is zeroed
// outside. Everything the gauge records before a return is the pulse moving on: cut at the
// window's end, the tail's high frequencies (5 % of the peak after 1 m of a 25 mm bar) were
// missing from every modelled pulse, and the fit bent the Poisson ratios to make up for them.
SourceWindow cut_source(std::vector<double>& source, double noise, std::size_t return_samples,
                        const std::string& file, const std::string& gauge) {
  const auto pulse = find_first_pulse(source, {0.0, noise});
  if (!pulse)
    throw input_error(file, "measurement.channels", "gauge \"" + gauge + "\"",
                      "its signal never rises above its noise: no pulse to calibrate with");
  const std::size_t n = source.size();
  const auto margin =
      static_cast<std::size_t>(kWindowMargin * static_cast<double>(pulse->end - pulse->onset));
  SourceWindow w{*pulse, pulse->onset > margin ? pulse->onset - margin : 0, 0};
  w.keep1 = std::min(n, pulse->end + margin);
  w.end = std::clamp(w.keep0 + return_samples, w.keep1, n);
  for (std::size_t i = 0; i < n; ++i)
    if (i < w.keep0 || i >= w.end) source[i] = 0;
  return w;
}

// Bars apart, the far end free: a pulse still passing the gauge when its reflection from that end
// returns is summed with it, inverted, and no source can be cut from the record (the model would
// propagate the sum: a gauge 195 mm from the end of a 2 m bar under a 120 µs pulse came out 83 mm
// off at a stated 3 mm, with no warning). The gauge must lie at least c0 T/2 from the far end.
void require_source_before_return(const SourceWindow& w, double return_s, double dt,
                                  const BarSpec& bar, const std::string& file,
                                  const GaugeSpec& gauge) {
  const double seen_s = static_cast<double>(w.pulse.end - w.pulse.onset) * dt;
  if (seen_s <= return_s) return;
  char msg[400];
  std::snprintf(msg, sizeof msg,
                "its first pulse is still passing the gauge when its reflection from the bar's "
                "free far end returns, 2(L - x)/c0 = %.3g s after it arrived (the pulse seen "
                "there lasts %.3g s): no source pulse can be cut from the record; a gauge at least "
                "c0 T/2 = %.3g m from the far end of bar \"%s\" for a pulse of T, or a shorter "
                "striker",
                return_s, seen_s, 0.5 * bar.material.wave_speed_m_s() * seen_s, bar.name.c_str());
  throw input_error(file, "measurement.channels", "gauge \"" + gauge.name + "\"", msg);
}

// A measured striker velocity (docs/methods.md §11, "Absolute gains"): the strain the striker
// gives the struck bar per unit of its wave speed, v Z_s / (Z_s + Z_b), and the source's plateau
// with its standard error. Nothing without a velocity or a striker bar with a material.
void striker_plateau(Shot& s, const Scene& scene, std::size_t struck, const SourceWindow& w,
                     double noise) {
  const auto striker = struck > 0 ? std::optional(struck - 1) : std::nullopt;
  if (!scene.measurement->striker_velocity_m_s || !striker || !scene.bars[*striker].has_material)
    return;
  const double zs = scene.bars[*striker].impedance_kg_s(), zb = scene.bars[struck].impedance_kg_s();
  s.strain_times_c = *scene.measurement->striker_velocity_m_s * zs / (zs + zb);
  // The middle half of the pulse: past the front's dispersion ringing, before the tail's.
  const std::size_t quarter = (w.pulse.end - w.pulse.onset) / 4;
  const std::vector<double> middle(s.source.begin() + static_cast<long>(w.pulse.onset + quarter),
                                   s.source.begin() + static_cast<long>(w.pulse.end - quarter));
  s.plateau = std::abs(median(middle));
  // Noise over the samples, and the ringing still on the plateau: the difference of the two
  // halves' medians (a systematic part the noise does not show).
  const auto half = static_cast<long>(middle.size() / 2);
  const double drift = median({middle.begin(), middle.begin() + half}) -
                       median({middle.begin() + half, middle.end()});
  s.plateau_sd = std::hypot(
      noise / std::sqrt(std::max<double>(1.0, static_cast<double>(middle.size()))), drift);
}

// The low-pass cut-off in Hz, the same in every leg (docs/methods.md §5, §11): the scene's
// `measurement.dispersion`, else kDefaultCutoffFaOverC0 at the struck bar's nominal c0.
double cutoff_of(const DispersionSpec& ds, const BarSpec& struck) {
  const double c_src = struck.material.wave_speed_m_s();
  return ds.cutoff_Hz ? *ds.cutoff_Hz
                      : (ds.cutoff_fa_c0 ? *ds.cutoff_fa_c0 : kDefaultCutoffFaOverC0) * c_src /
                            (0.5 * struck.diameter_m);
}

// The ways of the returning pulses to a gauge (position parameter pg) on the k-th gauged bar
// (length L), the source gauge's position parameter ps on the struck bar (length L_I),
// docs/methods.md §11.
std::vector<Arrival> ways_to(std::size_t k, bool together, double L, double L_I, std::size_t pg,
                             std::size_t ps, bool is_source) {
  std::vector<Arrival> ways;
  if (k == 0) {
    if (!is_source) ways.push_back({1, {{0, 0, {{pg, 1}, {ps, -1}}}}});
    if (!together) {  // bars apart: the far end, the struck end, the far end again
      ways.push_back({-1, {{0, 2 * L, {{pg, -1}, {ps, -1}}}}});
      ways.push_back({1, {{0, 2 * L, {{pg, 1}, {ps, -1}}}}});
      ways.push_back({-1, {{0, 4 * L, {{pg, -1}, {ps, -1}}}}});
    }
  } else {  // the transmitter: through the interface, then from its free far end
    const Segment in{0, L_I, {{ps, -1}}};
    ways.push_back({1, {in, {1, 0, {{pg, 1}}}}});
    ways.push_back({-1, {in, {1, 2 * L, {{pg, -1}}}}});
    ways.push_back({1, {in, {1, 2 * L, {{pg, 1}}}}});
  }
  return ways;
}

// The target's arrivals: the first kMaxArrivals ways whose window (the source's, moved by the
// travel at the nominal values) lies in the record; its compared samples are those windows.
void keep_in_record(Target& t, const std::vector<Arrival>& ways, const Shot& s,
                    const Parameters& params, const SourceWindow& w) {
  const std::size_t n = s.time_s.size();
  std::vector<double> nominal(params.list().size());
  for (std::size_t p = 0; p < nominal.size(); ++p) nominal[p] = params.list()[p].start;
  std::vector<char> mask(n, 0);
  for (const Arrival& a : ways) {
    if (t.arrivals.size() == kMaxArrivals) break;
    double travel = 0;
    for (const Segment& seg : a.way) travel += seg.length(nominal) / nominal[s.bars[seg.bar].c];
    const double shift = travel / s.dt;
    const double from = static_cast<double>(w.keep0) + shift,
                 to = static_cast<double>(w.keep1) + shift;
    if (!(to < static_cast<double>(n))) break;
    t.arrivals.push_back(a);
    for (auto i = static_cast<std::size_t>(std::max(0.0, from)); i < static_cast<std::size_t>(to);
         ++i)
      mask[i] = 1;
  }
  for (std::size_t i = 0; i < n; ++i)
    if (mask[i]) t.samples.push_back(i);
}

// The low-pass of a shot's model (docs/methods.md §5, §11): its cut-off in Hz in the struck bar at
// its nominal values, the record's ends untapered (a target's record starts at its baseline, and a
// taper would scale the compared samples near its end).
Propagator shot_low_pass(const Shot& s, const BarSpec& struck,
                         std::unique_ptr<DispersionTable>& table) {
  const double a = 0.5 * struck.diameter_m, c0 = struck.material.wave_speed_m_s();
  const double nu = struck.material.poisson_ratio;
  PropagationOptions po;
  po.cutoff_fa_over_c0 = s.cutoff_Hz * a / c0;
  po.taper_fraction = 0;
  table = std::make_unique<DispersionTable>(DispersionTable::up_to(nu, po.cutoff_fa_over_c0));
  return Propagator(*table, {a, c0, nu}, po);
}

// A target's record low-passed as its model is (docs/methods.md §11): the model's pulse passes the
// low-pass once per leg, with one cut-off in Hz in every bar, so the record passes it once per leg
// too, and the fit compares the two in the one band the model describes. The record holds the
// bar's response above the cut-off, which the model leaves out: compared unfiltered, the roll-off
// band's part of it bent the Poisson ratios. A clipped record is left as it is: its samples at the
// clip level are bounds, which a filter would smear. Sets the target's noise_share.
void low_pass_as_modelled(Target& t, Propagator& low_pass, double dt) {
  if (t.clipped) return;
  const std::size_t legs = t.arrivals.front().way.size();
  for (std::size_t k = 0; k < legs; ++k) t.measured = low_pass.propagate(t.measured, dt, 0.0);
  // The mean of H(f)^(2 legs) from 0 to the Nyquist frequency, on a grid fine against the roll-off.
  constexpr int kBins = 4096;
  double sum = 0;
  for (int j = 0; j < kBins; ++j) {
    const double f = (j + 0.5) / kBins * 0.5 / dt;
    sum += std::pow(low_pass.lowpass_gain(f), 2.0 * static_cast<double>(legs));
  }
  t.noise_share = sum / kBins;
}

// A channel other than the source's: its gain and delay relative to the reference channel's.
void channel_parameters(Target& t, const GaugeSpec& g, const std::string& source,
                        const std::string& reference, Parameters& params, const std::string& file) {
  if (source != reference)
    throw input_error(file, "measurement.channels", "gauge \"" + source + "\"",
                      "gains and delays are relative to one reference channel, \"" + reference +
                          "\" (the first shot's first gauge): its shots must record it too");
  t.gain = params.add(gauge_key(g) + ".gain", 1.0, 0.5, 2.0, 1.0);
  t.delay =
      params.add(gauge_key(g) + ".delay_s", 0.0, -kMaxChannelDelay_s, kMaxChannelDelay_s, 1e-6);
}

// A record more than twice as long as the span the fit compares (a scope's long idle tail) is
// cut to that span: every evaluation transforms the whole record, so a 10^7-sample shot took
// minutes per iteration for samples no residual uses. The span ends at the last compared sample
// plus the largest channel delay (a delay moves the model by up to that much), with a warning.
void cut_to_compared_span(Shot& s, const std::string& file) {
  const std::size_t n = s.time_s.size();
  std::size_t used = 0;
  for (const Target& t : s.targets)
    if (!t.samples.empty()) used = std::max(used, t.samples.back() + 1);
  used += static_cast<std::size_t>(std::ceil(kMaxChannelDelay_s / s.dt)) + 2;
  if (2 * used >= n) return;
  char msg[300];
  std::snprintf(msg, sizeof msg,
                "%s: the record's %zu samples cut to its first %zu (to %s s): the span the "
                "fit compares and the largest channel delay",
                file.c_str(), n, used, format_resolved(s.time_s[used - 1], s.dt, 6).c_str());
  s.warnings.push_back(msg);
  s.time_s.resize(used);
  s.source.resize(used);
  for (Target& t : s.targets) t.measured.resize(used);
}

// One calibration shot: its bars, its source pulse and the targets (each measured gauge's record
// with the ways of the pulses returning to it), its parameters added to `params`.
Shot prepare_shot(const CalibrationShot& cs, Parameters& params, std::string& reference) {
  const Scene& scene = cs.scene;
  const std::string file = scene.file.string();
  Shot s;
  s.scene = cs.display;
  check_shot_scene(scene, file);
  const GaugeSignals signals = read_gauge_signals(*scene.measurement, {});
  // What reading the record assumed, and what makes it doubtful (clipping, too few samples):
  // process's own checks of a record (analysis/signal_checks.hpp).
  s.warnings = signals.warnings;
  for (auto& w : signal_warnings(signals)) s.warnings.push_back(std::move(w));
  const std::vector<std::size_t> gauged = gauged_bars(scene, signals, file);
  s.kind = gauged.size() == 1 ? "bars apart" : "bars together";
  s.bars = bar_parameters(scene, gauged, params);
  const BarSpec& struck = scene.bars[gauged[0]];
  const GaugeSpec& src = source_gauge(struck, signals);
  s.source_gauge = src.name;
  if (reference.empty()) reference = src.name;
  const std::size_t ps = position_parameter(params, struck, src);
  s.dt = signals.dt_s;
  s.time_s = signals.time_s;
  // Each record's rest level is read before its first pulse, as process reads it (a record with
  // none is refused); the records keep their signs (a shot's returns come with both).
  RestSignal base = rest_signal(signals, src.name, 0.0, file);
  std::vector<double>& source = base.x;
  // The model propagates the source record: a clipped source cuts every modelled pulse, which no
  // reading of the targets can undo (a clipped target is read as bounds).
  const std::vector<ClippedLevel> cut =
      clipped_levels(*signals.find(src.name), signals.range_of(src.name));
  if (std::any_of(cut.begin(), cut.end(), [](const ClippedLevel& c) { return c.established; }))
    s.warnings.push_back(file + ": gauge \"" + src.name +
                         "\" is this shot's source and its record is clipped: every pulse the "
                         "calibration models from it is cut too, so its values are biased; fire "
                         "the shot again within the channel's range");
  // The earliest return to the source gauge: from the struck bar's far end (a free end, or the
  // interface with the transmitter), at the nominal wave speed.
  const double return_s = 2 * (struck.length_m - src.position_m) / struck.material.wave_speed_m_s();
  const SourceWindow w =
      cut_source(source, base.noise,
                 static_cast<std::size_t>(std::max(0.0, return_s / signals.dt_s)), file, src.name);
  // A striker pulse lasts 2 L_s/c0: ten times the struck bar's own round trip is no striker's,
  // but a clock read in the wrong unit (the rule of process, analysis/signal_checks.hpp).
  require_pulse_fits_round_trip(
      src.name, "first pulse", static_cast<double>(w.pulse.end - w.pulse.onset) * signals.dt_s,
      2 * struck.length_m / struck.material.wave_speed_m_s(), "2L/c0 = %.3g s of its bar", file);
  if (gauged.size() == 1)
    require_source_before_return(w, return_s, signals.dt_s, struck, file, src);
  s.source = source;
  s.source_level_sd = rest_level_sd(base.noise, baseline_samples(source.size()));
  s.source_noise = base.noise;
  s.keep0 = w.keep0, s.keep1 = w.end;
  s.peak = w.pulse.peak;
  striker_plateau(s, scene, gauged[0], w, base.noise);
  s.cutoff_Hz = cutoff_of(scene.measurement->dispersion, struck);
  std::unique_ptr<DispersionTable> low_pass_table;
  Propagator low_pass = shot_low_pass(s, struck, low_pass_table);

  for (std::size_t k = 0; k < gauged.size(); ++k) {
    const BarSpec& bar = scene.bars[gauged[k]];
    for (const auto& g : bar.gauges) {
      if (!signals.find(g.name)) continue;
      Target t;
      t.gauge = g.name;
      const std::size_t pg = position_parameter(params, bar, g);
      keep_in_record(
          t, ways_to(k, gauged.size() == 2, bar.length_m, struck.length_m, pg, ps, &g == &src), s,
          params, w);
      if (t.arrivals.empty()) continue;
      const RestSignal base_g = rest_signal(signals, g.name, 0.0, file);
      const std::vector<double>& measured = base_g.x;
      t.measured = measured;
      t.clipped = clipped_samples(*signals.find(g.name), t.measured, signals.range_of(g.name));
      if (t.clipped) t.clipped->noise = base_g.noise;
      t.level_sd = rest_level_sd(base_g.noise, baseline_samples(measured.size()));
      low_pass_as_modelled(t, low_pass, s.dt);
      if (&g != &src) channel_parameters(t, g, src.name, reference, params, file);
      s.targets.push_back(std::move(t));
    }
  }
  if (s.targets.empty())
    throw input_error(file, "measurement", s.scene,
                      "the record ends before any pulse returns to a gauge: record longer (at "
                      "least two bar lengths' travel after the first pulse)");
  cut_to_compared_span(s, file);
  return s;
}

std::vector<double> shot_residuals(const Shot& s, const std::vector<double>& theta,
                                   Tables& tables) {
  std::vector<double> r;
  for (const Target& t : s.targets) {
    const auto m = model_of(s, t, theta, tables);
    for (std::size_t i : t.samples) r.push_back(t.residual(i, m[i], s.peak));
  }
  return r;
}

std::vector<std::size_t> shot_parameters(const Shot& s) {
  std::vector<std::size_t> p;
  for (const ShotBar& b : s.bars) p.insert(p.end(), {b.c, b.nu});
  for (const Target& t : s.targets) {
    if (t.gain) p.push_back(*t.gain);
    if (t.delay) p.push_back(*t.delay);
    for (const Arrival& a : t.arrivals)
      for (const Segment& seg : a.way)
        for (const auto& term : seg.terms) p.push_back(term.first);
  }
  std::sort(p.begin(), p.end());
  p.erase(std::unique(p.begin(), p.end()), p.end());
  return p;
}

std::string two_digits(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2g", x);
  return text;
}

double rms(const std::vector<double>& r) {
  double e = 0;
  for (double v : r) e += v * v;
  return r.empty() ? 0.0 : std::sqrt(e / static_cast<double>(r.size()));
}

// ---- The fit and what it gives (docs/methods.md §11, "The fit" onwards), stage by stage ----

// Every shot prepared, the parameters they share, the reference channel and the highest cut-off
// (as f·a/c0) any trial wave speed asks of the dispersion tables.
struct PreparedShots {
  Parameters params;
  std::string reference;
  std::vector<Shot> shots;
  double fa_max = kDefaultCutoffFaOverC0;
};

PreparedShots prepare_shots(const std::vector<CalibrationShot>& input) {
  PreparedShots ps;
  for (const auto& cs : input) {
    ps.shots.push_back(prepare_shot(cs, ps.params, ps.reference));
    for (const ShotBar& b : ps.shots.back().bars)
      ps.fa_max = std::max(ps.fa_max, ps.shots.back().cutoff_Hz * b.radius_m /
                                          ((1 - kWaveSpeedRange) * ps.params.list()[b.c].start));
  }
  return ps;
}

// The residuals a shot's compared samples make, and all shots'.
std::size_t residual_count(const Shot& s) {
  std::size_t n = 0;
  for (const Target& t : s.targets) n += t.samples.size();
  return n;
}
std::size_t residual_count(const std::vector<Shot>& shots) {
  std::size_t n = 0;
  for (const Shot& s : shots) n += residual_count(s);
  return n;
}

// One least-squares group per shot: its residuals over its compared samples, plain squares.
std::vector<LsGroup> residual_groups(const std::vector<Shot>& shots, Tables& tables) {
  std::vector<LsGroup> groups;
  for (const Shot& s : shots) {
    LsGroup g;
    g.parameters = shot_parameters(s);
    const Shot* shot = &s;
    g.residuals = [shot, &tables](const std::vector<double>& theta) {
      return shot_residuals(*shot, theta, tables);
    };
    g.loss_scale.assign(residual_count(s), 1.0);
    groups.push_back(std::move(g));
  }
  return groups;
}

// The Jacobian at the optimum with its columns scaled to unit norm, and its SVD.
struct ScaledSvd {
  Eigen::VectorXd norm;  // the columns' norms (1 for a zero column)
  Eigen::VectorXd sv;    // singular values, largest first
  Eigen::MatrixXd v;     // right singular vectors
};

ScaledSvd scaled_svd(const Eigen::MatrixXd& jx, std::size_t p) {
  if (jx.rows() == 0 || jx.cols() != static_cast<long>(p))
    throw NumericalError("calibrate: the Jacobian at the solution cannot be evaluated");
  ScaledSvd out;
  out.norm.resize(static_cast<long>(p));
  for (std::size_t j = 0; j < p; ++j) {
    const double v = jx.col(static_cast<long>(j)).norm();
    out.norm(static_cast<long>(j)) = v > 0 ? v : 1.0;
  }
  const Eigen::MatrixXd js = jx * out.norm.cwiseInverse().asDiagonal();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(js, Eigen::ComputeThinV);
  out.sv = svd.singularValues();
  out.v = svd.matrixV();
  return out;
}

// The combinations of wave speeds, gauge positions and channel delays that move no compared
// pulse's arrival time (docs/methods.md §11, "Uncertainties"): the null space of the arrival
// times' derivatives, T = Σ legs d/c + τ, in the scaled parameters. Such a combination is fixed by
// the dispersion's shape alone — the Jacobian of the residuals sees it, far too weakly to trust
// (a record holding two of the transmitter's three returns: its wave speed 4 % off at a stated
// 0.02 %). It is named in fit.undetermined; its parameters, and the Poisson ratio of a bar whose
// wave speed is among them (fitted to the dispersion that then stands in for the travel times),
// get a weight of 1 in the returned vector (0 for the others); each combination is described in
// `undetermined`.
std::vector<double> timing_undetermined(const std::vector<Shot>& shots,
                                        const std::vector<LsParameter>& list,
                                        const std::vector<double>& theta,
                                        std::vector<std::string>& undetermined) {
  const std::size_t p = list.size();
  std::vector<std::vector<double>> rows;
  for (const Shot& s : shots)
    for (const Target& t : s.targets)
      for (const Arrival& a : t.arrivals) {
        std::vector<double> row(p, 0.0);
        for (const Segment& seg : a.way) {
          const std::size_t ic = s.bars[seg.bar].c;
          const double c = theta[ic];
          row[ic] -= seg.length(theta) / (c * c);
          for (const auto& [q, k] : seg.terms) row[q] += k / c;
        }
        if (t.delay) row[*t.delay] += 1;
        rows.push_back(std::move(row));
      }
  std::vector<std::size_t> used;  // the parameters some arrival time depends on
  for (std::size_t j = 0; j < p; ++j)
    if (std::any_of(rows.begin(), rows.end(), [j](const auto& r) { return r[j] != 0; }))
      used.push_back(j);
  std::vector<double> weight(p, 0.0);
  if (used.empty()) return weight;
  Eigen::MatrixXd a(static_cast<long>(std::max(rows.size(), used.size())),
                    static_cast<long>(used.size()));
  a.setZero();  // rows beyond the arrivals: zero (a thin SVD then gives every direction)
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t j = 0; j < used.size(); ++j)
      a(static_cast<long>(i), static_cast<long>(j)) = rows[i][used[j]] * list[used[j]].scale;
  const ScaledSvd svd = scaled_svd(a, used.size());
  // Travel times are exact functions of the parameters: a free combination has a singular value
  // at round-off, far below any that the arrivals determine.
  constexpr double kFreeDirection = 1e-9;
  for (long i = 0; i < svd.sv.size(); ++i) {
    if (svd.sv(i) > kFreeDirection * svd.sv(0)) continue;
    std::string line = "the travel times of the compared pulses do not determine ";
    bool first = true;
    for (std::size_t j = 0; j < used.size(); ++j) {
      const double w = svd.v(static_cast<long>(j), i);
      weight[used[j]] = std::max(weight[used[j]], w * w);
      if (std::abs(w) < 0.2) continue;
      line += (first ? "" : ", ") + list[used[j]].name + " (" + two_digits(w) + ")";
      first = false;
    }
    undetermined.push_back(
        line +
        ": only the dispersion's shape separates them, too weakly to trust; a record long enough "
        "to hold more of the pulse's returns to the gauges determines them");
  }
  for (const Shot& s : shots) {
    for (const ShotBar& b : s.bars) weight[b.nu] = std::max(weight[b.nu], weight[b.c]);
    // A channel whose pulses cross the bars' interface has its gain fitted against the crossing's
    // factor, which the bars' wave speeds set (strain_transmission): a wave speed no travel time
    // fixes leaves that gain unfixed too (one bars-together shot: 3 % off at a stated 0.3 %).
    for (const Target& t : s.targets)
      if (t.gain && !t.arrivals.empty() &&
          t.arrivals.front().way.front().bar != t.arrivals.front().way.back().bar)
        for (const ShotBar& b : s.bars) weight[*t.gain] = std::max(weight[*t.gain], weight[b.c]);
  }
  return weight;
}

// Each record's removed baseline level is an offset common to all its samples (its median over the
// record's first 5 %, rest_level_sd), which the residuals do not show: a target's record moves its
// residuals by 1/peak per unit, the source's moves every modelled pulse by the model of its kept
// window at 1 (the model is linear in the source). One error per record, over all residuals.
std::vector<LsCommonError> rest_level_errors(const std::vector<Shot>& shots,
                                             const std::vector<double>& theta, Tables& tables) {
  const std::size_t total = residual_count(shots);
  std::vector<LsCommonError> out;
  std::size_t first = 0;  // the shot's first residual
  for (const Shot& s : shots) {
    Shot unit = s;  // the source's window at 1: the source level's effect on the model
    std::fill(unit.source.begin(), unit.source.end(), 0.0);
    std::fill(unit.source.begin() + static_cast<long>(s.keep0),
              unit.source.begin() + static_cast<long>(std::min(s.keep1, s.source.size())), 1.0);
    LsCommonError source{s.source_level_sd, std::vector<double>(total, 0.0)};
    std::size_t row = first;
    for (const Target& t : s.targets) {
      const std::vector<double> m = model_of(unit, t, theta, tables);
      LsCommonError own{t.level_sd, std::vector<double>(total, 0.0)};
      for (std::size_t k = 0; k < t.samples.size(); ++k) {
        source.sensitivity[row + k] -= m[t.samples[k]] / s.peak;
        (t.gauge == s.source_gauge ? source : own).sensitivity[row + k] += 1 / s.peak;
      }
      if (t.gauge != s.source_gauge) out.push_back(std::move(own));
      row += t.samples.size();
    }
    out.push_back(std::move(source));
    first = row;
  }
  return out;
}

// The source record's noise over its kept samples (docs/methods.md §11, "Uncertainties"): every
// pulse modelled from the source carries it (the model is linear in the source), so it is common
// to all of a shot's compared pulses, not independent from residual to residual as s² counts it;
// on shots of an independent propagation ν scattered 1.2 times its sd so counted. d_j, the
// residuals' derivative in kept sample j, is the model of a unit sample there.
struct SourceNoise {
  Eigen::MatrixXd jtd;  // Σ_j σ² (Jᵀ d_j)(Jᵀ d_j)ᵀ, J unscaled
  double power = 0;     // Σ_j σ² |d_j|²: its expected share of Σ r²
};

SourceNoise source_noise(const std::vector<Shot>& shots, const std::vector<double>& theta,
                         Tables& tables, const Eigen::MatrixXd& jacobian) {
  SourceNoise out{Eigen::MatrixXd::Zero(jacobian.cols(), jacobian.cols()), 0.0};
  if (jacobian.rows() != static_cast<long>(residual_count(shots)))
    return out;    // no Jacobian: scaled_svd says so
  long first = 0;  // the shot's first residual
  for (const Shot& s : shots) {
    const auto rows = static_cast<long>(residual_count(s));
    Shot unit = s;
    std::fill(unit.source.begin(), unit.source.end(), 0.0);
    Eigen::VectorXd d(rows);
    // Jᵀ d_j, as j moves, is band-limited at the model's low-pass cut-off (zero above it in
    // every leg): sampled every `step` samples (above twice the cut-off) its sums over the window,
    // each sample weighing for its `step`, are those over every sample (every sd within 0.03 % of
    // the sum over every sample at 1 and 5 MS/s; 5 times faster at 5 MS/s).
    const auto step =
        std::max<std::size_t>(1, static_cast<std::size_t>(std::floor(0.5 / (s.cutoff_Hz * s.dt))));
    const std::size_t end = std::min(s.keep1, s.source.size());
    for (std::size_t j0 = s.keep0; j0 < end; j0 += step) {
      const std::size_t block = std::min(step, end - j0), j = j0 + block / 2;
      unit.source[j] = 1;
      long row = 0;
      for (const Target& t : s.targets) {
        const std::vector<double> m = model_of(unit, t, theta, tables);
        for (std::size_t i : t.samples) d(row++) = m[i] / s.peak;
      }
      unit.source[j] = 0;
      const Eigen::VectorXd v = jacobian.middleRows(first, rows).transpose() * d;
      const double var = s.source_noise * s.source_noise * static_cast<double>(block);
      out.jtd += var * v * v.transpose();
      out.power += var * d.squaredNorm();
    }
    first += rows;
  }
  return out;
}

// Uncertainties from the Jacobian at the optimum (docs/methods.md §11, "Uncertainties"):
// s² V S⁻² Vᵀ over the directions stronger than kWeakDirection (s² = Σr² less the source noise's
// share, over the low-passed residuals' independent count less P), plus the source's noise and
// each record's baseline level carried through the estimator (σ² g gᵀ, g = V S⁻² Vᵀ Jᵀ d); the
// weaker directions are left out and named in fit.undetermined, and a parameter weighing on them,
// or on a combination the travel times leave free (`timing_weight`), gets no sd.
void fitted_parameters(const std::vector<LsParameter>& list, const LsResult& r,
                       double independent_residuals, const std::vector<double>& timing_weight,
                       const std::vector<LsCommonError>& levels, const SourceNoise& source,
                       CalibrationFit& fit) {
  const std::size_t p = list.size();
  const ScaledSvd j = scaled_svd(r.jacobian, p);  // d r / d x, x = θ / scale
  const Eigen::VectorXd& sv = j.sv;
  fit.reciprocal_condition = sv(0) > 0 ? sv(static_cast<long>(p) - 1) / sv(0) : 0.0;
  const double dof = std::max(1.0, independent_residuals - static_cast<double>(p));
  // The records' own noise: what the source's noise leaves of Σr² (none if its baseline's noise
  // overstates it).
  const double s2 = std::max(0.0, 2 * r.cost - source.power) / dof;
  // (JᵀJ)⁻¹ over the determined directions, in the columns' unit-norm scaling.
  Eigen::MatrixXd pinv = Eigen::MatrixXd::Zero(static_cast<long>(p), static_cast<long>(p));
  std::vector<double> weak_weight = timing_weight;
  for (long i = 0; i < static_cast<long>(p); ++i) {
    if (sv(i) > kWeakDirection * sv(0)) {
      pinv += j.v.col(i) * j.v.col(i).transpose() / (sv(i) * sv(i));
      continue;
    }
    std::string line = "the shots do not determine ";
    bool first = true;
    for (std::size_t k = 0; k < p; ++k) {
      const double w = j.v(static_cast<long>(k), i);
      weak_weight[k] += w * w;
      if (std::abs(w) < 0.2) continue;
      line += (first ? "" : ", ") + list[k].name + " (" + two_digits(w) + ")";
      first = false;
    }
    fit.undetermined.push_back(line + ": that combination moves the residuals " +
                               two_digits(sv(i) / sv(0)) +
                               " times as much as the best-determined one");
  }
  const Eigen::MatrixXd scale_back = j.norm.cwiseInverse().asDiagonal();
  Eigen::MatrixXd cov = s2 * pinv + pinv * scale_back * source.jtd * scale_back * pinv;
  const Eigen::MatrixXd js = r.jacobian * scale_back;
  for (const LsCommonError& e : levels) {
    if (!(e.sd > 0) || static_cast<long>(e.sensitivity.size()) != js.rows()) continue;
    const Eigen::VectorXd g = pinv * (js.transpose() * Eigen::Map<const Eigen::VectorXd>(
                                                           e.sensitivity.data(), js.rows()));
    cov += e.sd * e.sd * g * g.transpose();
  }
  for (std::size_t k = 0; k < p; ++k) {
    FittedParameter fp{list[k].name, list[k].start, r.value[k], std::nullopt};
    // A parameter held by its bound is not determined by the shots: the Jacobian there measures
    // the misfit's slope into the bound, not an interval (a record without dispersion, as a 1D
    // simulation writes, put a Poisson ratio on 0.05 with sd 0.003).
    const bool bound = at_bound(r.value[k], list[k].lower, list[k].upper);
    if (bound)
      fit.undetermined.push_back(
          list[k].name + " ends at its bound " + format_number(r.value[k]) + " (bounds " +
          format_number(list[k].lower) + " to " + format_number(list[k].upper) +
          "): the shots ask for a value beyond it, so they do not determine it and it gets no "
          "uncertainty" +
          (list[k].name.ends_with(".poisson_ratio")
               ? " (a Poisson ratio is read from the pulses' dispersion: a record without it, as a "
                 "1D simulation writes, holds none)"
               : ""));
    // A parameter with a tenth of its weight on an undetermined direction is not determined.
    constexpr double kUndeterminedShare = 0.1;
    if (!bound && weak_weight[k] < kUndeterminedShare && r.residuals > p)
      fp.sd = std::sqrt(cov(static_cast<long>(k), static_cast<long>(k))) /
              j.norm(static_cast<long>(k)) * list[k].scale;
    fit.parameters.push_back(fp);
  }
}

// The calibration: every bar and gauge of the shots, the fitted values replacing the nominal.
Calibration calibration_of(const std::vector<CalibrationShot>& input,
                           const std::vector<FittedParameter>& parameters,
                           const std::string& reference) {
  auto value = [&](const std::string& name) -> std::optional<CalibratedValue> {
    for (const auto& fp : parameters)
      if (fp.name == name) return CalibratedValue{fp.value, fp.sd};
    return std::nullopt;
  };
  Calibration cal;
  cal.reference_gauge = reference;
  for (const auto& cs : input)
    for (const BarSpec& bar : cs.scene.bars) {
      const auto c = value(bar_key(bar) + ".wave_speed_m_s");
      if (c && std::none_of(cal.bars.begin(), cal.bars.end(),
                            [&](const BarCalibration& b) { return b.bar == bar.name; }))
        cal.bars.push_back(
            {bar.name, *c, *value(bar_key(bar) + ".poisson_ratio"), bar.material.density_kg_m3});
      for (const GaugeSpec& g : bar.gauges) {
        const auto x = value(gauge_key(g) + ".position_m");
        if (!x || std::any_of(cal.gauges.begin(), cal.gauges.end(),
                              [&](const GaugeCalibration& o) { return o.gauge == g.name; }))
          continue;
        GaugeCalibration gc{g.name, bar.name, *x, {1.0, 0.0}, {0.0, 0.0}};
        if (const auto gain = value(gauge_key(g) + ".gain")) gc.gain = *gain;
        if (const auto delay = value(gauge_key(g) + ".delay_s")) gc.delay_s = *delay;
        cal.gauges.push_back(gc);
      }
    }
  return cal;
}

// A measured striker velocity makes the gains absolute: the reference channel's gain is its
// recorded plateau over v Z_s / ((Z_s + Z_b) c0), with the fitted c0, weighted over the shots
// that give one (docs/methods.md §11, "Absolute gains"); every other gain is scaled by it.
void make_gains_absolute(const std::vector<Shot>& shots, const std::vector<double>& theta,
                         const std::string& reference, CalibrationFit& fit) {
  double weight = 0, sum = 0;
  for (const Shot& s : shots) {
    if (!s.plateau || s.source_gauge != reference) continue;
    const std::size_t ic = s.bars[0].c;
    const double c = theta[ic];
    const double g = *s.plateau * c / *s.strain_times_c;
    const auto sd_c = fit.parameters[ic].sd;
    const double rel2 =
        std::pow(s.plateau_sd / *s.plateau, 2) + (sd_c ? std::pow(*sd_c / c, 2) : 0);
    const double w = 1 / std::max(rel2 * g * g, 1e-30);
    sum += w * g, weight += w;
  }
  if (weight <= 0) return;
  const double g = sum / weight, sd = std::sqrt(1 / weight);
  Calibration& cal = fit.calibration;
  cal.absolute_gain = true;
  for (GaugeCalibration& gc : cal.gauges) {
    if (gc.gauge == reference) {
      gc.gain = {g, sd};
      continue;
    }
    const double rel = gc.gain.sd ? *gc.gain.sd / gc.gain.value : 0.0;
    gc.gain.sd =
        gc.gain.sd ? std::optional(g * gc.gain.value * std::hypot(rel, sd / g)) : std::nullopt;
    gc.gain.value *= g;
  }
  fit.parameters.push_back({"gauges." + reference + ".gain", 1.0, g, sd});
}

// Each shot's records with the model at the nominal and the fitted values, and the RMS of both
// over the compared samples (the figures and the per-shot residuals).
std::vector<ShotSignals> shot_signals(const std::vector<Shot>& shots,
                                      const std::vector<LsParameter>& list,
                                      const std::vector<double>& fitted, Tables& tables) {
  std::vector<double> nominal(list.size());
  for (std::size_t j = 0; j < list.size(); ++j) nominal[j] = list[j].start;
  std::vector<ShotSignals> all;
  for (const Shot& s : shots) {
    ShotSignals out;
    out.scene = s.scene;
    out.kind = s.kind;
    out.source_gauge = s.source_gauge;
    out.time_s = s.time_s;
    out.source = s.source;
    std::vector<double> rn, rf;
    for (const Target& t : s.targets) {
      out.gauges.push_back(t.gauge);
      out.measured.push_back(t.measured);
      out.nominal.push_back(model_of(s, t, nominal, tables));
      out.fitted.push_back(model_of(s, t, fitted, tables));
      std::vector<char> mask(s.time_s.size(), 0);
      for (std::size_t i : t.samples) {
        mask[i] = 1;
        rn.push_back(t.residual(i, out.nominal.back()[i], s.peak));
        rf.push_back(t.residual(i, out.fitted.back()[i], s.peak));
      }
      out.fitted_window.push_back(std::move(mask));
    }
    out.rms_nominal = rms(rn);
    out.rms_fitted = rms(rf);
    all.push_back(std::move(out));
  }
  return all;
}

}  // namespace

CalibrationFit calibrate_bars(const std::vector<CalibrationShot>& input,
                              const CalibrateOptions& options) {
  const PreparedShots prepared = prepare_shots(input);
  // Tabulated a little beyond the highest cut-off any trial wave speed asks for.
  Tables tables(1.05 * prepared.fa_max);
  const std::vector<LsParameter>& list = prepared.params.list();
  const std::vector<LsGroup> groups = residual_groups(prepared.shots, tables);
  LsOptions lo;
  lo.threads = options.threads;
  lo.max_iterations = options.max_iterations;
  lo.relative_step = 1e-4;
  lo.progress = options.progress;
  const LsResult r = solve_least_squares(list, groups, lo);

  CalibrationFit fit;
  fit.iterations = r.iterations;
  fit.converged = r.converged;
  fit.residuals = r.residuals;
  // What reading the records assumed comes first, then what the solve found.
  for (const Shot& s : prepared.shots)
    fit.warnings.insert(fit.warnings.end(), s.warnings.begin(), s.warnings.end());
  fit.warnings.insert(fit.warnings.end(), r.warnings.begin(), r.warnings.end());
  std::vector<std::string> timing_free;
  const std::vector<double> timing_weight =
      timing_undetermined(prepared.shots, list, r.value, timing_free);
  double independent = 0;  // the low-passed residuals' independent count (Target::noise_share)
  for (const Shot& s : prepared.shots)
    for (const Target& t : s.targets)
      independent += t.noise_share * static_cast<double>(t.samples.size());
  fitted_parameters(list, r, independent, timing_weight,
                    rest_level_errors(prepared.shots, r.value, tables),
                    source_noise(prepared.shots, r.value, tables, r.jacobian), fit);
  // The Jacobian's weak directions first, then what the travel times leave free besides.
  fit.undetermined.insert(fit.undetermined.end(), timing_free.begin(), timing_free.end());
  fit.calibration = calibration_of(input, fit.parameters, prepared.reference);
  make_gains_absolute(prepared.shots, r.value, prepared.reference, fit);
  fit.shots = shot_signals(prepared.shots, list, r.value, tables);
  return fit;
}

}  // namespace shpb
