#include "model/law_parameters.hpp"

#include <cstdio>
#include <stdexcept>

#include "model/laws/johnson_cook_law.hpp"
#include "model/material_law.hpp"

namespace shpb {
namespace {

// "arms[3].modulus" → (3, "modulus"); nullopt for other names.
std::optional<std::pair<std::size_t, std::string>> arm_parameter(const std::string& name) {
  if (name.rfind("arms[", 0) != 0) return std::nullopt;
  const auto close = name.find("].");
  if (close == std::string::npos || close <= 5) return std::nullopt;
  const std::string index = name.substr(5, close - 5);
  if (index.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  return std::pair{static_cast<std::size_t>(std::stoul(index)), name.substr(close + 2)};
}

double& slot(MaterialSpec& m, const std::string& name) {
  if (name == "youngs_modulus" && m.model != MaterialModel::kViscoelastic)
    return m.youngs_modulus_Pa;
  auto& jc = m.johnson_cook;
  if (m.model == MaterialModel::kJohnsonCook) {
    if (name == "A") return jc.A_Pa;
    if (name == "B") return jc.B_Pa;
    if (name == "n") return jc.n;
    if (name == "C") return jc.C;
    if (name == "m") return jc.m;
  }
  if (m.model == MaterialModel::kBilinear) {
    if (name == "yield_stress") return m.bilinear.yield_stress_Pa;
    if (name == "tangent_modulus") return m.bilinear.tangent_modulus_Pa;
  }
  if (m.model == MaterialModel::kViscoelastic) {
    if (name == "long_term_modulus") return m.viscoelastic.long_term_modulus_Pa;
    if (auto arm = arm_parameter(name); arm && arm->first < m.viscoelastic.arms.size()) {
      if (arm->second == "modulus") return m.viscoelastic.arms[arm->first].modulus_Pa;
      if (arm->second == "relaxation_time")
        return m.viscoelastic.arms[arm->first].relaxation_time_s;
    }
  }
  throw std::logic_error("law parameter " + name + " not in the law");
}

std::string format_value(double value, const char* unit, double per_unit) {
  char text[64];
  std::snprintf(text, sizeof text, "%.6g %s", value / per_unit, unit);
  return text;
}

}  // namespace

std::vector<std::string> law_parameter_names(const MaterialSpec& m) {
  switch (m.model) {
    case MaterialModel::kElastic:
      return {"youngs_modulus"};
    case MaterialModel::kBilinear:
      return {"yield_stress", "tangent_modulus", "youngs_modulus"};
    case MaterialModel::kJohnsonCook:
      return {"A", "B", "n", "C", "m", "youngs_modulus"};
    case MaterialModel::kViscoelastic: {
      std::vector<std::string> names = {"long_term_modulus"};
      for (std::size_t k = 0; k < m.viscoelastic.arms.size(); ++k) {
        names.push_back("arms[" + std::to_string(k) + "].modulus");
        names.push_back("arms[" + std::to_string(k) + "].relaxation_time");
      }
      return names;
    }
  }
  return {};
}

Dimension law_parameter_dimension(const std::string& name) {
  if (name == "n" || name == "C" || name == "m") return Dimension::kDimensionless;
  if (auto arm = arm_parameter(name); arm && arm->second == "relaxation_time")
    return Dimension::kTime;
  return Dimension::kPressure;
}

double law_parameter(const MaterialSpec& m, const std::string& name) {
  return slot(const_cast<MaterialSpec&>(m), name);
}

void set_law_parameter(MaterialSpec& m, const std::string& name, double value) {
  slot(m, name) = value;
  if (m.model == MaterialModel::kViscoelastic) {
    m.youngs_modulus_Pa = m.viscoelastic.long_term_modulus_Pa;
    for (const auto& arm : m.viscoelastic.arms) m.youngs_modulus_Pa += arm.modulus_Pa;
  }
}

nlohmann::json law_parameter_json(const std::string& name, double value) {
  switch (law_parameter_dimension(name)) {
    case Dimension::kPressure:
      return format_value(value, value >= 1e9 ? "GPa" : "MPa", value >= 1e9 ? 1e9 : 1e6);
    case Dimension::kTime:
      return format_value(value, "us", 1e-6);
    default:
      return value;
  }
}

nlohmann::json& law_parameter_member(nlohmann::json& document, const std::string& name) {
  if (auto arm = arm_parameter(name)) return document["arms"][arm->first][arm->second];
  return document[name];
}

void set_law_parameter(nlohmann::json& document, const std::string& name, double value) {
  law_parameter_member(document, name) = law_parameter_json(name, value);
}

std::optional<double> law_flow_stress(const MaterialSpec& m, double plastic_strain,
                                      double strain_rate_1_s, double temperature_K) {
  if (m.model == MaterialModel::kJohnsonCook)
    return johnson_cook_flow_stress(m.johnson_cook, plastic_strain, strain_rate_1_s, temperature_K);
  if (m.model == MaterialModel::kBilinear) {
    const double e = m.youngs_modulus_Pa, et = m.bilinear.tangent_modulus_Pa;
    return m.bilinear.yield_stress_Pa + e * et / (e - et) * plastic_strain;
  }
  return std::nullopt;
}

std::vector<double> law_stress_along(const MaterialSpec& m, const std::vector<double>& time_s,
                                     const std::vector<double>& strain, bool tension) {
  const auto law = make_material_law(m);
  MaterialPointState state;
  law->initialize({&state, 1});
  const double sign = tension ? 1.0 : -1.0;  // the laws' strain: negative in compression
  std::vector<double> stress(strain.size(), 0.0);
  for (std::size_t i = 1; i < strain.size(); ++i) {
    const double next = sign * strain[i];
    double out = 0;
    law->update({&next, 1}, time_s[i] - time_s[i - 1], {&state, 1}, {&out, 1});
    stress[i] = sign * out;
  }
  return stress;
}

}  // namespace shpb
