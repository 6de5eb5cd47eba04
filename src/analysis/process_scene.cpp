// `shpb process` without writing (docs/commands.md): the signals read and checked, the pulses at
// the specimen faces, the 1/2/3-wave reduction.
#include "analysis/process_scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "core/finite_values.hpp"
#include "core/options_check.hpp"
#include "model/calibration.hpp"
#include "output_schema.hpp"

namespace shpb {

namespace {

// What a scene without a specimen must give to be the bars-together check.
void require_bar_check_inputs(const Scene& scene, bool with_signals_file) {
  if (with_signals_file)
    throw input_error(scene.file.string(), "specimen", "(missing)",
                      "--signals reduces a simulated test: name the specimen bar");
  if (!scene.measurement)
    throw input_error(scene.file.string(), "measurement", "(missing)",
                      "a bars-together check needs the measured signals of two gauges");
}

}  // namespace

BarCheckOutcome check_scene_bars(const Scene& scene, bool with_signals_file, bool print_warnings) {
  require_bar_check_inputs(scene, with_signals_file);
  const MeasurementSpec& m = *scene.measurement;
  const GaugeSignals signals = read_gauge_signals(m, {});
  if (print_warnings)
    for (const auto& w : signals.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  BarCheckOutcome o;
  o.setup = resolve_bar_check(scene, signals.gauges);
  o.result = check_bars_together(signals, o.setup, m.dispersion, scene.file.string());
  o.warnings = signals.warnings;
  o.warnings.insert(o.warnings.end(), o.result.warnings.begin(), o.result.warnings.end());
  return o;
}

std::string reduction_failure(const ProcessingResult& r) {
  const Curve& c = r.curve;
  for (const auto* v : {&c.strain_rate_1_s, &c.strain, &c.stress_3wave_Pa, &c.true_strain,
                        &c.true_stress_Pa, &c.equilibrium_ratio, &c.strain_1wave})
    if (!all_finite(*v)) return "process: the reduction produced a non-finite value";
  if (c.strain.size() && *std::max_element(c.strain.begin(), c.strain.end()) >= 1)
    return "process: engineering strain reached 1 (the specimen would have no length "
           "left): check the channels' units and bridge factors, the specimen length and the "
           "windows";
  return "";
}

void use_simulated_signals(ProcessingOptions& options) {
  options.dispersion = {};
  options.dispersion.correction = false;
  options.windows = {};
}

GaugeSignals simulated_signals(const TimeSeries& gauges, const std::vector<std::string>& names) {
  GaugeSignals g;
  g.time_s = gauges.time_s;
  g.dt_s = gauges.samples() > 1 ? gauges.time_s[1] - gauges.time_s[0] : 0.0;
  for (const std::string& name : names) {
    g.gauges.push_back(name);
    g.strain.push_back(gauges.column(name));
  }
  return g;
}

ProcessOutcome process_scene(const Scene& scene,
                             const std::optional<std::filesystem::path>& signals_file,
                             bool print_warnings) {
  if (!scene.specimen) {
    // The command's refusals first (the same lines from the module), then the check it would run.
    require_bar_check_inputs(scene, signals_file.has_value());
    throw input_error(scene.file.string(), "specimen", "(missing)",
                      "name the specimen bar to reduce a test (a scene without one is the "
                      "command's bars-together check)");
  }
  std::vector<std::string> gauges;
  for (const auto& b : scene.bars)
    for (const auto& g : b.gauges) gauges.push_back(g.name);

  ProcessOutcome o;
  MeasurementSpec& m = o.measurement;
  ProcessingOptions& options = o.options = processing_options(scene);
  o.calibration = calibration_summary(scene);
  if (signals_file) {
    // A gauges.csv written by `shpb simulate` (time_s + one strain column per gauge): signals of
    // the 1D bar model, which does not disperse, so the faces are reached by a pure delay.
    o.simulated = true;
    const KolskySetup probe = resolve_setup(scene, gauges);
    m.file = *signals_file;
    m.format = SignalFormat::kCsv;
    m.time_column.name = "time_s";
    for (const auto& g : {probe.incident_gauge, probe.transmitted_gauge}) {
      ChannelSpec ch;
      ch.gauge = g;
      ch.column.name = g;
      ch.unit = SignalUnit::kStrain;
      m.channels.push_back(ch);
    }
    use_simulated_signals(options);
  } else {
    if (!scene.measurement)
      throw input_error(scene.file.string(), "measurement", "(missing)",
                        "needed to process measured signals (or give --signals FILE)");
    m = *scene.measurement;
    if (m.channels.empty())
      throw input_error(
          scene.file.string(), "measurement.channels", "(missing)",
          "a list of {\"gauge\", \"column\", \"unit\", ...} to process measured signals");
  }
  // What was assumed is said even with --quiet (which silences progress only), and as soon as
  // it is known: before any later error stops the run.
  GaugeSignals& signals = o.signals;
  signals = read_gauge_signals(m, {});
  if (print_warnings)
    for (const auto& w : signals.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  const KolskySetup& setup = o.setup = resolve_setup(scene, signals.gauges);
  ProcessedTest processed = process_test(scene, signals, setup, options);
  ProcessingResult& r = o.result = std::move(processed.result);
  o.corrections = processed.corrections;
  o.removed = processed.removed;
  if (print_warnings)
    for (const auto& w : r.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  std::vector<std::string>& warnings = o.warnings = signals.warnings;
  warnings.insert(warnings.end(), r.warnings.begin(), r.warnings.end());
  for (const auto* v : {&r.incident, &r.reflected, &r.transmitted})
    if (!all_finite(*v)) throw NumericalError("process: the pulses hold a non-finite value");
  o.failure = reduction_failure(r);
  return o;
}

void add_uncertainty(const Scene& scene, const MonteCarloOptions& monte_carlo, ProcessOutcome& o) {
  require_valid(monte_carlo);  // --draws, as the command's option check gives it
  if (!scene.measurement || !scene.measurement->uncertainty || !o.failure.empty()) return;
  // The block describes the lab's record (its gauges, channels, correction); simulated signals
  // have none of those uncertainties.
  if (o.simulated) {
    o.warnings.push_back(
        "measurement.uncertainty not propagated: the signals are simulated (--signals)");
    return;
  }
  o.uncertainty =
      propagate_uncertainty(scene, o.measurement, o.signals, o.options, o.result, monte_carlo);
}

namespace {

// The reduction's own columns.
std::vector<CurveColumn> nominal_curve_columns(const ProcessOutcome& o) {
  const ProcessingResult& r = o.result;
  const Curve& c = r.curve;
  namespace k = schema::curve;  // the column names (src/core/output_schema.json)
  if (o.options.primary == PrimaryReduction::kOneWave)
    return {{k::time_s, &r.time_s},
            {k::strain_rate_1wave_1_s, &c.strain_rate_1wave_1_s},
            {k::strain_1wave, &c.strain_1wave},
            {k::stress_1wave_Pa, &c.stress_1wave_Pa},
            {k::true_strain, &c.true_strain},
            {k::true_stress_Pa, &c.true_stress_Pa},
            {k::strain_rate_1_s, &c.strain_rate_1_s},
            {k::strain, &c.strain},
            {k::stress_2wave_Pa, &c.stress_2wave_Pa},
            {k::stress_3wave_Pa, &c.stress_3wave_Pa},
            {k::equilibrium_ratio, &c.equilibrium_ratio},
            {k::force_front_N, &c.force_front_N},
            {k::force_back_N, &c.force_back_N}};
  return {{k::time_s, &r.time_s},
          {k::strain_rate_1_s, &c.strain_rate_1_s},
          {k::strain, &c.strain},
          {k::stress_1wave_Pa, &c.stress_1wave_Pa},
          {k::stress_2wave_Pa, &c.stress_2wave_Pa},
          {k::stress_3wave_Pa, &c.stress_3wave_Pa},
          {k::true_strain, &c.true_strain},
          {k::true_stress_Pa, &c.true_stress_Pa},
          {k::equilibrium_ratio, &c.equilibrium_ratio},
          {k::strain_rate_1wave_1_s, &c.strain_rate_1wave_1_s},
          {k::force_front_N, &c.force_front_N},
          {k::force_back_N, &c.force_back_N},
          {k::strain_1wave, &c.strain_1wave}};
}

}  // namespace

// The band columns of measurement.uncertainty follow (docs/outputs.md).
std::vector<CurveColumn> curve_columns(const ProcessOutcome& o) {
  std::vector<CurveColumn> columns = nominal_curve_columns(o);
  if (o.uncertainty)
    for (const auto& band : uncertainty_band_columns(*o.uncertainty)) columns.push_back(band);
  return columns;
}

}  // namespace shpb
