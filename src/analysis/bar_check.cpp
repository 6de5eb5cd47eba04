#include "analysis/bar_check.hpp"

#include <algorithm>
#include <cmath>

#include "analysis/dispersion_cutoff.hpp"
#include "analysis/pulse_window.hpp"
#include "analysis/signal_checks.hpp"
#include "core/error.hpp"
#include "core/number_format.hpp"
#include "dispersion/dispersion_table.hpp"

namespace shpb {
namespace {

// The compared window reaches this fraction of the far pulse's length beyond both of its ends,
// and the near pulse is kept with the same margin (the rest of its record, later reflections,
// is zeroed before it is moved).
constexpr double kWindowMargin = 0.2;

}  // namespace

BarCheckSetup resolve_bar_check(const Scene& scene, const std::vector<std::string>& available) {
  const std::string file = scene.file.string();
  struct Place {
    std::size_t bar;
    const GaugeSpec* gauge;
  };
  std::vector<Place> found;
  for (std::size_t b = 0; b < scene.bars.size(); ++b)
    for (const auto& g : scene.bars[b].gauges)
      if (std::find(available.begin(), available.end(), g.name) != available.end())
        found.push_back({b, &g});
  std::sort(found.begin(), found.end(), [](const Place& x, const Place& y) {
    return x.bar != y.bar ? x.bar < y.bar : x.gauge->position_m < y.gauge->position_m;
  });
  if (found.size() < 2)
    throw input_error(file, "measurement.channels", std::to_string(found.size()) + " gauge(s)",
                      "a scene without a specimen is a bars-together check: it needs signals of "
                      "two gauges (near and far)");
  const Place& a = found.front();
  const Place& z = found.back();
  BarCheckSetup s;
  s.near_gauge = a.gauge->name;
  s.far_gauge = z.gauge->name;
  if (a.bar == z.bar) {
    s.distance_m = z.gauge->position_m - a.gauge->position_m;
  } else {
    s.distance_m = scene.bars[a.bar].length_m - a.gauge->position_m + z.gauge->position_m;
    for (std::size_t b = a.bar + 1; b < z.bar; ++b) s.distance_m += scene.bars[b].length_m;
  }
  const BarSpec& bar = scene.bars[a.bar];
  for (std::size_t b = a.bar + 1; b <= z.bar; ++b) {
    const BarSpec& o = scene.bars[b];
    if (!o.has_material ||
        std::abs(o.material.wave_speed_m_s() / bar.material.wave_speed_m_s() - 1) >
            kBarsTogetherSpeedSpread ||
        o.material.density_kg_m3 != bar.material.density_kg_m3 ||
        std::abs(o.diameter_m - bar.diameter_m) > 1e-9)
      throw input_error(file, "bars[" + std::to_string(b) + "]", "\"" + o.name + "\"",
                        "a bars-together check needs bars of one material and diameter between "
                        "its gauges (or name a specimen to process a test)");
  }
  if (!(s.distance_m > 0))
    throw input_error(file, "bars", "gauges \"" + s.near_gauge + "\" and \"" + s.far_gauge + "\"",
                      "the two gauges are at the same place");
  s.waveguide = {0.5 * bar.diameter_m, bar.material.wave_speed_m_s(), bar.material.poisson_ratio};
  for (std::size_t b = a.bar; b <= z.bar; ++b) {
    const BarSpec& o = scene.bars[b];
    const double from = b == a.bar ? a.gauge->position_m : 0.0;
    const double to = b == z.bar ? z.gauge->position_m : o.length_m;
    const BarWaveguide guide{0.5 * o.diameter_m, o.material.wave_speed_m_s(),
                             o.material.poisson_ratio};
    const auto same = [&](const BarWaveguide& w) {
      return w.radius_m == guide.radius_m && w.c0_m_s == guide.c0_m_s && w.poisson == guide.poisson;
    };
    if (!s.path.empty() && same(s.path.back().first))  // one propagation through bars alike
      s.path.back().second += to - from;
    else
      s.path.push_back({guide, to - from});
  }
  return s;
}

BarCheckResult check_bars_together(const GaugeSignals& signals, const BarCheckSetup& s,
                                   const DispersionSpec& ds, const std::string& scene_file) {
  BarCheckResult r;
  const double dt = signals.dt_s;
  const auto& t = signals.time_s;
  const std::size_t n = t.size();
  auto prepared = [&](const std::string& gauge) {
    RestSignal x = rest_signal(signals, gauge, 0.0, scene_file);
    if (!x.first) throw no_pulse_error(signals, gauge, scene_file, "no pulse to check");
    return std::pair{std::move(x.x), *x.first};
  };
  auto [near, pn] = prepared(s.near_gauge);
  auto [far, pf] = prepared(s.far_gauge);
  auto margin = [](const PulseWindow& w) {
    return static_cast<std::size_t>(kWindowMargin * static_cast<double>(w.end - w.onset));
  };
  // Only the near pulse travels: the rest of its record is zeroed.
  const std::size_t keep0 = pn.onset > margin(pn) ? pn.onset - margin(pn) : 0;
  const std::size_t keep1 = std::min(n, pn.end + margin(pn));
  for (std::size_t i = 0; i < n; ++i)
    if (i < keep0 || i >= keep1) near[i] = 0;

  if (s.distance_m / (s.waveguide.c0_m_s * dt) > kMaxDelaySamples)
    throw input_error(scene_file, "measurement.time.unit",
                      "delay " + format_number(s.distance_m / s.waveguide.c0_m_s) + " s = " +
                          format_number(s.distance_m / (s.waveguide.c0_m_s * dt)) + " samples",
                      "expected at most 2^24 samples: is the time unit right?");
  PropagationOptions po;
  // One cut-off in Hz, set on the near gauge's bar as process sets it on the incident bar.
  r.cutoff_Hz = dispersion_cutoff_Hz(ds, s.waveguide);
  // Zeros after the record leave room for the delay (the output keeps the input's length).
  std::vector<double> moved = near;
  moved.resize(n + static_cast<std::size_t>(1.25 * s.distance_m / (s.waveguide.c0_m_s * dt)) + 1,
               0.0);
  std::vector<double> shifted(moved.size());
  double delay_s = 0;
  // Bar by bar, each with its own mode and the cut-off's frequency (one cut-off in Hz).
  for (const auto& [guide, distance] : s.path) {
    delay_s += distance / guide.c0_m_s;
    if (!(distance > 0)) continue;
    PropagationOptions bar_po = po;
    bar_po.cutoff_fa_over_c0 = r.cutoff_Hz * guide.radius_m / guide.c0_m_s;
    const DispersionTable table(guide.poisson);
    if (bar_po.cutoff_fa_over_c0 > table.max_normalized_frequency())
      throw input_error(scene_file, dispersion_cutoff_key(ds),
                        "f·a/c0 = " + format_number(bar_po.cutoff_fa_over_c0),
                        "cut-off beyond the tabulated mode");
    Propagator prop(table, guide, bar_po);
    moved = prop.propagate(moved, dt, distance);
  }
  std::vector<double> padded = near;
  padded.resize(moved.size(), 0.0);
  delay_by_interpolation(padded, delay_s / dt, shifted);

  const std::size_t a = pf.onset > margin(pf) ? pf.onset - margin(pf) : 0;
  const std::size_t b = std::min(n, pf.end + margin(pf));
  double peak = 0, e_d = 0, e_s = 0;
  for (std::size_t i = a; i < b; ++i) {
    r.time_s.push_back(t[i]);
    r.far_measured.push_back(far[i]);
    r.far_dispersion.push_back(moved[i]);
    r.far_time_shift.push_back(shifted[i]);
    peak = std::max(peak, std::abs(far[i]));
    e_d += (moved[i] - far[i]) * (moved[i] - far[i]);
    e_s += (shifted[i] - far[i]) * (shifted[i] - far[i]);
  }
  const double m = static_cast<double>(b - a);
  r.rms_dispersion = std::sqrt(e_d / m) / peak;
  r.rms_time_shift = std::sqrt(e_s / m) / peak;
  return r;
}

}  // namespace shpb
