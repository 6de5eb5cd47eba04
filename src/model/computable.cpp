#include "model/computable.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/json_value.hpp"
#include "model/interface_name.hpp"
#include "model/penalty_links.hpp"
#include "model/scene_inputs.hpp"

namespace shpb {

namespace {

// One input a derived quantity comes from: where the user gave it and its SI value.
struct Input {
  std::string file, path, value;
  double si = 1;
};

bool computable(double q) {
  return std::isfinite(q) && std::abs(q) >= kSmallestComputable &&
         std::abs(q) <= kLargestComputable;
}

class Inputs {
 public:
  explicit Inputs(const Scene& scene) : scene_(scene), file_(scene.file.string()) {}

  Input density(std::size_t i) const {
    return material_input(i, "density", scene_.bars[i].material.density_kg_m3, Dimension::kDensity);
  }
  Input modulus(std::size_t i) const {
    const bool visco = scene_.bars[i].material.model == MaterialModel::kViscoelastic;
    return material_input(i, visco ? "long_term_modulus" : "youngs_modulus",
                          scene_.bars[i].material.youngs_modulus_Pa, Dimension::kPressure);
  }
  Input section(std::size_t i) const {
    const BarSpec& b = scene_.bars[i];
    if (b.area_given)
      return {file_, bar(i) + ".area", JsonValue::format(b.area_m2, Dimension::kArea), b.area_m2};
    return {file_, bar(i) + ".diameter", JsonValue::format(b.diameter_m, Dimension::kLength),
            b.diameter_m};
  }
  Input length(std::size_t i) const {
    const BarSpec& b = scene_.bars[i];
    return {file_, bar(i) + ".length", JsonValue::format(b.length_m, Dimension::kLength),
            b.length_m};
  }
  Input velocity(std::size_t i) const {
    const BarSpec& b = scene_.bars[i];
    return {file_, bar(i) + ".velocity", JsonValue::format(b.velocity_m_s, Dimension::kVelocity),
            b.velocity_m_s};
  }
  // The element length's inputs: the length, and the element count where the scene gives one.
  std::vector<Input> mesh(std::size_t i) const {
    const BarSpec& b = scene_.bars[i];
    std::vector<Input> in = {length(i)};
    if (b.elements > 0)
      in.push_back({file_, bar(i) + ".elements", std::to_string(b.elements), 1.0 * b.elements});
    return in;
  }
  // The penalty parameters of interface k the scene gives (its override's, else the contact's).
  std::vector<Input> penalty(std::size_t k) const {
    std::vector<Input> in;
    const PenaltyParams p = interface_penalty(scene_.contact, k);
    const auto add = [&](const char* key, const std::optional<double>& v, Dimension dim,
                         bool overridden) {
      if (!v) return;
      std::string where = "contact";
      for (std::size_t j = 0; j < scene_.contact.interfaces.size(); ++j)
        if (scene_.contact.interfaces[j].left_bar == k && overridden)
          where = "contact.interfaces[" + std::to_string(j) + "]";
      in.push_back({file_, where + "." + key, JsonValue::format(*v, dim), *v});
    };
    const PenaltyParams* own = nullptr;
    for (const InterfaceOverride& o : scene_.contact.interfaces)
      if (o.left_bar == k) own = &o.penalty;
    const bool stiffness_here =
        own && (own->stiffness_factor || own->stiffness_N_m || own->rise_time_s);
    add("stiffness_factor", p.stiffness_factor, Dimension::kDimensionless, stiffness_here);
    add("stiffness", p.stiffness_N_m, Dimension::kStiffness, stiffness_here);
    add("rise_time", p.rise_time_s, Dimension::kTime, stiffness_here);
    add("mass_ratio", p.mass_ratio, Dimension::kDimensionless, own && own->mass_ratio);
    return in;
  }

 private:
  static std::string bar(std::size_t i) { return "bars[" + std::to_string(i) + "]"; }

  // A material of the scene's `materials`, of a file, or given inline in the bar.
  Input material_input(std::size_t i, const char* key, double si, Dimension dim) const {
    const InputLocation at = material_key_location(scene_, i, key);
    return {at.file, at.path, JsonValue::format(si, dim), si};
  }

