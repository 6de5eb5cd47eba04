// `shpb validate SCENE.json [--json]`: reads and checks a scene with the checks every command
// shares (apply_overrides → validate_scene), then prints the resolved set-up — exactly the mesh,
// time steps and interface links `simulate` will use (discretize(), interface_model()).
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "app/commands.hpp"
#include "core/csv_writer.hpp"
#include "core/output_folder.hpp"
#include "model/discretization.hpp"
#include "model/mesh_error_model.hpp"
#include "model/scene_checks.hpp"
#include "model/test_setup.hpp"
#include "solver/contact.hpp"

namespace shpb {
namespace {

using nlohmann::json;

std::string g(double v, int digits = 4) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

json resolved_setup(const Scene& scene, const ChainDiscretization& d) {
  json out;
  out["name"] = scene.name;
  out["file"] = scene.file.string();
  out["specimen"] = scene.specimen ? json(scene.bars[*scene.specimen].name) : json(nullptr);
  out["memory_estimate_bytes"] = d.memory_estimate_bytes;
  out["node_updates_estimate"] = d.node_updates_estimate;
  for (std::size_t i = 0; i < scene.bars.size(); ++i) {
    const auto& b = scene.bars[i];
    const auto& m = b.material;
    const auto& bd = d.bars[i];
    out["bars"].push_back({{"name", b.name},
                           {"material", m.name},
                           {"model", to_string(m.model)},
                           {"length_m", b.length_m},
                           {"diameter_m", b.diameter_m},
                           {"area_m2", b.area_m2},
                           {"density_kg_m3", m.density_kg_m3},
                           {"youngs_modulus_Pa", m.youngs_modulus_Pa},
                           {"poisson_ratio", m.poisson_ratio},
                           {"wave_speed_m_s", m.wave_speed_m_s()},
                           {"impedance_kg_s", b.impedance_kg_s()},
                           {"velocity_m_s", b.velocity_m_s},
                           {"gap_m", b.gap_m},
                           {"elements", bd.elements},
                           {"element_length_m", bd.element_length_m},
                           {"critical_step_s", bd.critical_step_s},
                           {"time_step_s", bd.time_step_s},
                           {"courant", bd.courant}});
    for (const auto& g : b.gauges) {
      json gj = {{"name", g.name}, {"bar", b.name}, {"position_m", g.position_m}};
      const auto dist = distance_to_specimen_m(scene, i, g.position_m);
      gj["distance_to_specimen_m"] = dist ? json(*dist) : json(nullptr);
      out["gauges"].push_back(gj);
    }
  }
  if (!out.contains("gauges")) out["gauges"] = json::array();
  const TestRoles roles = test_roles(scene);
  auto bar_name = [&](std::optional<std::size_t> i) {
    return i ? json(scene.bars[*i].name) : json(nullptr);
  };
  json shapers = json::array();
  for (const std::size_t i : roles.shapers) shapers.push_back(scene.bars[i].name);
  out["roles"] = {{"striker", bar_name(roles.striker)},
                  {"shapers", shapers},
                  {"incident", bar_name(roles.incident)},
                  {"specimen", bar_name(roles.specimen)},
                  {"transmitter", bar_name(roles.transmitter)}};
  const auto speed = scene_striker_speed_m_s(scene);
  out["striker_velocity_m_s"] = speed ? json(striker_direction(scene) * *speed) : json(nullptr);
  for (std::size_t i = 0; i + 1 < scene.bars.size(); ++i) {
    // What the run uses: the rigid-link limit ignores the penalty values; finite localized
    // links have one per side; node-to-node methods one link (no mass penalty for penalty).
    const InterfaceModel m = interface_model(scene, d, i);
    json links;
    if (m.method == ContactMethod::kLocalizedBipenalty && !m.finite_links) {
      links = "rigid-link limit";
    } else {
      const int count = m.method == ContactMethod::kLocalizedBipenalty ? 2 : 1;
      json stiffness = json::array(), mass = json::array();
      for (int k = 0; k < count; ++k) {
        stiffness.push_back(m.stiffness_N_m[k]);
        mass.push_back(m.mass_penalty_kg[k]);
      }
      links = {{"stiffness_N_m", stiffness}};
      if (m.method != ContactMethod::kPenalty) links["mass_penalty_kg"] = mass;
    }
    out["interfaces"].push_back({{"left", scene.bars[i].name},
                                 {"right", scene.bars[i + 1].name},
                                 {"method", to_string(m.method)},
                                 {"gap_m", m.gap0_m},
                                 {"links", links}});
  }
  const auto warnings = scene_warnings(scene, d.duration_s);
  out["warnings"] = warnings;
  out["duration_s"] = d.duration_s;
  out["sample_rate_Hz"] = d.sample_rate_Hz;
  out["stepping"] = to_string(d.stepping);
  // Material-law bars: finite strain plans their step for this largest compression.
  out["kinematics"] = std::string(enum_name(kKinematicsNames, scene.simulation.finite_strain));
  out["max_strain"] = scene.simulation.finite_strain
                          ? json(scene.simulation.max_strain.value_or(kDefaultMaxStrain))
                          : json(nullptr);
  out["measurement"] = scene.measurement ? json({{"file", scene.measurement->file.string()},
                                                 {"channels", scene.measurement->channels.size()}})
                                         : json(nullptr);
  if (const auto t = scene.simulation.tolerance) {  // the meshes above are the model's choice
    const GaugeErrorPrediction p = predict_gauge_error(scene, d);
    out["tolerance"] = *t;
    out["predicted_gauge_error"] = p.total;
    out["predicted_gauge_error_bars"] = p.bars;
    out["predicted_gauge_error_specimen"] = p.specimen;
    out["pulse_rise_time_s"] = p.rise_time_s;  // what the model took: 0 is a step
    out["pulse_duration_s"] = p.pulse_s;
  }
  return out;
}

// "a" or "a / b" for the links of an interface.
std::string links(const json& values) {
  std::string t;
  for (const auto& v : values) t += (t.empty() ? "" : " / ") + g(v.get<double>());
  return t;
}

void print_table(const json& s) {
  std::printf("scene      %s (%s)\n", s["name"].get<std::string>().c_str(),
              s["file"].get<std::string>().c_str());
  std::printf("specimen   %s\n\n",
              s["specimen"].is_null() ? "(none)" : s["specimen"].get<std::string>().c_str());
  std::printf("%-12s %-26s %-12s %9s %8s %9s %8s %10s %9s %9s %9s %7s\n", "bar", "material",
              "model", "length_mm", "diam_mm", "area_mm2", "c0_m/s", "Z_kg/s", "elements", "h_mm",
              "dt_ns", "courant");
  for (const auto& b : s["bars"]) {
    std::printf(
        "%-12s %-26s %-12s %9s %8s %9s %8s %10s %9d %9s %9s %7s\n",
        b["name"].get<std::string>().c_str(), b["material"].get<std::string>().c_str(),
        b["model"].get<std::string>().c_str(), g(b["length_m"].get<double>() * 1e3).c_str(),
        g(b["diameter_m"].get<double>() * 1e3).c_str(), g(b["area_m2"].get<double>() * 1e6).c_str(),
        g(b["wave_speed_m_s"].get<double>()).c_str(), g(b["impedance_kg_s"].get<double>()).c_str(),
        b["elements"].get<int>(), g(b["element_length_m"].get<double>() * 1e3).c_str(),
        g(b["time_step_s"].get<double>() * 1e9).c_str(), g(b["courant"].get<double>()).c_str());
  }
  std::printf("\n%-14s %-12s %12s %22s\n", "gauge", "bar", "position_mm", "to_specimen_face_mm");
  for (const auto& gj : s["gauges"]) {
    const auto& d = gj["distance_to_specimen_m"];
    std::printf("%-14s %-12s %12s %22s\n", gj["name"].get<std::string>().c_str(),
                gj["bar"].get<std::string>().c_str(),
                g(gj["position_m"].get<double>() * 1e3).c_str(),
                d.is_null() ? "-" : g(d.get<double>() * 1e3).c_str());
  }
  std::printf("\n%-28s %-20s %8s %24s %24s\n", "interface", "method", "gap_mm",
              "link_stiffness_N/m", "link_mass_penalty_kg");
  for (const auto& i : s["interfaces"]) {
    const std::string name = i["left"].get<std::string>() + " | " + i["right"].get<std::string>();
    const json& l = i["links"];
    std::string stiffness, mass;
    if (l.is_string()) {
      stiffness = l.get<std::string>();
    } else {
      stiffness = links(l["stiffness_N_m"]);
      mass = l.contains("mass_penalty_kg") ? links(l["mass_penalty_kg"]) : "-";
    }
    std::printf("%-28s %-20s %8s %24s %24s\n", name.c_str(), i["method"].get<std::string>().c_str(),
                g(i["gap_m"].get<double>() * 1e3).c_str(), stiffness.c_str(), mass.c_str());
  }
  std::printf("\nduration     %s us\n", g(s["duration_s"].get<double>() * 1e6).c_str());
  std::printf("sample rate  %s MHz\n", g(s["sample_rate_Hz"].get<double>() * 1e-6).c_str());
  std::printf("stepping     %s\n", s["stepping"].get<std::string>().c_str());
  if (!s["max_strain"].is_null())  // finite kinematics: the strain its steps are planned for
    std::printf("kinematics   finite (material-law bars; steps planned for %s strain)\n",
                g(s["max_strain"].get<double>()).c_str());
  else
    std::printf("kinematics   small\n");
  if (!s["measurement"].is_null())
    std::printf("measurement  %s (%zu channels)\n",
                s["measurement"]["file"].get<std::string>().c_str(),
                s["measurement"]["channels"].get<std::size_t>());
  if (s.contains("tolerance"))
    std::printf(
        "tolerance    %s %%: meshes above chosen by the gauge-error model (docs/methods.md §1.1) "
        "for a %s us pulse with %s; predicted gauge error %s %% (bar fronts %s %%, specimen mesh "
        "%s %%); %s node updates, %s x the automatic meshes\n",
        g(100 * s["tolerance"].get<double>()).c_str(),
        g(1e6 * s["pulse_duration_s"].get<double>()).c_str(),
        s["pulse_rise_time_s"].get<double>() > 0
            ? ("a " + g(1e6 * s["pulse_rise_time_s"].get<double>()) + " us rise").c_str()
            : "step fronts",
        g(100 * s["predicted_gauge_error"].get<double>(), 3).c_str(),
        g(100 * s["predicted_gauge_error_bars"].get<double>(), 3).c_str(),
        g(100 * s["predicted_gauge_error_specimen"].get<double>(), 3).c_str(),
        g(s["node_updates_estimate"].get<double>(), 3).c_str(),
        g(s["cost_against_automatic"].get<double>(), 3).c_str());
  for (const auto& w : s["warnings"]) std::printf("warning: %s\n", w.get<std::string>().c_str());
}

}  // namespace

int run_validate(const ValidateArgs& args) {
  Scene scene = read_scene(args.scene);
  Scene automatic = scene;  // for the cost of the tolerance's meshes against today's
  json setup = resolved_setup(scene, apply_overrides(args.overrides, scene));
  if (scene.simulation.tolerance) {
    RunOverrides o = args.overrides;
    o.tolerance.reset();
    automatic.simulation.tolerance.reset();
    setup["cost_against_automatic"] = setup["node_updates_estimate"].get<double>() /
                                      apply_overrides(o, automatic).node_updates_estimate;
  }
  throw_if_interrupted();  // a signal during the checks: exit 130, not a report
  if (args.json)
    std::printf("%s\n", setup.dump(2).c_str());
  else
    print_table(setup);
  return 0;
}

}  // namespace shpb
