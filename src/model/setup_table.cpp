// validate's table: the resolved set-up document (model/setup_report.hpp) as text.
#include <cstdio>
#include <string>

#include "core/number_format.hpp"
#include "model/setup_report.hpp"

namespace shpb {
namespace {

using nlohmann::json;

std::string g(double v, int digits = 4) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
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
    std::string stiffness, mass = "-";  // the rigid-link limit and penalty take no mass penalty
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
        "tolerance    %s %%%s: meshes above chosen by the gauge-error model (docs/methods.md "
        "§1.1) for a %s us pulse with %s; predicted gauge error %s %% (bar fronts %s %%, specimen "
        "mesh %s %%); %s node updates, %s x the automatic meshes\n",
        g(100 * s["tolerance"].get<double>()).c_str(),
        s.value("tolerance_is_default", false)
            ? " (the default: the scene and the command line give none; bars with their own "
              "elements keep them)"
            : "",
        g(1e6 * s["pulse_duration_s"].get<double>()).c_str(),
        s["pulse_rise_time_s"].get<double>() > 0
            ? ("a " + g(1e6 * s["pulse_rise_time_s"].get<double>()) + " us rise").c_str()
            : "step fronts",
        g(100 * s["predicted_gauge_error"].get<double>(), 3).c_str(),
        g(100 * s["predicted_gauge_error_bars"].get<double>(), 3).c_str(),
        g(100 * s["predicted_gauge_error_specimen"].get<double>(), 3).c_str(),
        g(s["node_updates_estimate"].get<double>(), 3).c_str(),
        g(s["cost_against_automatic"].get<double>(), 3).c_str());
  else if (s.contains("tolerance_withheld"))
    std::printf("tolerance    none: the automatic meshes above, not the default %s %%: %s\n",
                g(100 * kDefaultTolerance).c_str(),
                s["tolerance_withheld"].get<std::string>().c_str());
}

void print_process(const json& p) {
  std::printf("\nprocess      %s%s, %zu samples at %s us (%s MHz), %s to %s us\n",
              p["reduction"].get<std::string>().c_str(),
              p.contains("test") ? (", " + p["test"].get<std::string>() + " test").c_str() : "",
              p["samples"].get<std::size_t>(),
              g(p["sample_interval_s"].get<double>() * 1e6).c_str(),
              g(1e-6 / p["sample_interval_s"].get<double>()).c_str(),
              format_resolved(p["record_s"][0].get<double>() * 1e6,
                              p["sample_interval_s"].get<double>() * 1e6, 4)
                  .c_str(),
              format_resolved(p["record_s"][1].get<double>() * 1e6,
                              p["sample_interval_s"].get<double>() * 1e6, 4)
                  .c_str());
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

}  // namespace

void print_setup_table(const json& s) {
  std::printf("scene      %s (%s)\n", s["name"].get<std::string>().c_str(),
              s["file"].get<std::string>().c_str());
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

}  // namespace shpb
