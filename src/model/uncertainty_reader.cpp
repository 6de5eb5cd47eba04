#include "model/uncertainty_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "model/input_keys.hpp"

namespace shpb {

std::string sign_keeping_problem(double value, double sigma, Dimension d) {
  if (sigma < std::abs(value) / kSignKeepingSigmas) return {};
  const double p = 0.5 * std::erfc(std::abs(value) / sigma / std::sqrt(2.0));
  char b[400];
  std::snprintf(b, sizeof b,
                "a standard deviation of %s on a value of %s that must stay %s: a normal draw "
                "would be %s with probability %.2g; expected one below %s (|value| / %g, a draw "
                "of the other sign then has a probability below 1e-9)",
                JsonValue::format(sigma, d).c_str(), JsonValue::format(value, d).c_str(),
                value > 0 ? "> 0" : "< 0", value > 0 ? "<= 0" : ">= 0", p,
                JsonValue::format(std::abs(value) / kSignKeepingSigmas, d).c_str(),
                kSignKeepingSigmas);
  return b;
}

StandardUncertainty read_standard_uncertainty(const JsonValue& v, Dimension d, bool relative_ok) {
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

UncertaintySpec read_uncertainty(const JsonValue& value, const std::vector<std::string>& bars,
                                 std::optional<std::size_t> specimen) {
  const auto o = value.object(input_keys::kUncertainty);
  UncertaintySpec u;
  if (auto v = o.get("notes")) v->string();
  if (auto v = o.get("gauge_factor"))
    u.gauge_factor = read_standard_uncertainty(*v, Dimension::kDimensionless);
  if (auto v = o.get("excitation"))
    u.excitation = read_standard_uncertainty(*v, Dimension::kVoltage);
  if (auto v = o.get("gain")) u.gain = read_standard_uncertainty(*v, Dimension::kDimensionless);
  if (auto sh = o.get("shared")) {
    for (const JsonValue& e : sh->array()) {
      const std::string key = e.is_string() ? e.string() : std::string();
      const bool given = (key == "gauge_factor" && u.gauge_factor) ||
                         (key == "excitation" && u.excitation) || (key == "gain" && u.gain);
      if (!given)
        throw e.error(
            "expected \"gauge_factor\", \"excitation\" or \"gain\", each with its own "
            "uncertainty in this block, once");
      if (std::find(u.shared.begin(), u.shared.end(), key) != u.shared.end())
        throw e.error("listed twice");
      u.shared.push_back(key);
    }
  }
  if (auto v = o.get("gauge_position"))
    u.gauge_position = read_standard_uncertainty(*v, Dimension::kLength);
  if (auto v = o.get("trigger_delay"))
    u.trigger_delay = read_standard_uncertainty(*v, Dimension::kTime, false);
  if (auto v = o.get("window_start"))
    u.window_start = read_standard_uncertainty(*v, Dimension::kDimensionless, false);
  if (auto v = o.get("dispersion_cutoff"))
    u.dispersion_cutoff = read_standard_uncertainty(*v, Dimension::kFrequency);
  if (auto v = o.get("friction"))
    u.friction = read_standard_uncertainty(*v, Dimension::kDimensionless);
  if (auto v = o.get("record_noise")) u.record_noise = v->boolean();
  if (auto b = o.get("bars")) {
    if (!b->is_object())
      throw b->error("expected {\"<bar name>\": {\"youngs_modulus\": \"1 %\", ...}, ...}");
    if (!specimen)
      throw b->error("bar uncertainties need the scene's specimen (the bars a reduction uses)");
    for (const auto& [name, item] : b->json().items()) {
      const JsonValue bv(item, value.file(), json_child_path(b->path(), name));
      const auto it = std::find(bars.begin(), bars.end(), name);
      if (it == bars.end())
        throw bv.error_with_value(json_quoted(name), "no such bar; " + suggestion_text(name, bars));
      const auto index = static_cast<std::size_t>(it - bars.begin());
      const bool is_specimen = index == *specimen;
      if (!is_specimen && index + 1 != *specimen && index != *specimen + 1)
        throw bv.error_with_value(json_quoted(name),
                                  "only the specimen and the bars either side of it enter the "
                                  "reduction");
      const auto bo =
          bv.object(is_specimen ? input_keys::kUncertaintySpecimen : input_keys::kUncertaintyBar);
      BarUncertainty bu;
      bu.bar = index;
      if (auto v = bo.get("youngs_modulus"))
        bu.youngs_modulus = read_standard_uncertainty(*v, Dimension::kPressure);
      if (auto v = bo.get("density"))
        bu.density = read_standard_uncertainty(*v, Dimension::kDensity);
      if (auto v = bo.get("wave_speed")) {
        if (bu.youngs_modulus && bu.density)
          throw v->error(
              "the wave speed is sqrt(E/density): give two of youngs_modulus, density and "
              "wave_speed");
        bu.wave_speed = read_standard_uncertainty(*v, Dimension::kVelocity);
      }
      if (auto v = bo.get("poisson_ratio"))
        bu.poisson_ratio = read_standard_uncertainty(*v, Dimension::kDimensionless);
      if (auto v = bo.get("diameter"))
        bu.diameter = read_standard_uncertainty(*v, Dimension::kLength);
      if (auto v = bo.get("length")) bu.length = read_standard_uncertainty(*v, Dimension::kLength);
      u.bars.push_back(bu);
    }
  }
  return u;
}

}  // namespace shpb
