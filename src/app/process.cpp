// `shpb process SCENE -o DIR [--signals FILE]` (docs/commands.md, docs/outputs.md): gauge signals → pulses at the
// specimen faces → 1/2/3-wave stress–strain curves. Everything is read and checked before the
// output folder is created.
#include <malloc.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "analysis/processing.hpp"
#include "analysis/specimen_corrections.hpp"
#include "app/commands.hpp"
#include "core/checked_write.hpp"
#include "core/csv_writer.hpp"
#include "core/error.hpp"
#include "core/output_folder.hpp"
#include "core/signal_gauges.hpp"
#include "core/signal_reader.hpp"
#include "version.hpp"

namespace shpb {
namespace {

nlohmann::json window_json(const WindowReport& w) {
  return {{"gauge", w.gauge},
          {"start_s", w.start_s},
          {"end_s", w.end_s},
          {"source", w.detected ? "detected" : "scene"}};
}

void check_finite(const ProcessingResult& r) {
  auto all = [](const std::vector<double>& v) {
    for (double x : v)
      if (!std::isfinite(x)) return false;
    return true;
  };
  const Curve& c = r.curve;
  for (const auto* v :
       {&r.incident, &r.reflected, &r.transmitted, &c.strain_rate_1_s, &c.strain,
        &c.stress_3wave_Pa, &c.true_strain, &c.true_stress_Pa, &c.equilibrium_ratio})
    if (!all(*v)) throw NumericalError("process: the reduction produced a non-finite value");
  if (c.strain.size() && *std::max_element(c.strain.begin(), c.strain.end()) >= 1)
    throw NumericalError(
        "process: engineering strain reached 1 (the specimen would have no length "
        "left): check the bridge factors, the specimen length and the windows");
}

}  // namespace

int run_process(const ProcessArgs& args) {
  // A long record passes through buffers of tens of MB (file, fields, columns, FFT): taken from
  // the heap and, once freed, reused instead of returned to the kernel and faulted in again
  // (1 M-row record: 70 700 -> 40 400 page faults, system time 0.17 -> 0.08 s). A glibc that
  // refuses the values keeps its defaults.
  constexpr int kHeapBuffers = 1 << 30;
  mallopt(M_MMAP_THRESHOLD, kHeapBuffers);
  mallopt(M_TRIM_THRESHOLD, kHeapBuffers);
  const Scene scene = read_scene(args.scene);
  std::vector<std::string> gauges;
  for (const auto& b : scene.bars)
    for (const auto& g : b.gauges) gauges.push_back(g.name);

  MeasurementSpec m;
  ProcessingOptions options;
  bool simulated = false;
  if (args.signals) {
    // A gauges.csv written by `shpb simulate` (time_s + one strain column per gauge): signals of
    // the 1D bar model, which does not disperse, so the faces are reached by a pure delay.
    simulated = true;
    const KolskySetup probe = resolve_setup(scene, gauges);
    m.file = *args.signals;
    m.format = SignalFormat::kCsv;
    m.time_column.name = "time_s";
    for (const auto& g : {probe.incident_gauge, probe.transmitted_gauge}) {
      ChannelSpec ch;
      ch.gauge = g;
      ch.column.name = g;
      ch.unit = SignalUnit::kStrain;
      m.channels.push_back(ch);
    }
    options.dispersion.correction = false;
  } else {
    if (!scene.measurement)
      throw input_error(scene.file.string(), "measurement", "(missing)",
                        "needed to process measured signals (or give --signals FILE)");
    m = *scene.measurement;
    if (m.channels.empty())
      throw input_error(
          scene.file.string(), "measurement.channels", "(missing)",
          "a list of {\"gauge\", \"column\", \"unit\", ...} to process measured signals");
    options.dispersion = m.dispersion;
    options.windows = m.windows;
  }
  options.scene_file = scene.file.string();
  const GaugeSignals signals = read_gauge_signals(m, {});
  const KolskySetup setup = resolve_setup(scene, signals.gauges);
  ProcessingResult r = process_signals(signals, setup, options);
  // Specimen corrections (docs/methods.md §8), also for simulated signals when the scene asks.
  const CorrectionsSpec corrections =
      scene.measurement ? scene.measurement->corrections : CorrectionsSpec{};
  const BarSpec& specimen_bar = scene.bars[*scene.specimen];
  const CorrectionReport removed = apply_specimen_corrections(
      r.curve, signals.dt_s,
      {specimen_bar.length_m, specimen_bar.area_m2, specimen_bar.material.density_kg_m3},
      {corrections.friction, corrections.inertia});
  if (corrections.friction || corrections.inertia)
    r.peak_stress_Pa =
        *std::max_element(r.curve.stress_3wave_Pa.begin(), r.curve.stress_3wave_Pa.end());
  check_finite(r);

  std::vector<std::string> warnings = signals.warnings;
  warnings.insert(warnings.end(), r.warnings.begin(), r.warnings.end());
  // What was assumed is said even with --quiet (which silences progress only).
  for (const auto& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());

  std::vector<std::filesystem::path> inputs = scene_inputs(scene);
  inputs.push_back(m.file);
  for (const ChannelSpec& c : m.channels) inputs.push_back(c.file);
  OutputFolder out(args.output, "process", inputs);
  {
    CsvWriter p(out.file("pulses.csv"), {"time_s", "incident", "reflected", "transmitted"});
    for (std::size_t i = 0; i < r.time_s.size(); ++i)
      p.row({r.time_s[i], r.incident[i], r.reflected[i], r.transmitted[i]});
    p.close();
  }
  {
    const Curve& c = r.curve;
    CsvWriter w(out.file("curve.csv"),
                {"time_s", "strain_rate_1_s", "strain", "stress_1wave_Pa", "stress_2wave_Pa",
                 "stress_3wave_Pa", "true_strain", "true_stress_Pa", "equilibrium_ratio",
                 "strain_rate_1wave_1_s", "force_front_N", "force_back_N"});
    for (std::size_t i = 0; i < r.time_s.size(); ++i)
      w.row({r.time_s[i], c.strain_rate_1_s[i], c.strain[i], c.stress_1wave_Pa[i],
             c.stress_2wave_Pa[i], c.stress_3wave_Pa[i], c.true_strain[i], c.true_stress_Pa[i],
             c.equilibrium_ratio[i], c.strain_rate_1wave_1_s[i], c.force_front_N[i],
             c.force_back_N[i]});
    w.close();
  }
  nlohmann::json s;
  s["version"] = kVersion;
  s["command"] = "process";
  s["scene"] = args.scene.string();
  s["signals"] = {{"source", simulated ? "simulated (--signals)" : "measurement"},
                  {"file", m.file.string()},
                  {"samples", signals.time_s.size()},
                  {"sample_interval_s", signals.dt_s},
                  {"incident_gauge", setup.incident_gauge},
                  {"transmitted_gauge", setup.transmitted_gauge}};
  s["warnings"] = warnings;
  s["conventions"] =
      "pulses.csv: strains at the specimen faces, tension positive, on the signals' clock; "
      "curve.csv: compression positive, strain and strain rate from the 3-wave reduction, true "
      "values from the 3-wave stress (after the corrections listed under corrections)";
  nlohmann::json disp = {
      {"correction", options.dispersion.correction ? "pochhammer-chree" : "none"},
      {"amplitude_factors", options.dispersion.amplitude_factors}};
  if (options.dispersion.correction) disp["cutoff_Hz"] = r.cutoff_Hz;
  if (simulated)
    disp["reason"] = "signals of the 1D bar model do not disperse: pure delay by distance/c0";
  s["dispersion"] = disp;
  s["windows"] = {{"incident", window_json(r.incident_window)},
                  {"reflected", window_json(r.reflected_window)},
                  {"transmitted", window_json(r.transmitted_window)},
                  {"specimen_faces", {{"start_s", r.face_start_s}, {"end_s", r.face_end_s}}}};
  s["shifts_s"] = {{"incident", r.shift_incident_s},
                   {"reflected", r.shift_reflected_s},
                   {"transmitted", r.shift_transmitted_s}};
  s["gauge_distances_m"] = {{"incident", setup.incident_distance_m},
                            {"transmitted", setup.transmitted_distance_m}};
  s["alignment"] = {
      {"reflected_onset_minus_expected_s",
       r.reflected_onset_offset_s ? nlohmann::json(*r.reflected_onset_offset_s) : nlohmann::json()},
      {"how",
       "incident forward and reflected/transmitted backward by their gauge distances over "
       "c0 (dispersion-corrected); the detected reflected onset is reported, not applied "
       "(onset picking on a dispersed front is less accurate than the geometry)"}};
  s["incident_plateau_strain"] = r.incident_plateau_strain;
  s["striker_velocity_m_s"] = {
      {"inferred", r.inferred_striker_velocity_m_s},
      {"scene", setup.striker_velocity_m_s
                    ? nlohmann::json(*setup.striker_velocity_m_s)
                    : (scene.measurement && scene.measurement->striker_velocity_m_s
                           ? nlohmann::json(*scene.measurement->striker_velocity_m_s)
                           : nlohmann::json())},
      {"how", "incident plateau at the front face: V = E A eps (Z_s + Z_b)/(Z_s Z_b)"}};
  s["plateau_strain_rate_1_s"] = r.plateau_strain_rate_1_s;
  s["peak_stress_Pa"] = r.peak_stress_Pa;
  s["max_strain"] = r.max_strain;
  s["time_to_equilibrium_s"] =
      r.time_to_equilibrium_s ? nlohmann::json(*r.time_to_equilibrium_s) : nlohmann::json();
  {
    nlohmann::json c = nlohmann::json::object();
    if (corrections.friction) {
      c["friction"] = {
          {"mu", *corrections.friction},
          {"form",
           "Dharan & Hauser (1970): measured = flow stress x (1 + mu d/(3 sqrt(3) L)), "
           "d and L current (volume-conserving)"},
          {"factor_min", removed.friction_factor_min},
          {"factor_max", removed.friction_factor_max}};
    }
    if (corrections.inertia)
      c["inertia"] = {{"form",
                       "3-wave minus flow stress = rho L^2 (eps_dd - eps_d^2)/12 (axial) + rho a^2 "
                       "(eps_dd/8 + eps_d^2/16) (radial; Davies & Hunter 1963, Gorham 1989, "
                       "Forrestal et al. 2007), true rates, L and a current"}};
    nlohmann::json terms = nlohmann::json::object();
    for (const RemovedTerm& t : removed.terms)
      terms[t.name] = {{"median_Pa", t.median_Pa}, {"max_abs_Pa", t.max_abs_Pa}};
    if (!removed.terms.empty()) {
      c["removed_true_stress"] = terms;
      c["removed_where"] = "samples with 3-wave stress >= 20 % of its peak, before correction";
    }
    s["corrections"] = c;
  }
  s["equilibrium_criterion"] = "R = 2|P1-P2|/|P1+P2| <= 0.05 while (P1+P2)/2 >= 20 % of its peak";
  write_text_file(out.file("summary.json"), s.dump(2) + "\n");
  out.commit();
  if (!args.quiet)
    std::fprintf(stderr,
                 "process: window %.6g–%.6g s at the faces; striker ≈ %.4g m/s (inferred); plateau "
                 "strain rate %.4g 1/s; peak 3-wave stress %.4g MPa -> %s\n",
                 r.face_start_s, r.face_end_s, r.inferred_striker_velocity_m_s,
                 r.plateau_strain_rate_1_s, r.peak_stress_Pa / 1e6, args.output.string().c_str());
  return 0;
}

}  // namespace shpb
