#include "analysis/process_outputs.hpp"

#include <cstdio>
#include <string>

#include "core/checked_write.hpp"
#include "core/csv_writer.hpp"
#include "core/error.hpp"
#include "core/number_format.hpp"
#include "core/output_folder.hpp"
#include "model/calibration.hpp"
#include "model/scene_inputs.hpp"
#include "output_schema.hpp"
#include "version.hpp"

namespace shpb {

// summary.json's entries (docs/outputs.md): one pulse window, and the equilibrium's extent.
void to_json(nlohmann::json& j, const WindowReport& w) {
  j = {{"gauge", w.gauge},
       {"start_s", w.start_s},
       {"end_s", w.end_s},
       {"source", w.detected ? "detected" : "scene"}};
}

void to_json(nlohmann::json& j, const Equilibrium& e) {
  auto interval = [](const std::optional<std::pair<double, double>>& p) {
    return p ? nlohmann::json::array({p->first, p->second}) : nlohmann::json();
  };
  j = {{"fraction_of_loaded_time", e.loaded_s ? nlohmann::json(e.fraction) : nlohmann::json()},
       {"loaded_s", interval(e.loaded_s)},
       {"longest_interval_s", interval(e.longest_s)},
       {"holds_until_unloading_from_s",
        e.holds_from_s ? nlohmann::json(*e.holds_from_s) : nlohmann::json()},
       {"first_s", e.first_s ? nlohmann::json(*e.first_s) : nlohmann::json()}};
}

namespace {

void write_pulses(const OutputFolder& out, const ProcessingResult& r) {
  namespace k = schema::pulses;
  CsvWriter p(out.file(k::kFile), {k::time_s, k::incident, k::reflected, k::transmitted});
  for (std::size_t i = 0; i < r.time_s.size(); ++i)
    p.row({r.time_s[i], r.incident[i], r.reflected[i], r.transmitted[i]});
  p.close();
}

void write_json(const OutputFolder& out, const std::string& name, const nlohmann::json& s) {
  write_text_file(out.file(name), s.dump(2) + "\n");
}

nlohmann::json alignment_json(const ProcessOutcome& o) {
  const ProcessingResult& r = o.result;
  const ProcessingOptions& options = o.options;
  return {
      {"reflected_onset_minus_expected_s",
       r.reflected_onset_offset_s ? nlohmann::json(*r.reflected_onset_offset_s) : nlohmann::json()},
      {"transmitted_onset_minus_expected_s", r.transmitted_onset_offset_s
                                                 ? nlohmann::json(*r.transmitted_onset_offset_s)
                                                 : nlohmann::json()},
      {"suspect", r.alignment_suspect},
      {"align", std::string(enum_name(kAlignmentNames, options.align))},
      {"applied",
       {{"reflected",
         r.reflected_at_onset ? "onset" : (options.windows.reflected ? "window" : "geometry")},
        {"transmitted", r.transmitted_at_onset
                            ? "onset"
                            : (options.windows.transmitted ? "window" : "geometry")}}},
      {"area_ratio", r.area_ratio},
      {"reflected_offset_3wave_stress_error", r.reflected_offset_stress_error
                                                  ? nlohmann::json(*r.reflected_offset_stress_error)
                                                  : nlohmann::json()},
      {"how",
       std::string("incident forward and reflected/transmitted backward by their gauge distances "
                   "over c0 (dispersion-corrected)") +
           (options.align == Alignment::kOnsets
                ? "; with align \"onsets\" the reflected and transmitted pulses are shifted "
                  "further so that their detected onsets fall where geometry expects them"
                : "; the detected onsets are reported, not applied (align \"geometry\")") +
           ". reflected_offset_3wave_stress_error: the largest change of the 3-wave stress, as a "
           "fraction of the 1-wave peak, that moving the reflected pulse by its onset offset "
           "makes where the 1-wave stress is >= 20 % of its peak"}};
}

nlohmann::json striker_json(const ProcessOutcome& o) {
  const ProcessingResult& r = o.result;
  const KolskySetup& setup = o.setup;
  return {
      {"inferred",
       setup.pulse_shaper ? nlohmann::json() : nlohmann::json(r.inferred_striker_velocity_m_s)},
      {"meaningful", !setup.pulse_shaper},
      {"scene",
       setup.striker_velocity_m_s ? nlohmann::json(*setup.striker_velocity_m_s) : nlohmann::json()},
      {"how", setup.pulse_shaper
                  ? "not inferred: a pulse shaper lies between the striker and the incident bar, "
                    "so the incident plateau is set by the shaper's flow, not by the striker's "
                    "impedance"
              : setup.front_waveguide.viscoelastic()
                  ? "incident plateau moved back to the struck end through the viscoelastic "
                    "bar's law, as a velocity: V = c0 eps (Z_s + Z_b)/Z_s"
                  : "incident plateau at the front face: V = E A eps (Z_s + Z_b)/(Z_s Z_b)"}};
}

nlohmann::json strain_rate_json(const ProcessOutcome& o) {
  const ProcessingResult& r = o.result;
  const ProcessingOptions& options = o.options;
  return {
      {"plateau_1_s",
       r.strain_rate_has_plateau ? nlohmann::json(r.plateau_strain_rate_1_s) : nlohmann::json()},
      {"plateau_fraction_of_loading", r.strain_rate_plateau_fraction},
      {"mean_over_loading_1_s", r.mean_strain_rate_1_s},
      {"reduction", std::string(enum_name(kPrimaryNames, options.primary))},
      {"window",
       !options.rate_window ? nlohmann::json()
       : options.rate_window->by_strain
           ? nlohmann::json({{"strain", {options.rate_window->from, options.rate_window->to}}})
           : nlohmann::json({{"time_s", {options.rate_window->from, options.rate_window->to}}})},
      {"mean_over_window_1_s",
       r.window_strain_rate_1_s ? nlohmann::json(*r.window_strain_rate_1_s) : nlohmann::json()},
      {"how",
       "plateau: the longest run of samples within +-10 % of the rate's plateau level (median of "
       "the samples above half its 95th percentile) covers at least 30 % of the loading (samples "
       "with a positive rate); otherwise null and only the mean is quoted. window: "
       "measurement.rate_window, the strain or time range (faces' clock) over which "
       "mean_over_window_1_s is the mean rate; of the primary reduction"}};
}

// What the headline peak stress is (processing.hpp, headline_peak_stress).
nlohmann::json peak_stress_from(const ProcessingResult& r) {
  const HeadlinePeak peak = headline_peak_stress(r);
  std::string how;
  if (r.primary == PrimaryReduction::kOneWave)
    how =
        "the primary reduction's: the transmitted face's stress P2/A_s, largest over the loading "
        "(ended where the transmitted stress starts to unload, as its record shows it) of a "
        "straight line fitted to the samples within the half period the transmitter resolves";
  else if (peak.reduction == PrimaryReduction::kOneWave)
    how =
        "the specimen is in equilibrium (reached and held until unloading, or over at least half "
        "its loading), where its two faces' stresses agree: the transmitted face's stress "
        "P2/A_s, largest over the loading (every sample of it, where the 3-wave peak is read "
        "over the samples with R <= 0.05 only, ended where the transmitted stress starts to "
        "unload, as its record shows it) of a straight line fitted to the samples within the "
        "half period the transmitter resolves";
  else
    how =
        "the 3-wave stress, largest over the whole loading, its ring-up and unloading fronts "
        "included, of a straight line fitted to the samples within the half period both bars "
        "resolve: the specimen is not in equilibrium over most of its loading (warnings)";
  return {{"reduction", std::string(enum_name(kPrimaryNames, peak.reduction))}, {"how", how}};
}

nlohmann::json corrections_json(const ProcessOutcome& o) {
  const SpecimenCorrections& corrections = o.corrections;
  const CorrectionReport& removed = o.removed;
  nlohmann::json c = nlohmann::json::object();
  if (corrections.friction) {
    c["friction"] = {{"mu", *corrections.friction},
                     {"form",
                      "Dharan & Hauser (1970): measured = flow stress x (1 + mu d/(3 sqrt(3) L)), "
                      "d and L current (volume-conserving)"},
                     {"factor_min", removed.friction_factor_min},
                     {"factor_max", removed.friction_factor_max}};
  }
  if (corrections.inertia)
    c["inertia"] = {{"form",
                     "3-wave minus flow stress = rho L^2 (eps_dd - eps_d^2)/12 (axial) + radial; "
                     "1-wave minus flow stress = -rho L (v2_d/2 + L (eps_dd - eps_d^2)/6) (axial, "
                     "v2 the transmitted face's velocity) + radial; 2-wave minus flow stress = "
                     "rho L (v1_d/2 - L (eps_dd - eps_d^2)/6) (axial, v1 the incident face's "
                     "velocity) + radial; radial = rho a^2 (eps_dd/8 + "
                     "eps_d^2/16) (Davies & Hunter 1963, Gorham 1989, Forrestal et al. 2007), true "
                     "rates, L and a current"}};
  nlohmann::json terms = nlohmann::json::object();
  for (const RemovedTerm& t : removed.terms)
    terms[t.name] = {{"median_Pa", t.median_Pa}, {"max_abs_Pa", t.max_abs_Pa}};
  if (!removed.terms.empty()) {
    c["removed_true_stress"] = terms;
    c["removed_where"] = "samples with 3-wave stress >= 20 % of its peak, before correction";
  }
  return c;
}

}  // namespace

void write_bar_check(const BarCheckOutcome& o, const Scene& scene, const std::string& scene_display,
                     const std::filesystem::path& output) {
  const BarCheckResult& r = o.result;
  OutputFolder out(output, "process", scene_inputs(scene));
  {
    namespace k = schema::bar_check_pulses;
    CsvWriter p(out.file(k::kFile),
                {k::time_s, k::far_measured, k::far_pochhammer_chree, k::far_time_shift});
    for (std::size_t i = 0; i < r.time_s.size(); ++i)
      p.row({r.time_s[i], r.far_measured[i], r.far_dispersion[i], r.far_time_shift[i]});
  }
  write_json(out, "summary.json", bar_check_summary(o, scene, scene_display));
  out.commit();
}

nlohmann::json bar_check_summary(const BarCheckOutcome& o, const Scene& scene,
                                 const std::string& scene_display) {
  const BarCheckSetup& setup = o.setup;
  const BarCheckResult& r = o.result;
  return {
      {"version", kVersion},
      {"command", "process"},
      {"scene", scene_display},
      {"calibration", calibration_summary(scene)},
      {"check", "bars together (no specimen)"},
      {"near_gauge", setup.near_gauge},
      {"far_gauge", setup.far_gauge},
      {"distance_m", setup.distance_m},
      {"cutoff_Hz", r.cutoff_Hz},
      {"rms_of_peak", {{"pochhammer_chree", r.rms_dispersion}, {"time_shift", r.rms_time_shift}}},
      {"how",
       "the near gauge's first pulse (the rest of its record zeroed) moved by the distance "
       "to the far gauge, with Pochhammer-Chree dispersion and by a plain delay "
       "distance/c0; RMS of the difference from the far record over its pulse (+-20 % of "
       "its length), as a fraction of its peak"},
      {"warnings", o.warnings}};
}

void write_process_outputs(const ProcessOutcome& o, const Scene& scene,
                           const std::string& scene_display, const std::filesystem::path& output) {
  const MeasurementSpec& m = o.measurement;
  const GaugeSignals& signals = o.signals;
  const ProcessingResult& r = o.result;
  std::vector<std::filesystem::path> inputs = scene_inputs(scene);
  inputs.push_back(m.file);
  for (const ChannelSpec& c : m.channels) inputs.push_back(c.file);
  OutputFolder out(output, "process", inputs);
  {  // the signals as read, in strain, tension positive: what the windows were found on
    std::vector<std::string> header = {schema::raw_signals::time_s};
    header.insert(header.end(), signals.gauges.begin(), signals.gauges.end());
    CsvWriter w(out.file(schema::raw_signals::kFile), header);
    std::vector<double> row(header.size());
    for (std::size_t i = 0; i < signals.time_s.size(); ++i) {
      row[0] = signals.time_s[i];
      for (std::size_t g = 0; g < signals.strain.size(); ++g) row[g + 1] = signals.strain[g][i];
      w.row(row);
    }
    w.close();
  }
  write_pulses(out, r);
  // A failed reduction still leaves the pulses at the faces to look at, and says why.
  if (!o.failure.empty()) {
    write_json(out, "summary.json",
               {{"version", kVersion},
                {"command", "process"},
                {"scene", scene_display},
                {"calibration", o.calibration},
                {"error", o.failure},
                {"warnings", o.warnings},
                {"written", "pulses.csv only: the reduction failed"}});
    out.commit();
    throw NumericalError(o.failure + " (pulses.csv written to " + output.string() + ")");
  }
  {
    const std::vector<CurveColumn> columns = curve_columns(o);
    std::vector<std::string> header;
    for (const auto& [name, v] : columns) header.push_back(name);
    CsvWriter w(out.file(schema::curve::kFile), header);
    // The band columns come last; a strain too few draws reach has none (an empty field).
    const std::size_t nominal =
        columns.size() - (o.uncertainty ? uncertainty_band_columns(*o.uncertainty).size() : 0);
    std::vector<double> row(nominal);
    for (std::size_t i = 0; i < r.loading_end; ++i) {
      for (std::size_t j = 0; j < nominal; ++j) row[j] = (*columns[j].second)[i];
      std::string bands;
      for (std::size_t j = nominal; j < columns.size(); ++j) {
        bands.push_back(',');
        bands += format_field((*columns[j].second)[i]);
      }
      w.row(row, bands);
    }
    w.close();
  }
  write_json(out, "summary.json", process_summary(o, scene_display));
  out.commit();
}

nlohmann::json process_summary(const ProcessOutcome& o, const std::string& scene_display) {
  const MeasurementSpec& m = o.measurement;
  const GaugeSignals& signals = o.signals;
  const KolskySetup& setup = o.setup;
  const ProcessingOptions& options = o.options;
  const ProcessingResult& r = o.result;
  const bool simulated = o.simulated;
  const bool one_wave = options.primary == PrimaryReduction::kOneWave;
  nlohmann::json s;
  s["version"] = kVersion;
  s["command"] = "process";
  s["scene"] = scene_display;
  s["calibration"] = o.calibration;
  s["signals"] = {{"source", simulated ? "simulated (--signals)" : "measurement"},
                  {"file", o.signals_shown.empty() ? m.file.string() : o.signals_shown},
                  {"samples", signals.time_s.size()},
                  {"sample_interval_s", signals.dt_s},
                  {"incident_gauge", setup.incident_gauge},
                  {"transmitted_gauge", setup.transmitted_gauge}};
  s["warnings"] = o.warnings;
  s["test"] = options.tension ? "tension" : "compression";
  s["conventions"] =
      std::string(
          "pulses.csv: strains at the specimen faces, tension positive, on the signals' "
          "clock; curve.csv: ") +
      (options.tension ? "tension positive (true strain ln(1+e), true stress s(1+e))"
                       : "compression positive") +
      (one_wave ? ", led by the 1-wave reduction (primary): 1-wave stress against the "
                  "reflected-pulse strain, whose true values are given; the 3-wave columns "
                  "follow"
                : ", strain and strain rate from the 3-wave reduction, true values from the "
                  "3-wave stress (after the corrections listed under corrections)");
  s["primary"] = {
      {"reduction", std::string(enum_name(kPrimaryNames, options.primary))},
      {"stress", one_wave ? schema::curve::stress_1wave_Pa : schema::curve::stress_3wave_Pa},
      {"strain", one_wave ? schema::curve::strain_1wave : schema::curve::strain},
      {"how", one_wave ? "1-wave: transmitted-face stress P2/A_s against the strain of the "
                         "reflected pulse, integral of 2 c0 eps_R / L_s; it does not depend on "
                         "the alignment of the incident and reflected pulses"
                       : "3-wave: the mean of the two face forces over A_s against the integral "
                         "of (v1 - v2)/L_s"}};
  s["reductions"] = {
      {"3-wave",
       {{"peak_stress_Pa", r.peak_stress_3wave_Pa},
        {"max_strain", r.max_strain_3wave},
        {"peak_stress_over_loading_Pa", r.peak_stress_3wave_over_loading_Pa}}},
      {"1-wave", {{"peak_stress_Pa", r.peak_stress_1wave_Pa}, {"max_strain", r.max_strain_1wave}}},
      {"over",
       "the loading (the rows of curve.csv); the 3-wave peak_stress_Pa over its samples in "
       "equilibrium (R <= 0.05) once the specimen reaches equilibrium that lasts until unloading "
       "or is in equilibrium over at least half its loading, else over the loading: "
       "peak_stress_over_loading_Pa includes the ring-up and the unloading edge, where the front "
       "face's force is not the specimen's"}};
  nlohmann::json disp = {
      {"correction", std::string(enum_name(kCorrectionNames, options.dispersion.correction))},
      {"amplitude_factors", options.dispersion.amplitude_factors}};
  if (options.dispersion.correction) disp["cutoff_Hz"] = r.cutoff_Hz;
  const bool law = o.setup.front_waveguide.viscoelastic() || o.setup.back_waveguide.viscoelastic();
  if (simulated)
    disp["reason"] = law ? "signals of the 1D bar model have no geometric dispersion: a "
                           "viscoelastic bar's pulses move through its law alone, an elastic "
                           "bar's by a pure delay distance/c0"
                         : "signals of the 1D bar model do not disperse: pure delay by distance/c0";
  s["dispersion"] = disp;
  s["windows"] = {{"incident", r.incident_window},
                  {"reflected", r.reflected_window},
                  {"transmitted", r.transmitted_window},
                  {"specimen_faces", {{"start_s", r.face_start_s}, {"end_s", r.face_end_s}}}};
  s["shifts_s"] = {{"incident", r.shift_incident_s},
                   {"reflected", r.shift_reflected_s},
                   {"transmitted", r.shift_transmitted_s}};
  s["gauge_distances_m"] = {{"incident", setup.incident_distance_m},
                            {"transmitted", setup.transmitted_distance_m}};
  s["alignment"] = alignment_json(o);
  s["incident_plateau_strain"] = r.incident_plateau_strain;
  s["striker_velocity_m_s"] = striker_json(o);
  s["plateau_strain_rate_1_s"] =
      r.strain_rate_has_plateau ? nlohmann::json(r.plateau_strain_rate_1_s) : nlohmann::json();
  s["strain_rate"] = strain_rate_json(o);
  s["end_of_loading"] = {{"time_s", r.time_s[r.loading_end - 1]},
                         {"how", r.loading_end_how},
                         {"curve_rows", r.loading_end},
                         {"strain_reached", r.max_strain},
                         {"record_max_strain", r.record_max_strain},
                         {"cut_short", r.loading_cut_short},
                         {"note", "curve.csv ends here; pulses.csv keeps the whole window"}};
  s["peak_stress_Pa"] = r.peak_stress_Pa;
  s["peak_stress_from"] = peak_stress_from(r);
  s["max_strain"] = r.max_strain;
  s["time_to_equilibrium_s"] =
      r.time_to_equilibrium_s ? nlohmann::json(*r.time_to_equilibrium_s) : nlohmann::json();
  s["corrections"] = corrections_json(o);
  s["equilibrium_criterion"] =
      "R = 2|P1-P2|/|P1+P2| <= 0.05 while (P1+P2)/2 >= 20 % of its peak (loaded); reached at the "
      "start of the interval with R <= 0.05 that lasts until unloading";
  s["equilibrium"] = r.equilibrium;
  if (o.uncertainty) s["uncertainty"] = uncertainty_summary(*o.uncertainty);
  return s;
}

ProcessedScene process_into(const std::filesystem::path& scene_file,
                            const std::optional<std::filesystem::path>& signals_file,
                            const std::filesystem::path& output,
                            const MonteCarloOptions* monte_carlo, bool print_warnings) {
  ProcessedScene p;
  p.scene = read_scene(scene_file);
  if (!p.scene.specimen) {
    p.bars = check_scene_bars(p.scene, signals_file.has_value(), print_warnings);
    write_bar_check(*p.bars, p.scene, scene_file.string(), output);
  } else {
    p.outcome = process_scene(p.scene, signals_file, print_warnings);
    if (monte_carlo) add_uncertainty(p.scene, *monte_carlo, *p.outcome);
    write_process_outputs(*p.outcome, p.scene, scene_file.string(), output);
  }
  return p;
}

std::string bar_check_headline(const BarCheckOutcome& o, const std::filesystem::path& output) {
  char line[512];
  std::snprintf(line, sizeof line,
                "process: bars together, %s -> %s over %.4g m: RMS %.3g %% of peak with "
                "Pochhammer-Chree dispersion, %.3g %% with a plain time shift -> %s",
                o.setup.near_gauge.c_str(), o.setup.far_gauge.c_str(), o.setup.distance_m,
                100 * o.result.rms_dispersion, 100 * o.result.rms_time_shift,
                output.string().c_str());
  return line;
}

std::string process_headline(const ProcessOutcome& o, const std::filesystem::path& output) {
  const ProcessingResult& r = o.result;
  const HeadlinePeak peak = headline_peak_stress(r);
  char striker[80], rate[120];
  if (o.setup.pulse_shaper)
    std::snprintf(striker, sizeof striker, "striker not inferred (pulse shaper)");
  else
    std::snprintf(striker, sizeof striker, "striker ≈ %.4g m/s (inferred)",
                  r.inferred_striker_velocity_m_s);
  if (r.window_strain_rate_1_s)
    std::snprintf(rate, sizeof rate, "mean strain rate over the rate window %.4g 1/s",
                  *r.window_strain_rate_1_s);
  else
    std::snprintf(rate, sizeof rate, "%s strain rate %.4g 1/s",
                  r.strain_rate_has_plateau ? "plateau" : "no plateau: mean",
                  r.strain_rate_has_plateau ? r.plateau_strain_rate_1_s : r.mean_strain_rate_1_s);
  std::string line(1024, '\0');
  line.resize(static_cast<std::size_t>(std::snprintf(
      line.data(), line.size(),
      "process: window %s–%s s at the faces; %s; %s; peak %s stress %.4g MPa%s -> %s",
      format_resolved(r.face_start_s, o.signals.dt_s, 6).c_str(),
      format_resolved(r.face_end_s, o.signals.dt_s, 6).c_str(), striker, rate,
      std::string(enum_name(kPrimaryNames, peak.reduction)).c_str(), r.peak_stress_Pa / 1e6,
      peak.reduction == o.options.primary ? "" : " (transmitted face, in equilibrium)",
      output.string().c_str())));
  if (o.uncertainty) line.append("\n").append(uncertainty_headline(*o.uncertainty));
  return line;
}

}  // namespace shpb
