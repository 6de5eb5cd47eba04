#include "model/calibration.hpp"

#include <cmath>

#include "core/csv_writer.hpp"  // format_double
#include "core/error.hpp"
#include "core/file_digest.hpp"
#include "core/json_document.hpp"
#include "core/json_value.hpp"
#include "model/input_keys.hpp"
#include "model/input_limits.hpp"
#include "model/scene.hpp"

namespace shpb {
namespace {

nlohmann::json value_json(const CalibratedValue& v) {
  return {{"value", v.value}, {"sd", v.sd ? nlohmann::json(*v.sd) : nlohmann::json()}};
}

// density_kg_m3 and youngs_modulus_Pa are the scene's density and ρ c0², written for reading; they
// are checked to be those, not read as values (the calibration sets the wave speed). A file
// `shpb calibrate` wrote reads them back exactly; the tolerance admits one printed again at
// 10 significant digits and refuses any edit of a value.
constexpr double kRecordedValueTolerance = 1e-9;

bool same_value(double a, double b) {
  return std::abs(a - b) <= kRecordedValueTolerance * std::abs(b);
}

CalibratedValue read_value(const JsonValue& v, Dimension d, double lo, double hi) {
  const auto o = v.object(input_keys::kCalibratedValue);
  CalibratedValue c;
  c.value = o.require("value", "the fitted value").quantity_in(d, lo, hi, true, true);
  if (auto sd = o.get("sd"); sd && !sd->json().is_null()) c.sd = sd->non_negative_quantity(d);
  return c;
}

// Gains and delays are relative to the reference gauge's channel: its own delay is 0 and, unless
// `absolute_gain`, its gain 1 (a reference or absolute_gain edited by hand would change nothing
// the scene reads: refused).
void check_reference_gauge(const JsonObject& o, const Calibration& c) {
  const auto given = o.get("reference_gauge");
  if (!given || c.reference_gauge.empty()) return;  // none recorded
  for (const GaugeCalibration& g : c.gauges)
    if (g.gauge == c.reference_gauge) {
      if (g.delay_s.value == 0 && (c.absolute_gain || g.gain.value == 1)) return;
      throw given->error(
          "gains and delays are relative to this gauge's channel, whose gauges[] "
          "entry has gain " +
          format_double(g.gain.value) + " and delay " +
          JsonValue::format(g.delay_s.value, Dimension::kTime) +
          ": expected delay 0 and, unless absolute_gain, gain 1 (a file shpb "
          "calibrate wrote; the reference is not changed by editing it)");
    }
  throw given->error(
      "expected the name of a gauge in gauges[] (the channel the gains and delays "
      "are relative to)");
}

}  // namespace

nlohmann::json calibration_to_json(const Calibration& c) {
  nlohmann::json bars = nlohmann::json::array(), gauges = nlohmann::json::array();
  for (const auto& b : c.bars)
    bars.push_back(
        {{"bar", b.bar},
         {"wave_speed_m_s", value_json(b.wave_speed_m_s)},
         {"poisson_ratio", value_json(b.poisson_ratio)},
         {"density_kg_m3", b.density_kg_m3},
         {"youngs_modulus_Pa", b.density_kg_m3 * b.wave_speed_m_s.value * b.wave_speed_m_s.value}});
  for (const auto& g : c.gauges)
    gauges.push_back({{"gauge", g.gauge},
                      {"bar", g.bar},
                      {"position_m", value_json(g.position_m)},
                      {"gain", value_json(g.gain)},
                      {"delay_s", value_json(g.delay_s)}});
  return {{"format", "shpb calibration 1"},
          {"reference_gauge", c.reference_gauge},
          {"absolute_gain", c.absolute_gain},
          {"bars", bars},
          {"gauges", gauges},
          {"provenance", c.provenance}};
}

namespace {

Calibration read_calibration_objects(const std::filesystem::path& file) {
  const std::string display = file.string();
  const nlohmann::json j = read_json_object_file(file, display);
  const JsonValue root(j, display, "");
  const auto o = root.object(input_keys::kCalibration);
  const auto format = o.require("format", "\"shpb calibration 1\" (a file `shpb calibrate` wrote)");
  if (format.string() != "shpb calibration 1")
    throw format.error("expected \"shpb calibration 1\" (a file `shpb calibrate` wrote)");
  Calibration c;
  if (auto r = o.get("reference_gauge")) c.reference_gauge = r->string();
  if (auto a = o.get("absolute_gain")) c.absolute_gain = a->boolean();
  for (const auto& b : o.require("bars", "a list of calibrated bars").array()) {
    const auto bo = b.object(input_keys::kCalibrationBar);
    BarCalibration bc;
    const auto name = bo.require("bar", "the bar's name");
    bc.bar = name.name();
    for (std::size_t k = 0; k < c.bars.size(); ++k)
      if (c.bars[k].bar == bc.bar)
        throw name.error("calibrated twice (bars[" + std::to_string(k) + "]): one value per bar");
    // Wave speeds of solids lie between about 100 m/s (soft polymers) and 20 km/s.
    bc.wave_speed_m_s = read_value(bo.require("wave_speed_m_s", "{\"value\", \"sd\"}"),
                                   Dimension::kVelocity, 0, 20000);
    bc.poisson_ratio = read_value(bo.require("poisson_ratio", "{\"value\", \"sd\"}"),
                                  Dimension::kDimensionless, 0, 0.5);
    if (auto d = bo.get("density_kg_m3"))
      bc.density_kg_m3 = d->positive_quantity(Dimension::kDensity);
    if (auto e = bo.get("youngs_modulus_Pa")) {
      const double c0 = bc.wave_speed_m_s.value;
      if (!bc.density_kg_m3)
        throw e->error("is density_kg_m3 x wave_speed_m_s^2: needs density_kg_m3 beside it");
      const double modulus = bc.density_kg_m3 * c0 * c0;
      if (!same_value(e->positive_quantity(Dimension::kPressure), modulus))
        throw e->error("expected density_kg_m3 x wave_speed_m_s^2 = " +
                       JsonValue::format(modulus, Dimension::kPressure) +
                       ", which it records: the calibrated modulus is the scene's density times "
                       "wave_speed_m_s squared (edit wave_speed_m_s to change it)");
    }
    c.bars.push_back(bc);
  }
  for (const auto& g : o.require("gauges", "a list of calibrated gauges").array()) {
    const auto go = g.object(input_keys::kCalibrationGauge);
    GaugeCalibration gc;
    const auto name = go.require("gauge", "the gauge's name");
    gc.gauge = name.name();
    for (std::size_t k = 0; k < c.gauges.size(); ++k)
      if (c.gauges[k].gauge == gc.gauge)
        throw name.error("calibrated twice (gauges[" + std::to_string(k) +
                         "]): one value per gauge");
    if (auto b = go.get("bar")) gc.bar = b->string();
    gc.position_m =
        read_value(go.require("position_m", "{\"value\", \"sd\"}"), Dimension::kLength, -1e3, 1e3);
    gc.gain =
        read_value(go.require("gain", "{\"value\", \"sd\"}"), Dimension::kDimensionless, 0, 1e6);
    gc.delay_s = read_value(go.require("delay_s", "{\"value\", \"sd\"}"), Dimension::kTime, -1, 1);
    c.gauges.push_back(gc);
  }
  if (auto p = o.get("provenance")) c.provenance = p->json();
  check_reference_gauge(o, c);
  return c;
}

}  // namespace

// A key refused in one object of the file names the others it belongs to.
Calibration read_calibration_file(const std::filesystem::path& file) {
  return read_placing_keys(file.string(), input_keys::kCalibrationPlaces,
                           [&] { return read_calibration_objects(file); });
}

void apply_calibration(Scene& scene, const Calibration& c, const std::filesystem::path& file) {
  const std::string where = scene.file.string();
  for (std::size_t i = 0; i < c.bars.size(); ++i) {
    const BarCalibration& b = c.bars[i];
    BarSpec* bar = nullptr;
    for (auto& s : scene.bars)
      if (s.name == b.bar) bar = &s;
    if (!bar || !bar->has_material)
      throw input_error(
          file.string(), "bars[" + std::to_string(i) + "].bar", json_quoted(b.bar),
          "no such bar (with a material) in " + where + ": a calibration of other bars");
    MaterialSpec& m = bar->material;
    if (b.density_kg_m3 && !same_value(b.density_kg_m3, m.density_kg_m3))
      throw input_error(file.string(), "bars[" + std::to_string(i) + "].density_kg_m3",
                        JsonValue::format(b.density_kg_m3, Dimension::kDensity),
                        "expected the density of bar \"" + b.bar + "\" in " + where + " (" +
                            JsonValue::format(m.density_kg_m3, Dimension::kDensity) +
                            "): the calibration was made with another; it sets the wave speed, "
                            "the scene the density (run shpb calibrate again with this scene's)");
    set_instantaneous_modulus(m, m.density_kg_m3 * b.wave_speed_m_s.value * b.wave_speed_m_s.value);
    m.poisson_ratio = b.poisson_ratio.value;
  }
  for (std::size_t i = 0; i < c.gauges.size(); ++i) {
    const GaugeCalibration& g = c.gauges[i];
    const std::string path = "gauges[" + std::to_string(i) + "]";
    GaugeSpec* gauge = nullptr;
    BarSpec* on = nullptr;
    for (auto& s : scene.bars)
      for (auto& x : s.gauges)
        if (x.name == g.gauge) gauge = &x, on = &s;
    if (!gauge)
      throw input_error(file.string(), path + ".gauge", json_quoted(g.gauge),
                        "no such gauge in " + where + ": a calibration of other bars");
    if (!g.bar.empty() && on->name != g.bar)
      throw input_error(file.string(), path + ".bar", json_quoted(g.bar),
                        "gauge \"" + g.gauge + "\" is on bar \"" + on->name + "\" in " + where +
                            ": a calibration of other bars");
    if (const std::string what = gauge_position_problem(g.position_m.value, on->length_m);
        !what.empty())
      throw input_error(file.string(), path + ".position_m.value",
                        JsonValue::format(g.position_m.value, Dimension::kLength),
                        what + " (bar \"" + on->name + "\" of " + where + ")");
    gauge->position_m = g.position_m.value;
    if (scene.measurement)
      for (ChannelSpec& ch : scene.measurement->channels)
        if (ch.gauge == g.gauge)
          ch.calibrated_gain = g.gain.value, ch.calibrated_delay_s = g.delay_s.value;
  }
  scene.calibration_file = file;
}

nlohmann::json calibration_summary(const Scene& scene) {
  if (scene.calibration_file.empty()) return nullptr;
  return input_digests({scene.calibration_file}).at(0);
}

}  // namespace shpb
