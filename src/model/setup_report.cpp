#include "model/setup_report.hpp"

#include "model/calibration.hpp"
#include "model/mesh_error_model.hpp"
#include "model/scene_checks.hpp"
#include "model/test_setup.hpp"

namespace shpb {

using nlohmann::json;

// The bars and gauges as read; with the mesh and steps of `d` when the scene simulates.
json scene_setup_json(const Scene& scene, const ChainDiscretization* d) {
  json out;
  out["name"] = scene.name;
  out["file"] = scene.file.string();
  // The values below are the calibration's where it gives them (model/calibration.hpp).
  if (!scene.calibration_file.empty()) out["calibration"] = calibration_summary(scene);
  out["specimen"] = scene.specimen ? json(scene.bars[*scene.specimen].name) : json(nullptr);
  for (std::size_t i = 0; i < scene.bars.size(); ++i) {
    const auto& b = scene.bars[i];
    const auto& m = b.material;
    json bar = {
        {"name", b.name},       {"length_m", b.length_m},         {"diameter_m", b.diameter_m},
        {"area_m2", b.area_m2}, {"velocity_m_s", b.velocity_m_s}, {"gap_m", b.gap_m}};
    if (b.has_material) {
      bar.update({{"material", m.name},
                  {"model", to_string(m.model)},
                  {"density_kg_m3", m.density_kg_m3},
                  {"youngs_modulus_Pa", m.youngs_modulus_Pa},
                  {"poisson_ratio", m.poisson_ratio},
                  {"wave_speed_m_s", m.wave_speed_m_s()},
                  {"impedance_kg_s", b.impedance_kg_s()}});
    } else {
      bar["material"] = nullptr;
    }
    if (d) {
      const auto& bd = d->bars[i];
      bar.update({{"elements", bd.elements},
                  {"element_length_m", bd.element_length_m},
                  {"critical_step_s", bd.critical_step_s},
                  {"time_step_s", bd.time_step_s},
                  {"courant", bd.courant}});
    }
    out["bars"].push_back(bar);
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
  return out;
}

json resolved_setup_json(const Scene& scene, const ChainDiscretization& d) {
  json out = scene_setup_json(scene, &d);
  out["memory_estimate_bytes"] = d.memory_estimate_bytes;
  out["node_updates_estimate"] = d.node_updates_estimate;
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
    out["tolerance_is_default"] = scene.simulation.tolerance_is_default;
    out["predicted_gauge_error"] = p.total;
    out["predicted_gauge_error_bars"] = p.bars;
    out["predicted_gauge_error_specimen"] = p.specimen;
    out["pulse_rise_time_s"] = p.rise_time_s;  // what the model took: 0 is a step
    out["pulse_duration_s"] = p.pulse_s;
  } else if (!scene.simulation.tolerance_withheld.empty()) {
    out["tolerance_withheld"] = scene.simulation.tolerance_withheld;
  }
  return out;
}

}  // namespace shpb
