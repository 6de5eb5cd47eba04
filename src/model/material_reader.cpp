#include "model/material_reader.hpp"

#include <algorithm>
#include <stdexcept>

#include "core/closest_match.hpp"
#include "core/json_document.hpp"
#include "model/input_keys.hpp"
#include "model/input_limits.hpp"
#include "model/law_parameters.hpp"
#include "model/material_law.hpp"
#include "model/scene.hpp"

namespace shpb {

std::string melting_temperature_problem(double melting_K, double room_K) {
  if (melting_K > room_K) return {};
  return "must be > room_temperature (" + JsonValue::format(room_K, Dimension::kTemperature) + ")";
}

std::string test_temperature_problem(double test_K, double melting_K) {
  if (test_K < melting_K) return {};
  return "must be below melting_temperature (" +
         JsonValue::format(melting_K, Dimension::kTemperature) + ")";
}

std::string tangent_modulus_problem(double tangent_Pa, double youngs_modulus_Pa) {
  if (tangent_Pa >= 0 && tangent_Pa < youngs_modulus_Pa) return {};
  return "must be >= 0 and < youngs_modulus (" +
         JsonValue::format(youngs_modulus_Pa, Dimension::kPressure) + ")";
}

const std::vector<std::string>& material_model_keys(MaterialModel model) {
  switch (model) {
    case MaterialModel::kElastic:
      return input_keys::kElastic;
    case MaterialModel::kBilinear:
      return input_keys::kBilinear;
    case MaterialModel::kJohnsonCook:
      return input_keys::kJohnsonCook;
    case MaterialModel::kViscoelastic:
      return input_keys::kViscoelastic;
  }
  throw std::logic_error("material_model_keys: unknown model");
}

namespace {

std::vector<std::string> allowed_keys(MaterialModel model) {
  std::vector<std::string> keys = input_keys::kMaterial;
  const auto& own = material_model_keys(model);
  keys.insert(keys.end(), own.begin(), own.end());
  return keys;
}

void read_bilinear(const JsonObject& o, MaterialSpec& m) {
  auto& p = m.bilinear;
  p.yield_stress_Pa = o.require("yield_stress", "the initial yield stress, e.g. \"300 MPa\"")
                          .positive_quantity(Dimension::kPressure);
  const auto et = o.require("tangent_modulus", "the hardening slope after yield, e.g. \"1 GPa\"");
  p.tangent_modulus_Pa = et.quantity(Dimension::kPressure);
  if (const std::string what = tangent_modulus_problem(p.tangent_modulus_Pa, m.youngs_modulus_Pa);
      !what.empty())
    throw et.error_with_value(JsonValue::format(p.tangent_modulus_Pa, Dimension::kPressure), what);
}

void read_johnson_cook(const JsonObject& o, MaterialSpec& m) {
  auto& p = m.johnson_cook;
  p.A_Pa = o.require("A", "the yield stress term, e.g. \"324 MPa\"")
               .non_negative_quantity(Dimension::kPressure);
  p.B_Pa = o.require("B", "the hardening modulus, e.g. \"114 MPa\"")
               .non_negative_quantity(Dimension::kPressure);
  p.n = o.require("n", "the hardening exponent in [0, 1]")
            .quantity_in(Dimension::kDimensionless, 0, 1, false, false);
  p.C =
      o.require("C", "the strain-rate coefficient, e.g. 0.002").quantity(Dimension::kDimensionless);
  if (auto v = o.get("reference_strain_rate"))
    p.reference_strain_rate_1_s = v->positive_quantity(Dimension::kStrainRate);
  p.m = o.require("m", "the thermal softening exponent, e.g. 1.34")
            .positive_quantity(Dimension::kDimensionless);
  if (auto v = o.get("room_temperature"))
    set_room_temperature(p, v->positive_quantity(Dimension::kTemperature));
  const auto melt = o.require("melting_temperature", "e.g. \"925 K\"");
  p.melting_temperature_K = melt.quantity(Dimension::kTemperature);
  if (const std::string what =
          melting_temperature_problem(p.melting_temperature_K, p.room_temperature_K);
      !what.empty())
    throw melt.error_with_value(JsonValue::format(p.melting_temperature_K, Dimension::kTemperature),
                                what);
  if (auto v = o.get("temperature")) {
    p.initial_temperature_K = v->positive_quantity(Dimension::kTemperature);
    p.temperature_given = true;
    if (const std::string what =
            test_temperature_problem(p.initial_temperature_K, p.melting_temperature_K);
        !what.empty())
      throw v->error_with_value(JsonValue::format(p.initial_temperature_K, Dimension::kTemperature),
                                what);
  }
  if (auto v = o.get("adiabatic")) p.adiabatic = v->boolean();
  if (auto v = o.get("taylor_quinney"))
    p.taylor_quinney = v->quantity_in(Dimension::kDimensionless, 0, 1, false, false);
  if (p.adiabatic || o.has("specific_heat")) {
    p.specific_heat_J_kgK =
        o.require("specific_heat", "needed for adiabatic heating, e.g. \"885 J/(kg K)\"")
            .positive_quantity(Dimension::kSpecificHeat);
    p.specific_heat_given = true;
  }
  if (auto v = o.get("strain_rate_filter"))
    p.strain_rate_filter_s = v->non_negative_quantity(Dimension::kTime);
}

void read_viscoelastic(const JsonObject& o, MaterialSpec& m) {
  auto& p = m.viscoelastic;
  p.long_term_modulus_Pa = o.require("long_term_modulus", "E_inf, e.g. \"2 GPa\"")
                               .positive_quantity(Dimension::kPressure);
  const auto arms = o.require("arms", "a list of {\"modulus\", \"relaxation_time\"}");
  const auto items = arms.array();
  if (items.size() > static_cast<std::size_t>(MaterialPointState::kMaxArms))
    throw arms.error_with_value(std::to_string(items.size()) + " arms",
                                "at most " + std::to_string(MaterialPointState::kMaxArms));
  m.youngs_modulus_Pa = p.long_term_modulus_Pa;
  for (const auto& item : items) {
    const auto a = item.object(input_keys::kMaxwellArm);
    MaxwellArm arm;
    arm.modulus_Pa = a.require("modulus", "e.g. \"1 GPa\"").positive_quantity(Dimension::kPressure);
    arm.relaxation_time_s =
        a.require("relaxation_time", "e.g. \"10 us\"").positive_quantity(Dimension::kTime);
    p.arms.push_back(arm);
    m.youngs_modulus_Pa += arm.modulus_Pa;  // instantaneous modulus E_inf + ΣE_k
  }
}

// A fit's intervals of the law's parameters (fit.json, docs/outputs.md): a record of the fit that
// no command propagates, checked to be one. A standard uncertainty written here ("2 %", a density)
// would be read by nothing: the uncertainty `process` draws is measurement.uncertainty's.
void check_fit_intervals(const JsonValue& v, const MaterialSpec& m) {
  const std::string elsewhere =
      "a material's uncertainty holds a fit's 95 % intervals of its law parameters (fit.json), "
      "which no command propagates; a standard uncertainty that process draws goes in "
      "measurement.uncertainty.bars.<bar> (docs/scene-format.md)";
  if (!v.is_object()) throw v.error("expected an object: " + elsewhere);
  const std::vector<std::string> names = law_parameter_names(m);
  for (const auto& [key, item] : v.json().items()) {
    const JsonValue p(item, v.file(), json_child_path(v.path(), key));
    if (std::find(names.begin(), names.end(), key) == names.end())
      throw p.error("not a law parameter of this " + std::string(to_string(m.model)) +
                    " material (" + suggestion_text(key, names) + "): " + elsewhere);
    if (!p.is_object())
      throw p.error(
          "expected {\"interval_95\": [lower, upper], \"method\", \"weakly_identified\"}: " +
          elsewhere);
    const auto po = p.object(input_keys::kFitInterval);
    const auto interval = po.require("interval_95", "[lower, upper] in SI units");
    const auto ends = interval.array();
    if (ends.size() != 2) throw interval.error("expected [lower, upper] in SI units");
    const Dimension d = law_parameter_dimension(key);
    if (!(ends[0].quantity(d) <= ends[1].quantity(d)))
      throw interval.error("expected [lower, upper] with lower <= upper");
    if (auto x = po.get("method")) x->string();
    if (auto x = po.get("weakly_identified")) x->boolean();
  }
}

}  // namespace

MaterialSpec read_material(const JsonValue& value, const std::string& name) {
  if (!value.is_object()) throw value.error("expected a material object { \"model\": ..., ... }");
  MaterialSpec m;
  m.name = name;
  const auto model_value = JsonObject(value).require("model", enum_names_text(kMaterialModelNames));
  m.model = enum_from(model_value, kMaterialModelNames);

  if (m.model == MaterialModel::kViscoelastic)
    if (auto e = JsonObject(value).get("youngs_modulus"))
      throw e->error(
          "not an input of the viscoelastic model: E = long_term_modulus + sum of arm moduli");
  const JsonObject o = value.object(allowed_keys(m.model));
  if (auto v = o.get("source")) m.source = v->string();
  if (auto v = o.get("notes")) v->string();
  if (auto v = o.get("name")) v->string();
  m.density_kg_m3 =
      o.require("density", "e.g. \"7.85 g/cm3\"").positive_quantity(Dimension::kDensity);
  if (m.model == MaterialModel::kViscoelastic) {
    read_viscoelastic(o, m);
  } else {
    m.youngs_modulus_Pa =
        o.require("youngs_modulus", "e.g. \"200 GPa\"").positive_quantity(Dimension::kPressure);
  }
  const auto nu = o.require("poisson_ratio", "e.g. 0.3");
  m.poisson_ratio =
      nu.quantity_in(Dimension::kDimensionless, kPoissonRatioAbove, kPoissonRatioBelow, true, true);

  if (m.model == MaterialModel::kBilinear) read_bilinear(o, m);
  if (m.model == MaterialModel::kJohnsonCook) read_johnson_cook(o, m);
  if (auto v = o.get("uncertainty")) check_fit_intervals(*v, m);
  return m;
}

MaterialSpec read_material_document(const nlohmann::json& document, const std::string& display) {
  return read_placing_keys(display, input_keys::kMaterialPlaces, [&] {
    return read_material(JsonValue(document, display, ""), display);
  });
}

MaterialSpec read_material_file(const std::filesystem::path& file, const std::string& display) {
  return read_material_document(read_json_object_file(file, display), display);
}

}  // namespace shpb
