#include "analysis/processing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "analysis/pulse_window.hpp"
#include "core/csv_writer.hpp"  // format_double
#include "core/error.hpp"

namespace shpb {
namespace {

// The face window runs this fraction of the incident duration past its end, so the
// transmitted pulse (delayed by the specimen transit) is not cut.
constexpr double kWindowTail = 0.15;
// Equilibrium is only judged where the mean force is above this fraction of its peak.
constexpr double kMeanForceForEquilibrium = 0.2;

BarSide side_of(const BarSpec& b) {
  return {b.material.youngs_modulus_Pa, b.area_m2, b.material.wave_speed_m_s()};
}
BarWaveguide waveguide_of(const BarSpec& b) {
  return {0.5 * b.diameter_m, b.material.wave_speed_m_s(), b.material.poisson_ratio};
}

std::size_t index_at(const std::vector<double>& t, double time) {
  const auto it = std::lower_bound(t.begin(), t.end(), time);
  return static_cast<std::size_t>(it - t.begin());
}

}  // namespace

KolskySetup resolve_setup(const Scene& scene, const std::vector<std::string>& available) {
  const std::string file = scene.file.string();
  if (!scene.specimen)
    throw input_error(file, "specimen", "missing", "processing needs the specimen bar named");
  const std::size_t s = *scene.specimen;
  if (s == 0 || s + 1 >= scene.bars.size())
    throw input_error(file, "specimen", scene.bars[s].name,
                      "needs a bar on each side (incident and transmitter)");
  const BarSpec& inc = scene.bars[s - 1];
  const BarSpec& tra = scene.bars[s + 1];
  auto has = [&](const std::string& g) {
    return std::find(available.begin(), available.end(), g) != available.end();
  };
  KolskySetup k;
  for (const auto& g : inc.gauges)
    if (has(g.name)) {
      k.incident_gauge = g.name;
      k.incident_distance_m = inc.length_m - g.position_m;
      break;
    }
  for (const auto& g : tra.gauges)
    if (has(g.name)) {
      k.transmitted_gauge = g.name;
      k.transmitted_distance_m = g.position_m;
      break;
    }
  std::string names;
  for (const auto& a : available) names += (names.empty() ? "" : ", ") + a;
  if (k.incident_gauge.empty())
    throw input_error(file, "bars[" + std::to_string(s - 1) + "].gauges", "\"" + inc.name + "\"",
                      "no gauge of the incident bar has a signal (signals: " + names + ")");
  if (k.transmitted_gauge.empty())
    throw input_error(file, "bars[" + std::to_string(s + 1) + "].gauges", "\"" + tra.name + "\"",
                      "no gauge of the transmitter bar has a signal (signals: " + names + ")");
  k.front = side_of(inc);
  k.back = side_of(tra);
  k.front_waveguide = waveguide_of(inc);
  k.back_waveguide = waveguide_of(tra);
  // Pochhammer–Chree tables are computed for 0 ≤ ν ≤ 0.49 (docs/methods.md §5): bar steels,
  // aluminium, titanium and PMMA lie well inside; auxetic (ν < 0) bars are not supported.
  for (const std::size_t b : {s - 1, s + 1})
    if (const double nu = scene.bars[b].material.poisson_ratio; !(nu >= 0 && nu <= 0.49))
      throw input_error(file, "bars[" + std::to_string(b) + "].material.poisson_ratio",
                        format_double(nu),
                        "must be in [0, 0.49] for a bar whose pulses are processed (dispersion "
                        "tables cover that range; auxetic bars are not supported)");
  k.specimen = {scene.bars[s].length_m, scene.bars[s].area_m2};
  k.incident_impedance_kg_s = inc.impedance_kg_s();
  if (s >= 2) {
    k.striker_impedance_kg_s = scene.bars[s - 2].impedance_kg_s();
    if (scene.bars[s - 2].velocity_m_s != 0)
      k.striker_velocity_m_s = std::abs(scene.bars[s - 2].velocity_m_s);
  }
  return k;
}

std::vector<std::string> signal_warnings(const GaugeSignals& signals) {
  std::vector<std::string> warnings;
  if (signals.time_s.size() < kMinRecordSamples)
    warnings.push_back("the record has only " + std::to_string(signals.time_s.size()) +
                       " samples: too few to resolve a pulse (check the sample rate)");
  for (std::size_t g = 0; g < signals.gauges.size(); ++g) {
    const std::vector<double>& x = signals.strain[g];
    if (x.empty()) continue;
    const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
    for (const double extreme : {*hi, *lo}) {
      if (extreme == 0) continue;
      std::size_t run = 0, longest = 0;
      for (double v : x) longest = std::max(longest, run = v == extreme ? run + 1 : 0);
      if (longest >= kClippedRun) {
        warnings.push_back("gauge \"" + signals.gauges[g] + "\": " + std::to_string(longest) +
                           " consecutive samples at the record's extreme " +
                           format_double(extreme) +
                           ": the signal looks clipped (amplifier or digitizer range); pulses and "
                           "the striker velocity inferred from it are too small");
        break;
      }
    }
  }
  return warnings;
}

ProcessingResult process_signals(const GaugeSignals& signals, const KolskySetup& k,
                                 const ProcessingOptions& options) {
  ProcessingResult r;
  r.warnings = signal_warnings(signals);
  const auto* inc_raw = signals.find(k.incident_gauge);
  const auto* tra_raw = signals.find(k.transmitted_gauge);
  if (!inc_raw || !tra_raw) throw std::logic_error("process_signals: gauge without a signal");
  const double dt = signals.dt_s;
  const auto& t = signals.time_s;
  const std::size_t n = t.size();

  // Baseline removed; polarity checked (the first large excursion of each gauge is compressive).
  auto prepare = [&](const std::vector<double>& raw, const std::string& gauge) {
    const Baseline b = estimate_baseline(raw);
    std::vector<double> x(raw.size());
    for (std::size_t i = 0; i < raw.size(); ++i) x[i] = raw[i] - b.level;
    const auto p = find_first_pulse(x, {0.0, b.noise});
    if (!p)
      throw input_error(options.scene_file, "measurement.channels", "gauge \"" + gauge + "\"",
                        "its signal never rises above its noise: no pulse to process");
    if (p->sign > 0) {
      for (double& v : x) v = -v;
      r.warnings.push_back("gauge \"" + gauge +
                           "\": its first pulse is tensile; a compression "
                           "test's first pulse is compressive, so the signal was inverted (check "
                           "the channel's `invert`)");
    }
    return std::pair{x, b.noise};
  };
  auto [inc, inc_noise] = prepare(*inc_raw, k.incident_gauge);
  auto [tra, tra_noise] = prepare(*tra_raw, k.transmitted_gauge);
  (void)tra_noise;

  // Incident window on the gauge clock: detected, or the scene's.
  std::size_t on = 0, end = 0;
  if (options.windows.incident) {
    on = index_at(t, options.windows.incident->start_s);
    end = index_at(t, options.windows.incident->end_s);
    if (!(end > on + 2) || end > n)
      throw input_error(options.scene_file, "measurement.windows.incident", "",
                        "the window lies outside the record or is shorter than 3 samples");
  } else {
    const auto p = find_first_pulse(inc, {0.0, inc_noise});
    on = p->onset;
    end = p->end;
    r.incident_window.detected = true;
  }
  const double c_front = k.front.c0_m_s, c_back = k.back.c0_m_s;
  const double duration = t[end - 1] - t[on];
  r.incident_window = {k.incident_gauge, t[on], t[end - 1], r.incident_window.detected};

  // Shifts to the faces: incident forward by d_I, reflected back by d_I, transmitted back by d_T;
  // manual reflected/transmitted windows add a pure time shift that puts their start at the
  // incident's face start.
  const double d_i = k.incident_distance_m, d_t = k.transmitted_distance_m;
  const double face_start = t[on] + d_i / c_front;
  double extra_r = 0, extra_t = 0;
  const double expected_r = t[on] + 2 * d_i / c_front;
  if (options.windows.reflected) extra_r = options.windows.reflected->start_s - expected_r;
  if (options.windows.transmitted)
    extra_t = options.windows.transmitted->start_s - d_t / c_back - face_start;
  r.shift_incident_s = d_i / c_front;
  r.shift_reflected_s = -d_i / c_front - extra_r;
  r.shift_transmitted_s = -d_t / c_back - extra_t;
  r.reflected_window = {k.incident_gauge, expected_r + extra_r, expected_r + extra_r + duration,
                        !options.windows.reflected};
  // Alignment check: where the reflected pulse really starts against where geometry puts it.
  {
    const auto i0 = index_at(t, t[end - 1]);
    const auto i1 = index_at(t, expected_r + duration);
    if (const auto o = find_onset(inc, {0.0, inc_noise}, +1.0, i0, i1))
      r.reflected_onset_offset_s = t[*o] - expected_r;
  }

  // Propagation (Pochhammer–Chree or pure delay), strains and — with Tyas–Pope factors —
  // separate stress pulses.
  const DispersionSpec& ds = options.dispersion;
  PropagationOptions po;
  po.dispersion = ds.correction;
  auto cutoff_fa = [&](const BarWaveguide& w) {
    if (ds.cutoff_fa_c0) return *ds.cutoff_fa_c0;
    return ds.cutoff_Hz ? *ds.cutoff_Hz * w.radius_m / w.c0_m_s : kDefaultCutoffFaOverC0;
  };
  // The mode is tabulated only for a correction, and only up to the highest cut-off asked of its
  // Poisson ratio; the corrections share their FFT plans (one per padded length).
  std::optional<DispersionTable> front_table, back_own;
  if (ds.correction) {
    const bool shared = k.back_waveguide.poisson == k.front_waveguide.poisson;
    const double fa_front = cutoff_fa(k.front_waveguide), fa_back = cutoff_fa(k.back_waveguide);
    front_table.emplace(DispersionTable::up_to(k.front_waveguide.poisson,
                                               shared ? std::max(fa_front, fa_back) : fa_front));
    if (!shared) back_own.emplace(DispersionTable::up_to(k.back_waveguide.poisson, fa_back));
  }
  const DispersionTable* front = front_table ? &*front_table : nullptr;
  const DispersionTable* back = back_own ? &*back_own : front;
  FftPlans plans;
  // A manual window's extra shift is a pure delay after the move.
  auto delayed = [&](std::vector<double> y, double extra) {
    if (extra == 0) return y;
    std::vector<double> z(y.size());
    delay_by_interpolation(y, -extra / dt, z);
    return z;
  };
  auto moved = [&](const std::vector<double>& x, const BarWaveguide& w,
                   const DispersionTable* table, double distance, double extra, AmplitudeFactor a) {
    PropagationOptions o = po;
    o.amplitude = a;
    o.cutoff_fa_over_c0 = cutoff_fa(w);
    if (!ds.correction) {
      Propagator p(w, o);
      return delayed(p.propagate(x, dt, distance), extra);
    }
    const DispersionTable& tab = *table;
    const std::string key =
        ds.cutoff_fa_c0 ? "measurement.dispersion.cutoff_fa_c0" : "measurement.dispersion.cutoff";
    if (o.cutoff_fa_over_c0 > tab.max_normalized_frequency())
      throw input_error(options.scene_file, key, "f·a/c0 = " + format_double(o.cutoff_fa_over_c0),
                        "cut-off beyond the tabulated mode");
    if (a != AmplitudeFactor::kNone && o.cutoff_fa_over_c0 >= tab.m1_pole_normalized_frequency())
      throw input_error(options.scene_file, key, "f·a/c0 = " + format_double(o.cutoff_fa_over_c0),
                        "with amplitude factors the cut-off must lie below the m1 pole (f·a/c0 = " +
                            std::to_string(tab.m1_pole_normalized_frequency()) + ")");
    Propagator p(tab, w, o, &plans);
    return delayed(p.propagate(x, dt, distance), extra);
  };
  const auto kin = ds.amplitude_factors ? AmplitudeFactor::kStrain : AmplitudeFactor::kNone;
  const auto ei = moved(inc, k.front_waveguide, front, d_i, 0, kin);
  const auto er = moved(inc, k.front_waveguide, front, -d_i, extra_r, kin);
  const auto et = moved(tra, k.back_waveguide, back, -d_t, extra_t, kin);
  std::vector<double> fi = ei, fr = er, ft = et;
  if (ds.amplitude_factors) {
    fi = moved(inc, k.front_waveguide, front, d_i, 0, AmplitudeFactor::kStress);
    fr = moved(inc, k.front_waveguide, front, -d_i, extra_r, AmplitudeFactor::kStress);
    ft = moved(tra, k.back_waveguide, back, -d_t, extra_t, AmplitudeFactor::kStress);
  }
  if (ds.correction)
    r.cutoff_Hz =
        cutoff_fa(k.front_waveguide) * k.front_waveguide.c0_m_s / k.front_waveguide.radius_m;

  // Common window at the faces: the incident duration plus a tail, never reaching the next
  // reflection of the incident pulse (2 d_I / c0 later) nor the record's end.
  double face_end = face_start + (1 + kWindowTail) * duration;
  face_end = std::min({face_end, face_start + 2 * d_i / c_front - dt, t.back()});
  const std::size_t a = index_at(t, face_start), b = std::min(index_at(t, face_end) + 1, n);
  if (!(b > a + 4))
    throw input_error(options.scene_file, "measurement", "gauge \"" + k.incident_gauge + "\"",
                      "the pulse window at the specimen faces lies outside the record");
  r.face_start_s = t[a];
  r.face_end_s = t[b - 1];
  r.transmitted_window = {k.transmitted_gauge, t[a] - r.shift_transmitted_s,
                          t[b - 1] - r.shift_transmitted_s, !options.windows.transmitted};
  auto cut = [&](const std::vector<double>& v) {
    return std::vector<double>(v.begin() + static_cast<std::ptrdiff_t>(a),
                               v.begin() + static_cast<std::ptrdiff_t>(b));
  };
  r.time_s = cut(t);
  r.incident = cut(ei);
  r.reflected = cut(er);
  r.transmitted = cut(et);
  r.curve = reduce_pulses(r.incident, r.reflected, r.transmitted, cut(fi), cut(fr), cut(ft), dt,
                          k.front, k.back, k.specimen);

  // Summary numbers.
  const std::size_t m = r.time_s.size();
  const std::size_t inc_end = std::min(m, index_at(r.time_s, face_start + duration));
  r.incident_plateau_strain = plateau_level(r.incident, 0, inc_end, -1.0);
  // Striker on the incident bar: F1 = Z_s Z_b V/(Z_s + Z_b) = E A ε (docs/methods.md §4).
  const double zb = k.incident_impedance_kg_s;
  const double zs = k.striker_impedance_kg_s.value_or(zb);
  r.inferred_striker_velocity_m_s = k.front.youngs_modulus_Pa * k.front.area_m2 *
                                    r.incident_plateau_strain * (zs + zb) / (zs * zb);
  r.plateau_strain_rate_1_s = plateau_level(r.curve.strain_rate_1_s, 0, m, 1.0);
  r.peak_stress_Pa =
      *std::max_element(r.curve.stress_3wave_Pa.begin(), r.curve.stress_3wave_Pa.end());
  r.max_strain = *std::max_element(r.curve.strain.begin(), r.curve.strain.end());
  double peak_force = 0;
  for (std::size_t i = 0; i < m; ++i)
    peak_force = std::max(peak_force, r.curve.force_front_N[i] + r.curve.force_back_N[i]);
  for (std::size_t i = 0; i < m; ++i)
    if (r.curve.force_front_N[i] + r.curve.force_back_N[i] >=
            kMeanForceForEquilibrium * peak_force &&
        r.curve.equilibrium_ratio[i] <= kEquilibriumThreshold) {
      r.time_to_equilibrium_s = r.time_s[i] - r.time_s[0];
      break;
    }
  return r;
}

}  // namespace shpb
