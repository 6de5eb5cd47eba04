// Materials and their law groups (material.bilinear, material.johnson_cook): Material, Bilinear,
// JohnsonCook. Material parameters, SI units in the names (docs/scene-format.md gives the JSON
// keys).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <type_traits>
#include <utility>

#include "bindings.hpp"
#include "core/csv_writer.hpp"
#include "core/error.hpp"
#include "model/input_limits.hpp"
#include "model/law_parameters.hpp"
#include "model/scene.hpp"
#include "values.hpp"

namespace shpb::python {

namespace {

// A Johnson-Cook temperature edit: its range, then the readers' rules between the temperatures
// (model/input_limits.hpp), so that the homologous temperature stays the one a file could give. A
// room temperature edit moves a test without a `temperature` of its own with it, as the file's
// edit would (set_room_temperature); the test's temperature set is its own from then on.
auto jc_temperature(double JohnsonCookParams::*field, const char* name) {
  return [field, name](JohnsonCookParams& o, const py::object& x) {
    JohnsonCookParams edited = o;
    checked(field, name, Range::kPositive)(edited, x);
    if (field == &JohnsonCookParams::room_temperature_K)
      set_room_temperature(edited, edited.room_temperature_K);
    if (field == &JohnsonCookParams::initial_temperature_K) edited.temperature_given = true;
    std::string what =
        melting_temperature_problem(edited.melting_temperature_K, edited.room_temperature_K);
    if (!what.empty())
      what = "melting_temperature_K " + format_double(edited.melting_temperature_K) + " " + what;
    else if (what = test_temperature_problem(edited.initial_temperature_K,
                                             edited.melting_temperature_K);
             !what.empty())
      what = "initial_temperature_K " + format_double(edited.initial_temperature_K) + " " + what;
    if (!what.empty()) throw input_error("scene edit", name, format_double(edited.*field), what);
    o = edited;
  };
}

// A material's parameters of one law, its attribute group (material.bilinear,
// material.johnson_cook): read on any material, set only on a material of that law, where the
// scene reader takes them (model/material_reader.cpp); on another one an edit was kept unused.
template <class P>
struct LawParams {
  MaterialSpec* material;
};
template <class P>
P& params_of(const LawParams<P>& l) {
  if constexpr (std::is_same_v<P, BilinearParams>)
    return l.material->bilinear;
  else if constexpr (std::is_same_v<P, ViscoelasticParams>)
    return l.material->viscoelastic;
  else
    return l.material->johnson_cook;
}
template <class P>
constexpr std::pair<MaterialModel, const char*> law_of() {
  if constexpr (std::is_same_v<P, BilinearParams>)
    return {MaterialModel::kBilinear, "bilinear"};
  else if constexpr (std::is_same_v<P, ViscoelasticParams>)
    return {MaterialModel::kViscoelastic, "viscoelastic"};
  else
    return {MaterialModel::kJohnsonCook, "johnson_cook"};
}
// Refuses an edit `name` = `x` of a law's group unless the material's law is the group's.
template <class P>
void require_law(const LawParams<P>& l, const char* name, const py::handle& x) {
  const auto [law, group] = law_of<P>();
  if (l.material->model != law)
    throw input_error("scene edit", name, shown(x),
                      "material \"" + l.material->name + "\" is " +
                          std::string(to_string(l.material->model)) + ": " + group +
                          ".* applies only to a " + std::string(to_string(law)) + " material");
}
template <class P, class T>
auto law_get(T P::*field) {
  return [field](const LawParams<P>& l) { return params_of(l).*field; };
}
// The edit `set` of the attribute `name` (group.attribute), refused unless the material's law is
// the group's.
template <class P, class Set>
auto law_set(const char* name, Set set) {
  return [name, set](LawParams<P>& l, const py::object& x) {
    require_law(l, name, x);
    set(params_of(l), x);
  };
}
template <class P>
auto law_set(double P::*field, const char* name, Range range) {
  return law_set<P>(name, checked(field, name, range));
}

using JohnsonCook = LawParams<JohnsonCookParams>;
using Bilinear = LawParams<BilinearParams>;
using Viscoelastic = LawParams<ViscoelasticParams>;

// A viscoelastic law's moduli and relaxation times, each in the range its file's key takes; the
// instantaneous modulus (youngs_modulus_Pa, which the meshes and the wave speed follow) follows
// them as the reader derives it (set_law_parameter).
void bind_viscoelastic(py::module_& m) {
  using VP = ViscoelasticParams;
  py::class_<Viscoelastic>(m, "Viscoelastic")
      .def_property("long_term_modulus_Pa", law_get(&VP::long_term_modulus_Pa),
                    [](Viscoelastic& l, const py::object& x) {
                      const char* name = "viscoelastic.long_term_modulus_Pa";
                      require_law(l, name, x);
                      set_law_parameter(*l.material, "long_term_modulus",
                                        checked_value(x, name, Range::kPositive));
                    })
      .def_property_readonly("arms",
                             [](const Viscoelastic& l) {
                               py::list arms;
                               for (const MaxwellArm& a : params_of(l).arms) {
                                 py::dict d;
                                 d["modulus_Pa"] = a.modulus_Pa;
                                 d["relaxation_time_s"] = a.relaxation_time_s;
                                 arms.append(d);
                               }
                               return arms;
                             })
      .def(
          "set_arm",
          [](Viscoelastic& l, const py::object& k, const py::object& modulus,
             const py::object& time) {
            const char* name = "viscoelastic.set_arm";
            require_law(l, name, k);
            const auto i = number<std::size_t>(k, "viscoelastic.set_arm: k");
            const std::size_t arms = params_of(l).arms.size();
            if (i >= arms)
              throw input_error("scene edit", name, std::to_string(i),
                                "material \"" + l.material->name + "\" has " +
                                    std::to_string(arms) + " arms: expected an index below that");
            const std::string arm = "arms[" + std::to_string(i) + "].";
            // Both checked before either is set: a refused edit leaves the material unchanged.
            const auto e =
                modulus.is_none()
                    ? std::nullopt
                    : std::optional(checked_value(modulus, "viscoelastic.set_arm: modulus_Pa",
                                                  Range::kPositive));
            const auto tau =
                time.is_none()
                    ? std::nullopt
                    : std::optional(checked_value(time, "viscoelastic.set_arm: relaxation_time_s",
                                                  Range::kPositive));
            if (e) set_law_parameter(*l.material, arm + "modulus", *e);
            if (tau) set_law_parameter(*l.material, arm + "relaxation_time", *tau);
          },
          py::arg("k"), py::arg("modulus_Pa") = py::none(),
          py::arg("relaxation_time_s") = py::none())
      .def("__repr__", [](const Viscoelastic& l) {
        return "<shpb.Viscoelastic " +
               fields({{"long_term_modulus_Pa", params_of(l).long_term_modulus_Pa}}) + ", " +
               std::to_string(params_of(l).arms.size()) + " arms>";
      });
}

void bind_johnson_cook(py::module_& m) {
  using JC = JohnsonCookParams;
  py::class_<JohnsonCook>(m, "JohnsonCook")
      .def_property("A_Pa", law_get(&JC::A_Pa),
                    law_set(&JC::A_Pa, "johnson_cook.A_Pa", Range::kNonNegative))
      .def_property("B_Pa", law_get(&JC::B_Pa),
                    law_set(&JC::B_Pa, "johnson_cook.B_Pa", Range::kNonNegative))
      .def_property("n", law_get(&JC::n), law_set(&JC::n, "johnson_cook.n", Range::kFraction))
      .def_property("C", law_get(&JC::C), law_set(&JC::C, "johnson_cook.C", Range::kFinite))
      .def_property("reference_strain_rate_1_s", law_get(&JC::reference_strain_rate_1_s),
                    law_set(&JC::reference_strain_rate_1_s,
                            "johnson_cook.reference_strain_rate_1_s", Range::kPositive))
      .def_property("m", law_get(&JC::m), law_set(&JC::m, "johnson_cook.m", Range::kPositive))
      .def_property(
          "room_temperature_K", law_get(&JC::room_temperature_K),
          law_set<JC>("johnson_cook.room_temperature_K",
                      jc_temperature(&JC::room_temperature_K, "johnson_cook.room_temperature_K")))
      .def_property("melting_temperature_K", law_get(&JC::melting_temperature_K),
                    law_set<JC>("johnson_cook.melting_temperature_K",
                                jc_temperature(&JC::melting_temperature_K,
                                               "johnson_cook.melting_temperature_K")))
      .def_property("initial_temperature_K", law_get(&JC::initial_temperature_K),
                    law_set<JC>("johnson_cook.initial_temperature_K",
                                jc_temperature(&JC::initial_temperature_K,
                                               "johnson_cook.initial_temperature_K")))
      .def_property("specific_heat_J_kgK", law_get(&JC::specific_heat_J_kgK),
                    law_set<JC>("johnson_cook.specific_heat_J_kgK",
                                [](JC& o, const py::object& x) {
                                  checked(&JC::specific_heat_J_kgK,
                                          "johnson_cook.specific_heat_J_kgK",
                                          Range::kPositive)(o, x);
                                  o.specific_heat_given = true;
                                }))
      .def_property("taylor_quinney", law_get(&JC::taylor_quinney),
                    law_set(&JC::taylor_quinney, "johnson_cook.taylor_quinney", Range::kFraction))
      .def_property("adiabatic", law_get(&JC::adiabatic),
                    law_set<JC>("johnson_cook.adiabatic",
                                [](JC& o, const py::object& x) {
                                  // True or False (a numpy bool by its value), as the file's
                                  // JSON boolean; anything else a TypeError naming it.
                                  const bool on = boolean(x, "johnson_cook.adiabatic");
                                  if (on && !o.specific_heat_given)
                                    throw input_error(
                                        "scene edit", "johnson_cook.adiabatic", "True",
                                        "adiabatic heating needs the material's specific heat: "
                                        "set johnson_cook.specific_heat_J_kgK first");
                                  o.adiabatic = on;
                                }))
      // None: the default (the scene's specimen: half its elastic transit; other bars: off).
      .def_property("strain_rate_filter_s", law_get(&JC::strain_rate_filter_s),
                    law_set<JC>("johnson_cook.strain_rate_filter_s",
                                [](JC& o, const py::object& x) {
                                  if (x.is_none()) {
                                    o.strain_rate_filter_s.reset();
                                    return;
                                  }
                                  o.strain_rate_filter_s = checked_value(
                                      x, "johnson_cook.strain_rate_filter_s", Range::kNonNegative);
                                }))
      .def("__repr__", [](const JohnsonCook& l) {
        const JC& o = params_of(l);
        return "<shpb.JohnsonCook " +
               fields({{"A_Pa", o.A_Pa},
                       {"B_Pa", o.B_Pa},
                       {"n", o.n},
                       {"C", o.C},
                       {"reference_strain_rate_1_s", o.reference_strain_rate_1_s},
                       {"m", o.m},
                       {"room_temperature_K", o.room_temperature_K},
                       {"melting_temperature_K", o.melting_temperature_K},
                       {"initial_temperature_K", o.initial_temperature_K}}) +
               (o.adiabatic ? ", adiabatic" : "") + ">";
      });
}

void bind_bilinear(py::module_& m) {
  py::class_<Bilinear>(m, "Bilinear")
      .def_property(
          "yield_stress_Pa", law_get(&BilinearParams::yield_stress_Pa),
          law_set(&BilinearParams::yield_stress_Pa, "bilinear.yield_stress_Pa", Range::kPositive))
      .def_property(
          "tangent_modulus_Pa", law_get(&BilinearParams::tangent_modulus_Pa),
          [](Bilinear& l, const py::object& x) {
            BilinearParams& p = l.material->bilinear;
            const double before = p.tangent_modulus_Pa;
            law_set(&BilinearParams::tangent_modulus_Pa, "bilinear.tangent_modulus_Pa",
                    Range::kNonNegative)(l, x);  // the law and the range (refused: unchanged)
            if (const std::string what =
                    tangent_modulus_problem(p.tangent_modulus_Pa, l.material->youngs_modulus_Pa);
                !what.empty()) {
              const double refused = p.tangent_modulus_Pa;
              p.tangent_modulus_Pa = before;
              throw input_error("scene edit", "bilinear.tangent_modulus_Pa", format_double(refused),
                                what);
            }
          })
      .def("__repr__", [](const Bilinear& l) {
        const BilinearParams& o = params_of(l);
        return "<shpb.Bilinear " +
               fields({{"yield_stress_Pa", o.yield_stress_Pa},
                       {"tangent_modulus_Pa", o.tangent_modulus_Pa}}) +
               ">";
      });
}

// Young's modulus edited as a file could give it: a viscoelastic material has none of its own (its
// instantaneous modulus is its long-term modulus plus its arms', which the meshes and the wave
// speed follow), and a bilinear law's tangent modulus stays below it.
void set_youngs_modulus(MaterialSpec& o, const py::object& value) {
  const char* name = "material.youngs_modulus_Pa";
  if (o.model == MaterialModel::kViscoelastic)
    throw input_error("scene edit", name, shown(value),
                      "material \"" + o.name +
                          "\" is viscoelastic: its modulus is its long_term_modulus plus its "
                          "arms' moduli (a scene file gives it no youngs_modulus)");
  MaterialSpec edited = o;
  checked(&MaterialSpec::youngs_modulus_Pa, name, Range::kPositive)(edited, value);
  if (o.model == MaterialModel::kBilinear)
    if (const std::string what =
            tangent_modulus_problem(edited.bilinear.tangent_modulus_Pa, edited.youngs_modulus_Pa);
        !what.empty())
      throw input_error("scene edit", name, format_double(edited.youngs_modulus_Pa),
                        "bilinear.tangent_modulus_Pa " +
                            format_double(edited.bilinear.tangent_modulus_Pa) + " " + what);
  o.youngs_modulus_Pa = edited.youngs_modulus_Pa;
}

}  // namespace

void bind_materials(py::module_& m) {
  bind_johnson_cook(m);
  bind_bilinear(m);
  bind_viscoelastic(m);
  py::class_<MaterialSpec>(m, "Material")
      .def_readonly("name", &MaterialSpec::name)
      .def_property_readonly("model",
                             [](const MaterialSpec& s) { return std::string(to_string(s.model)); })
      .def_property(
          "density_kg_m3", [](const MaterialSpec& o) { return o.density_kg_m3; },
          checked(&MaterialSpec::density_kg_m3, "material.density_kg_m3", Range::kPositive))
      .def_property(
          "youngs_modulus_Pa", [](const MaterialSpec& o) { return o.youngs_modulus_Pa; },
          &set_youngs_modulus)
      .def_property(
          "poisson_ratio", [](const MaterialSpec& o) { return o.poisson_ratio; },
          [](MaterialSpec& o, const py::object& value) {
            const double x = number<double>(value, "material.poisson_ratio");
            if (!(x > kPoissonRatioAbove && x < kPoissonRatioBelow))
              throw input_error("scene edit", "material.poisson_ratio", format_double(x),
                                "must be in (" + format_double(kPoissonRatioAbove) + ", " +
                                    format_double(kPoissonRatioBelow) + ")");
            o.poisson_ratio = x;
          })
      // The group holds its material alive. A property applies no call policy given beside its
      // getter (pybind11 takes only the function's record from it), so the getter carries it.
      .def_property_readonly(
          "bilinear",
          py::cpp_function([](MaterialSpec& s) { return Bilinear{&s}; }, py::keep_alive<0, 1>()))
      .def_property_readonly(
          "johnson_cook",
          py::cpp_function([](MaterialSpec& s) { return JohnsonCook{&s}; }, py::keep_alive<0, 1>()))
      .def_property_readonly("viscoelastic",
                             py::cpp_function([](MaterialSpec& s) { return Viscoelastic{&s}; },
                                              py::keep_alive<0, 1>()))
      .def_property_readonly("wave_speed_m_s", &MaterialSpec::wave_speed_m_s)
      .def("__repr__", [](const MaterialSpec& s) {
        return "<shpb.Material " + s.name + " (" + std::string(to_string(s.model)) + "): " +
               fields({{"density_kg_m3", s.density_kg_m3},
                       {"youngs_modulus_Pa", s.youngs_modulus_Pa},
                       {"poisson_ratio", s.poisson_ratio},
                       {"wave_speed_m_s", s.wave_speed_m_s()}}) +
               ">";
      });
}

}  // namespace shpb::python