  const Scene& scene_;
  std::string file_;
};

// Of the inputs of a quantity that is not computable, the one farthest from 1 in SI units.
[[noreturn]] void refuse(const std::vector<Input>& inputs, const std::string& what, double q,
                         const char* unit) {
  const auto blamed =
      std::max_element(inputs.begin(), inputs.end(), [](const Input& a, const Input& b) {
        return std::abs(std::log10(std::abs(a.si))) < std::abs(std::log10(std::abs(b.si)));
      });
  char text[400];
  std::snprintf(text, sizeof text,
                "gives %s of %.3g %s, which double precision cannot compute with (a derived "
                "quantity must be finite and between %.3g and %.3g in SI units, "
                "docs/scene-format.md)",
                what.c_str(), q, unit, kSmallestComputable, kLargestComputable);
  throw input_error(blamed->file, blamed->path, blamed->value, text);
}

void check(double q, const std::vector<Input>& inputs, const std::string& what, const char* unit) {
  if (!computable(q)) refuse(inputs, what, q, unit);
}

template <class... Lists>
std::vector<Input> join(Lists&&... lists) {
  std::vector<Input> all;
  (all.insert(all.end(), lists.begin(), lists.end()), ...);
  return all;
}

}  // namespace

void check_computable(const Scene& scene, const ChainDiscretization& d) {
  const Inputs in(scene);
  const auto bar_of = [&](std::size_t i) { return "bar \"" + scene.bars[i].name + "\" "; };
  for (std::size_t i = 0; i < scene.bars.size(); ++i) {
    const BarSpec& b = scene.bars[i];
    const MaterialSpec& m = b.material;
    const std::vector<Input> section = {in.section(i)}, material = {in.density(i), in.modulus(i)};
    const std::vector<Input> mesh = in.mesh(i);
    const NeighbourInfo end = neighbour_info(scene, d, i);
    const double h = end.element_length_m;
    check(b.area_m2, section, bar_of(i) + "a cross-section area", "m^2");
    check(end.wave_speed_m_s, material, bar_of(i) + "a wave speed sqrt(E/rho)", "m/s");
    check(b.impedance_kg_s(), join(material, section), bar_of(i) + "an impedance rho c A", "kg/s");
    check(h, mesh, bar_of(i) + "an element length", "m");
    check(m.density_kg_m3 * b.area_m2 * h, join(material, section, mesh),
          bar_of(i) + "an element mass rho A h", "kg");
    check(end.stiffness_N_m, join(material, section, mesh), bar_of(i) + "an element stiffness EA/h",
          "N/m");
    check(d.bars[i].critical_step_s, join(material, mesh), bar_of(i) + "a stable step h/c", "s");
    check(end.critical_ratio(), join(material, mesh), bar_of(i) + "a critical mass ratio (2c/h)^2",
          "1/s^2");
    if (b.velocity_m_s != 0)
      check(0.5 * m.density_kg_m3 * b.area_m2 * b.length_m * b.velocity_m_s * b.velocity_m_s,
            join(material, section, std::vector<Input>{in.length(i), in.velocity(i)}),
            bar_of(i) + "a kinetic energy", "J");
  }
  for (std::size_t k = 0; k + 1 < scene.bars.size(); ++k) {
    const ContactMethod method = interface_method(scene.contact, k);
    const PenaltyParams params = interface_penalty(scene.contact, k);
    if (!links_are_finite(method, params)) continue;
    const PenaltyLinks links =
        penalty_links(method, params, neighbour_info(scene, d, k), neighbour_info(scene, d, k + 1));
    std::vector<Input> inputs = in.penalty(k);
    for (const std::size_t i : {k, k + 1})
      inputs =
          join(inputs, std::vector<Input>{in.density(i), in.modulus(i), in.section(i)}, in.mesh(i));
    const std::string where = "the interface " + interface_name(scene, k) + " ";
    check(links.stiffness_N_m, inputs, where + "a penalty stiffness", "N/m");
    if (method != ContactMethod::kPenalty)
      check(links.mass_penalty_kg, inputs, where + "a mass penalty", "kg");
  }
}

void check_reduction_computable(const Scene& scene) {
  if (!scene.specimen || *scene.specimen == 0 || *scene.specimen + 1 >= scene.bars.size()) return;
  const std::size_t s = *scene.specimen;
  const Inputs in(scene);
  const BarSpec& specimen = scene.bars[s];
  const std::vector<Input> specimen_section = {in.section(s)}, specimen_length = {in.length(s)};
  const std::string of_specimen = " on specimen \"" + specimen.name + "\"";
  check(specimen.area_m2, specimen_section,
        "specimen \"" + specimen.name + "\" a cross-section area", "m^2");
  for (const std::size_t i : {s - 1, s + 1}) {
    const BarSpec& b = scene.bars[i];
    const std::string bar = "bar \"" + b.name + "\" ";
    const std::vector<Input> section = {in.section(i)}, material = {in.density(i), in.modulus(i)};
    const double c0 = b.material.wave_speed_m_s();
    check(b.area_m2, section, bar + "a cross-section area", "m^2");
    check(c0, material, bar + "a wave speed sqrt(E/rho)", "m/s");
    check(b.impedance_kg_s(), join(material, section), bar + "an impedance rho c A", "kg/s");
    check(b.material.youngs_modulus_Pa * b.area_m2 / specimen.area_m2,
          join(material, section, specimen_section),
          bar + "a stress per unit strain E A_bar / A_specimen" + of_specimen, "Pa");
    check(c0 / specimen.length_m, join(material, specimen_length),
          bar + "a strain rate per unit strain c0 / L_specimen" + of_specimen, "1/s");
  }
}

}  // namespace shpb
