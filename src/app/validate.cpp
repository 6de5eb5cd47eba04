// `shpb validate SCENE.json [--json]`: reads and checks a scene with the checks every command
// shares (apply_overrides → validate_scene), then prints the resolved set-up — exactly the mesh,
// time steps and interface links `simulate` will use (discretize(), interface_model()) and, for a
// scene with a measurement, what `process` will read and use (the signals read by the same
// read_gauge_signals, the gauges resolved by the same resolve_setup / resolve_bar_check). A scene
// that only processes (a bar without material) is checked for `process` alone.
#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "analysis/bar_check.hpp"
#include "analysis/gauge_signals.hpp"
#include "analysis/processing.hpp"
#include "app/commands.hpp"
#include "core/csv_writer.hpp"
#include "core/output_folder.hpp"
#include "model/calibration.hpp"
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

// The bars and gauges as read; with the mesh and steps of `d` when the scene simulates.
json bars_and_gauges(const Scene& scene, const ChainDiscretization* d) {
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

json resolved_setup(const Scene& scene, const ChainDiscretization& d) {
  json out = bars_and_gauges(scene, &d);
  out["memory_estimate_bytes"] = d.memory_estimate_bytes;
  out["node_updates_estimate"] = d.node_updates_estimate;
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

json window_json(const std::optional<TimeWindow>& w) {
  return w ? json::array({w->start_s, w->end_s}) : json("detected");
}

json column_json(const ColumnRef& c) { return c.index ? json(*c.index) : json(c.name); }

// What `process` will read and use, read and resolved by process's own functions: every channel
// (file, column, unit, strain per unit), the common time base, the gauges' roles and distances,
// the windows, the dispersion correction, the expected pulse timing, and the warnings process
// would give on reading. A problem is the InputError process would throw (exit 2).
json process_setup(const Scene& scene) {
  const MeasurementSpec& m = *scene.measurement;
  const GaugeSignals signals = read_gauge_signals(m, {});
  json p;
  p["file"] = m.file.empty() ? json(nullptr) : json(m.file.string());
  p["format"] = std::string(enum_name(kSignalFormatNames, m.format));
  if (!m.sheet.empty()) p["sheet"] = m.sheet;
  p["time_column"] = m.time_column.name.empty() && !m.time_column.index
                         ? json("the format's own")
                         : column_json(m.time_column);
  p["time_unit"] = m.time_unit;
  p["samples"] = signals.time_s.size();
  p["sample_interval_s"] = signals.dt_s;
  p["record_s"] = {signals.time_s.front(), signals.time_s.back()};
  for (const ChannelSpec& ch : m.channels) {
    json c = {{"gauge", ch.gauge},
              {"file", (ch.file.empty() ? m.file : ch.file).string()},
              {"column", column_json(ch.column)},
              {"unit", std::string(enum_name(kSignalUnitNames, ch.unit))},
              {"invert", ch.invert}};
    double per_unit = ch.unit == SignalUnit::kMicrostrain ? 1e-6 : 1.0;
    if (ch.unit == SignalUnit::kVolt) per_unit = ch.scale ? *ch.scale : volts_to_strain(*ch.bridge);
    if (ch.bridge)
      c["bridge"] = {{"arms", ch.bridge->arms},
                     {"gauge_factor", ch.bridge->gauge_factor},
                     {"excitation_V", ch.bridge->excitation_V},
                     {"gain", ch.bridge->gain}};
    c["strain_per_unit"] = per_unit;
    p["channels"].push_back(c);
  }
  for (std::size_t g = 0; g < signals.gauges.size(); ++g) {
    const auto [lo, hi] = std::minmax_element(signals.strain[g].begin(), signals.strain[g].end());
    p["gauges"].push_back({{"name", signals.gauges[g]}, {"strain_min", *lo}, {"strain_max", *hi}});
  }
  std::vector<std::string> warnings = signals.warnings;
  const std::vector<std::string> record = signal_warnings(signals);
  warnings.insert(warnings.end(), record.begin(), record.end());
  if (scene.specimen) {
    const KolskySetup k = resolve_setup(scene, signals.gauges);
    p["reduction"] = "specimen";
    p["test"] = m.tension ? "tension" : "compression";
    p["incident_gauge"] = {{"name", k.incident_gauge},
                           {"distance_to_specimen_m", k.incident_distance_m}};
    p["transmitted_gauge"] = {{"name", k.transmitted_gauge},
                              {"distance_to_specimen_m", k.transmitted_distance_m}};
    // Timing of the 1D bar model (docs/methods.md §6): the reflected pulse reaches the incident
    // gauge 2d/c0 after the incident pulse (the lab's calibrated time when given), the
    // transmitted one reaches its gauge (d_i/c0 + d_t/c0) after it (the specimen's transit aside).
    const double reflected =
        m.reflected_time_s.value_or(2 * k.incident_distance_m / k.front.c0_m_s);
    const double transmitted =
        k.incident_distance_m / k.front.c0_m_s + k.transmitted_distance_m / k.back.c0_m_s;
    p["timing"] = {
        {"reflected_after_incident_s", reflected},
        {"transmitted_after_incident_s", transmitted},
        {"reflected_time", m.reflected_time_s ? "measurement.reflected_time" : "2 d / c0"}};
  } else {
    const BarCheckSetup b = resolve_bar_check(scene, signals.gauges);
    p["reduction"] = "bars together (no specimen)";
    p["near_gauge"] = b.near_gauge;
    p["far_gauge"] = b.far_gauge;
    p["distance_m"] = b.distance_m;
  }
  p["windows"] = {{"incident", window_json(m.windows.incident)},
                  {"reflected", window_json(m.windows.reflected)},
                  {"transmitted", window_json(m.windows.transmitted)}};
  p["dispersion"] = std::string(enum_name(kCorrectionNames, m.dispersion.correction));
  p["warnings"] = warnings;
  return p;
}

// "a" or "a / b" for the links of an interface.
std::string links(const json& values) {
  std::string t;
  for (const auto& v : values) t += (t.empty() ? "" : " / ") + g(v.get<double>());
  return t;
}

void print_simulation(const json& s) {
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
}

void print_process(const json& p) {
  std::printf("\nprocess      %s%s, %zu samples at %s us (%s MHz), %s to %s us\n",
              p["reduction"].get<std::string>().c_str(),
              p.contains("test") ? (", " + p["test"].get<std::string>() + " test").c_str() : "",
              p["samples"].get<std::size_t>(),
              g(p["sample_interval_s"].get<double>() * 1e6).c_str(),
              g(1e-6 / p["sample_interval_s"].get<double>()).c_str(),
              g(p["record_s"][0].get<double>() * 1e6).c_str(),
              g(p["record_s"][1].get<double>() * 1e6).c_str());
  std::printf("%-14s %-40s %-14s %-11s %14s %12s %12s\n", "channel", "file", "column", "unit",
              "strain/unit", "min_strain", "max_strain");
  for (const auto& c : p["channels"]) {
    const std::string gauge = c["gauge"].get<std::string>();
    const json* peaks = nullptr;
    for (const auto& gj : p["gauges"])
      if (gj["name"] == gauge) peaks = &gj;
    const json& col = c["column"];
    std::string column = "#";  // by index; built by append (GCC 12 warns falsely on "#" + string)
    if (col.is_string())
      column = col.get<std::string>();
    else
      column.append(std::to_string(col.get<int>()));
    std::printf("%-14s %-40s %-14s %-11s %14s %12s %12s\n", gauge.c_str(),
                c["file"].get<std::string>().c_str(), column.c_str(),
                (c["unit"].get<std::string>() + (c["invert"].get<bool>() ? " (inv)" : "")).c_str(),
                g(c["strain_per_unit"].get<double>()).c_str(),
                g((*peaks)["strain_min"].get<double>()).c_str(),
                g((*peaks)["strain_max"].get<double>()).c_str());
  }
  if (p.contains("incident_gauge")) {
    std::printf(
        "gauges       incident \"%s\" %s mm and transmitted \"%s\" %s mm from the specimen\n",
        p["incident_gauge"]["name"].get<std::string>().c_str(),
        g(p["incident_gauge"]["distance_to_specimen_m"].get<double>() * 1e3).c_str(),
        p["transmitted_gauge"]["name"].get<std::string>().c_str(),
        g(p["transmitted_gauge"]["distance_to_specimen_m"].get<double>() * 1e3).c_str());
    std::printf("timing       reflected %s us after the incident (%s), transmitted %s us\n",
                g(p["timing"]["reflected_after_incident_s"].get<double>() * 1e6).c_str(),
                p["timing"]["reflected_time"].get<std::string>().c_str(),
                g(p["timing"]["transmitted_after_incident_s"].get<double>() * 1e6).c_str());
  } else {
    std::printf(
        "gauges       \"%s\" -> \"%s\" over %s mm\n", p["near_gauge"].get<std::string>().c_str(),
        p["far_gauge"].get<std::string>().c_str(), g(p["distance_m"].get<double>() * 1e3).c_str());
  }
  std::string windows;
  for (const char* w : {"incident", "reflected", "transmitted"}) {
    const json& v = p["windows"][w];
    windows +=
        std::string(windows.empty() ? "" : ", ") + w + " " +
        (v.is_string() ? v.get<std::string>()
                       : g(v[0].get<double>() * 1e6) + "-" + g(v[1].get<double>() * 1e6) + " us");
  }
  std::printf("windows      %s\n", windows.c_str());
  std::printf("dispersion   %s\n", p["dispersion"].get<std::string>().c_str());
  for (const auto& w : p["warnings"]) std::printf("warning: %s\n", w.get<std::string>().c_str());
}

void print_table(const json& s) {
  std::printf("scene      %s (%s)\n", s["name"].get<std::string>().c_str(),
              s["file"].get<std::string>().c_str());
  if (s.contains("calibration"))
    std::printf("calibration %s\n", s["calibration"]["file"].get<std::string>().c_str());
  std::printf("specimen   %s\n\n",
              s["specimen"].is_null() ? "(none)" : s["specimen"].get<std::string>().c_str());
  const bool simulates = s.contains("interfaces");
  if (simulates) {
    std::printf("%-12s %-26s %-12s %9s %8s %9s %8s %10s %9s %9s %9s %7s\n", "bar", "material",
                "model", "length_mm", "diam_mm", "area_mm2", "c0_m/s", "Z_kg/s", "elements", "h_mm",
                "dt_ns", "courant");
    for (const auto& b : s["bars"]) {
      std::printf(
          "%-12s %-26s %-12s %9s %8s %9s %8s %10s %9d %9s %9s %7s\n",
          b["name"].get<std::string>().c_str(), b["material"].get<std::string>().c_str(),
          b["model"].get<std::string>().c_str(), g(b["length_m"].get<double>() * 1e3).c_str(),
          g(b["diameter_m"].get<double>() * 1e3).c_str(),
          g(b["area_m2"].get<double>() * 1e6).c_str(), g(b["wave_speed_m_s"].get<double>()).c_str(),
          g(b["impedance_kg_s"].get<double>()).c_str(), b["elements"].get<int>(),
          g(b["element_length_m"].get<double>() * 1e3).c_str(),
          g(b["time_step_s"].get<double>() * 1e9).c_str(), g(b["courant"].get<double>()).c_str());
    }
  } else {  // a scene that only processes: no mesh
    std::printf("%-12s %-26s %9s %8s %9s %8s\n", "bar", "material", "length_mm", "diam_mm",
                "area_mm2", "c0_m/s");
    for (const auto& b : s["bars"]) {
      const bool known = !b["material"].is_null();
      std::printf("%-12s %-26s %9s %8s %9s %8s\n", b["name"].get<std::string>().c_str(),
                  known ? b["material"].get<std::string>().c_str() : "(none)",
                  g(b["length_m"].get<double>() * 1e3).c_str(),
                  g(b["diameter_m"].get<double>() * 1e3).c_str(),
                  g(b["area_m2"].get<double>() * 1e6).c_str(),
                  known ? g(b["wave_speed_m_s"].get<double>()).c_str() : "-");
    }
  }
  std::printf("\n%-14s %-12s %12s %22s\n", "gauge", "bar", "position_mm", "to_specimen_face_mm");
  for (const auto& gj : s["gauges"]) {
    const auto& d = gj["distance_to_specimen_m"];
    std::printf("%-14s %-12s %12s %22s\n", gj["name"].get<std::string>().c_str(),
                gj["bar"].get<std::string>().c_str(),
                g(gj["position_m"].get<double>() * 1e3).c_str(),
                d.is_null() ? "-" : g(d.get<double>() * 1e3).c_str());
  }
  if (simulates)
    print_simulation(s);
  else
    std::printf("\nsimulation   not possible: %s\n", s["simulation"].get<std::string>().c_str());
  if (s.contains("process")) print_process(s["process"]);
  for (const auto& w : s["warnings"]) std::printf("warning: %s\n", w.get<std::string>().c_str());
}

}  // namespace

int run_validate(const ValidateArgs& args) {
  Scene scene = read_scene(args.scene);
  const bool measured = scene.measurement && !scene.measurement->channels.empty();
  const auto no_material = std::find_if(scene.bars.begin(), scene.bars.end(),
                                        [](const BarSpec& b) { return !b.has_material; });
  json setup;
  if (no_material != scene.bars.end() && measured) {
    // Only `process` runs on it: nothing to mesh.
    setup = bars_and_gauges(scene, nullptr);
    setup["simulation"] = "bar \"" + no_material->name + "\" has no material (only process runs)";
    setup["warnings"] = json::array();
  } else {
    Scene automatic = scene;  // for the cost of the tolerance's meshes against today's
    setup = resolved_setup(scene, apply_overrides(args.overrides, scene));
    if (scene.simulation.tolerance) {
      RunOverrides o = args.overrides;
      o.tolerance.reset();
      automatic.simulation.tolerance.reset();
      setup["cost_against_automatic"] = setup["node_updates_estimate"].get<double>() /
                                        apply_overrides(o, automatic).node_updates_estimate;
    }
  }
  if (measured) {
    // A record not there (kept elsewhere) stays a warning, as for simulate; a record that is
    // there is read as process reads it.
    std::filesystem::path missing;
    std::error_code ec;
    for (const ChannelSpec& c : scene.measurement->channels) {
      const auto& f = c.file.empty() ? scene.measurement->file : c.file;
      if (missing.empty() && !std::filesystem::exists(f, ec)) missing = f;
    }
    if (missing.empty()) {
      setup["process"] = process_setup(scene);
    } else {
      bool said = false;  // scene_warnings names a missing measurement.file already
      for (const auto& w : setup["warnings"])
        said = said || w.get<std::string>().find(missing.string()) != std::string::npos;
      if (!said)
        setup["warnings"].push_back("measurement file " + missing.string() +
                                    " not found (process and compare will need it)");
    }
  }
  throw_if_interrupted();  // a signal during the checks: exit 130, not a report
  if (args.json)
    std::printf("%s\n", setup.dump(2).c_str());
  else
    print_table(setup);
  return 0;
}

}  // namespace shpb
