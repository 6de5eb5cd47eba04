#include "model/uncertainty_reader.hpp"

#include <algorithm>

namespace shpb {
namespace {

// A standard uncertainty: "x %" of the nominal value, or an absolute value of dimension `d` (a
// bare number for a plain number: "%" always means relative). `relative_ok` false: the nominal
// value is zero (a delay, a window shift), so only an absolute value means something.
StandardUncertainty read_value(const JsonValue& v, Dimension d, bool relative_ok = true) {
  StandardUncertainty u;
  u.path = v.path();
  const bool percent = v.is_string() && v.string().find('%') != std::string::npos;
  if (percent) {
    if (!relative_ok)
      throw v.error("its nominal value is zero: give an absolute standard uncertainty, not \"%\"");
    u.relative = true;
    // A relative standard uncertainty of 100 % or more is no longer a small perturbation.
    u.value = v.quantity_in(Dimension::kDimensionless, 0, 1, false, true);
  } else {
    u.value = v.non_negative_quantity(d);
  }
  return u;
}

}  // namespace

UncertaintySpec read_uncertainty(const JsonValue& value, const std::vector<std::string>& bars,
                                 std::optional<std::size_t> specimen) {
  const auto o =
      value.object({"gauge_factor", "excitation", "gain", "gauge_position", "trigger_delay",
                    "window_start", "dispersion_cutoff", "friction", "bars", "notes"});
  UncertaintySpec u;
  if (auto v = o.get("notes")) v->string();
  if (auto v = o.get("gauge_factor")) u.gauge_factor = read_value(*v, Dimension::kDimensionless);
  if (auto v = o.get("excitation")) u.excitation = read_value(*v, Dimension::kVoltage);
  if (auto v = o.get("gain")) u.gain = read_value(*v, Dimension::kDimensionless);
  if (auto v = o.get("gauge_position")) u.gauge_position = read_value(*v, Dimension::kLength);
  if (auto v = o.get("trigger_delay")) u.trigger_delay = read_value(*v, Dimension::kTime, false);
  if (auto v = o.get("window_start"))
    u.window_start = read_value(*v, Dimension::kDimensionless, false);
  if (auto v = o.get("dispersion_cutoff"))
    u.dispersion_cutoff = read_value(*v, Dimension::kFrequency);
  if (auto v = o.get("friction")) u.friction = read_value(*v, Dimension::kDimensionless);
  if (auto b = o.get("bars")) {
    if (!b->is_object())
      throw b->error("expected {\"<bar name>\": {\"youngs_modulus\": \"1 %\", ...}, ...}");
    if (!specimen)
      throw b->error("bar uncertainties need the scene's specimen (the bars a reduction uses)");
    for (const auto& [name, item] : b->json().items()) {
      const JsonValue bv(item, value.file(), json_child_path(b->path(), name));
      const auto it = std::find(bars.begin(), bars.end(), name);
      if (it == bars.end())
        throw bv.error_with_value("\"" + name + "\"",
                                  "no such bar; " + suggestion_text(name, bars));
      const auto index = static_cast<std::size_t>(it - bars.begin());
      const bool is_specimen = index == *specimen;
      if (!is_specimen && index + 1 != *specimen && index != *specimen + 1)
        throw bv.error_with_value("\"" + name + "\"",
                                  "only the specimen and the bars either side of it enter the "
                                  "reduction");
      const auto bo =
          is_specimen
              ? bv.object({"diameter", "length"})
              : bv.object({"youngs_modulus", "density", "wave_speed", "poisson_ratio", "diameter"});
      BarUncertainty bu;
      bu.bar = index;
      if (auto v = bo.get("youngs_modulus"))
        bu.youngs_modulus = read_value(*v, Dimension::kPressure);
      if (auto v = bo.get("density")) bu.density = read_value(*v, Dimension::kDensity);
      if (auto v = bo.get("wave_speed")) {
        if (bu.youngs_modulus && bu.density)
          throw v->error(
              "the wave speed is sqrt(E/density): give two of youngs_modulus, density and "
              "wave_speed");
        bu.wave_speed = read_value(*v, Dimension::kVelocity);
      }
      if (auto v = bo.get("poisson_ratio"))
        bu.poisson_ratio = read_value(*v, Dimension::kDimensionless);
      if (auto v = bo.get("diameter")) bu.diameter = read_value(*v, Dimension::kLength);
      if (auto v = bo.get("length")) bu.length = read_value(*v, Dimension::kLength);
      u.bars.push_back(bu);
    }
  }
  return u;
}

}  // namespace shpb
