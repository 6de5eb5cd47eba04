// The files of `shpb calibrate` (docs/outputs.md): calibration.json (what a scene's "calibration"
// names), summary.json and one CSV of measured and modelled signals per shot.
#include "fit/calibration_report.hpp"

#include <nlohmann/json.hpp>
#include <string>

#include "core/checked_write.hpp"
#include "core/csv_writer.hpp"
#include "core/output_folder.hpp"
#include "fit/fit_interval.hpp"
#include "output_schema.hpp"
#include "version.hpp"

namespace shpb {
namespace {

nlohmann::json optional(const std::optional<double>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json();
}

}  // namespace

void write_calibration_outputs(CalibrationFit& fit, const std::filesystem::path& output,
                               const std::vector<std::filesystem::path>& inputs) {
  nlohmann::json shot_list = nlohmann::json::array();
  for (std::size_t k = 0; k < fit.shots.size(); ++k) {
    const ShotSignals& s = fit.shots[k];
    shot_list.push_back({{"scene", s.scene},
                         {"kind", s.kind},
                         {"source_gauge", s.source_gauge},
                         {"gauges", s.gauges},
                         {"signals", "shot-" + std::to_string(k + 1) + ".csv"},
                         {"rms_of_peak", {{"nominal", s.rms_nominal}, {"fitted", s.rms_fitted}}}});
  }
  fit.calibration.provenance = {{"version", kVersion},
                                {"shots", shot_list},
                                {"undetermined", fit.undetermined},
                                {"warnings", fit.warnings}};
  OutputFolder out(output, "calibrate", inputs);
  write_text_file(out.file("calibration.json"),
                  calibration_to_json(fit.calibration).dump(2) + "\n");
  for (std::size_t k = 0; k < fit.shots.size(); ++k) {
    const ShotSignals& s = fit.shots[k];
    std::vector<std::string> header = {schema::calibration_shot::time_s,
                                       s.source_gauge + "_source"};
    for (const auto& g : s.gauges)
      for (const char* what : {"_measured", "_nominal", "_fitted", "_compared"})
        header.push_back(g + what);
    CsvWriter csv(out.file("shot-" + std::to_string(k + 1) + ".csv"), header);
    std::vector<double> row(header.size());
    for (std::size_t i = 0; i < s.time_s.size(); ++i) {
      row[0] = s.time_s[i];
      row[1] = s.source[i];
      for (std::size_t g = 0; g < s.gauges.size(); ++g) {
        row[2 + 4 * g] = s.measured[g][i];
        row[3 + 4 * g] = s.nominal[g][i];
        row[4 + 4 * g] = s.fitted[g][i];
        row[5 + 4 * g] = s.fitted_window[g][i];
      }
      csv.row(row);
    }
    csv.close();
  }
  nlohmann::json parameters = nlohmann::json::array();
  for (const auto& p : fit.parameters) {
    nlohmann::json ci;
    if (p.sd) ci = {p.value - kNormalZ95 * *p.sd, p.value + kNormalZ95 * *p.sd};
    parameters.push_back({{"name", p.name},
                          {"nominal", p.nominal},
                          {"value", p.value},
                          {"sd", optional(p.sd)},
                          {"ci95", ci}});
  }
  write_text_file(
      out.file("summary.json"),
      nlohmann::json{
          {"version", kVersion},
          {"command", "calibrate"},
          {"scenes", shot_list},
          {"calibration", "calibration.json"},
          {"reference_gauge", fit.calibration.reference_gauge},
          {"parameters", parameters},
          {"how",
           "least squares (Ceres, Levenberg-Marquardt) of each returning pulse modelled as the "
           "source pulse moved along its way with Pochhammer-Chree dispersion, times the "
           "channel's gain, delayed by its delay, against its record low-passed as the model; sd "
           "from the Jacobian at the optimum, s^2 (J^T J)^-1 with s^2 = (sum r^2 less the source "
           "noise's share) / (N' - P), N' the low-passed residuals' independent count, plus the "
           "source record's noise and each record's baseline level carried through the fit; ci95 "
           "= value +- 1.96 sd"},
          {"residuals", fit.residuals},
          {"iterations", fit.iterations},
          {"converged", fit.converged},
          {"reciprocal_condition", fit.reciprocal_condition},
          {"undetermined", fit.undetermined},
          {"warnings", fit.warnings}}
              .dump(2) +
          "\n");
  out.commit();
}

}  // namespace shpb
