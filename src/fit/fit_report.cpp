#include "fit/fit_report.hpp"

#include <algorithm>

#include "core/checked_write.hpp"
#include "core/csv_writer.hpp"
#include "model/calibration.hpp"
#include "model/law_parameters.hpp"
#include "output_schema.hpp"
#include "version.hpp"

namespace shpb {
namespace {

// A stage in summary.json (docs/outputs.md), with its values and Jacobian step check by name.
nlohmann::json stage_json(const FitRun& run, const FitStageReport& st) {
  nlohmann::json j = {{"stage", to_string(st.stage)},
                      {"cost_start", st.result.cost_start},
                      {"cost", st.result.cost},
                      {"residuals", st.result.residuals},
                      {"iterations", st.result.iterations},
                      {"evaluations", st.result.evaluations},
                      {"simulations", st.simulations},
                      {"wall_time_s", st.wall_time_s},
                      {"cpu_time_s", st.cpu_time_s},
                      {"converged", st.result.converged},
                      {"termination", st.result.termination}};
  if (st.stage == FitStage::kSignals) {
    j["simulations_per_second"] = st.wall_time_s > 0 ? st.simulations / st.wall_time_s : 0.0;
    j["simulations_per_cpu_second"] = st.cpu_time_s > 0 ? st.simulations / st.cpu_time_s : 0.0;
  }
  nlohmann::json values = nlohmann::json::object(), check = nlohmann::json::object();
  for (std::size_t a = 0; a < st.unknowns.size(); ++a) {
    values[run.unknowns[st.unknowns[a]].name] = st.result.value[a];
    if (a < st.result.step_check.size())
      check[run.unknowns[st.unknowns[a]].name] = st.result.step_check[a];
  }
  j["values"] = values;
  j["jacobian_step_check"] = check;
  return j;
}

nlohmann::json parameters_json(const FitRun& run) {
  const FitStageReport* last = run.stages.empty() ? nullptr : &run.stages.back();
  nlohmann::json parameters = nlohmann::json::object();
  for (std::size_t i = 0; i < run.unknowns.size(); ++i) {
    const FitUnknown& u = run.unknowns[i];
    nlohmann::json p = {{"value", run.current[i]},
                        {"start", u.start},
                        {"bounds", {u.lower, u.upper}},
                        {"unit", std::string(si_unit(u.dimension))},
                        {"std_error", nullptr}};
    if (last)
      for (std::size_t j = 0; j < last->unknowns.size(); ++j)
        if (last->unknowns[j] == i && !last->result.std_error.empty())
          p["std_error"] = last->result.std_error[j];
    if (u.law < run.spec.free.size() && u.test < 0 && !run.after_curve.empty())
      p["after_curve"] = run.after_curve[u.law];
    if (i < run.intervals.size()) {
      const ParameterInterval& iv = run.intervals[i];
      p["interval_95"] = iv.known ? nlohmann::json{iv.lower, iv.upper} : nlohmann::json(nullptr);
      p["interval_method"] = iv.known ? nlohmann::json(iv.method) : nlohmann::json(nullptr);
      p["weakly_identified"] = iv.weak;
      if (iv.weak) p["weakly_identified_why"] = iv.weak_reason;
      if (iv.has_linear) p["linearised_interval_95"] = {iv.linear_lower, iv.linear_upper};
      if (iv.has_bootstrap)
        p["bootstrap"] = {{"std_dev", iv.bootstrap_sd},
                          {"bias", iv.bootstrap_bias},
                          {"interval_95", {iv.bootstrap_lower, iv.bootstrap_upper}},
                          {"at_bound", iv.at_bound}};
    }
    parameters[u.name] = p;
  }
  return parameters;
}

nlohmann::json correlation_json(const FitRun& run) {
  const FitStageReport* last = run.stages.empty() ? nullptr : &run.stages.back();
  std::vector<std::string> order;
  nlohmann::json corr = nlohmann::json::array();
  if (last && !last->result.std_error.empty()) {
    for (std::size_t a = 0; a < last->unknowns.size(); ++a) {
      order.push_back(run.unknowns[last->unknowns[a]].name);
      nlohmann::json row = nlohmann::json::array();
      for (std::size_t b = 0; b < last->unknowns.size(); ++b)
        row.push_back(last->result.correlation(static_cast<long>(a), static_cast<long>(b)));
      corr.push_back(row);
    }
  }
  return {{"parameters", order}, {"matrix", corr}};
}

nlohmann::json tests_json(const FitRun& run) {
  nlohmann::json tests = nlohmann::json::array();
  for (std::size_t k = 0; k < run.cases.size(); ++k) {
    const FitCase& c = *run.cases[k];
    nlohmann::json t = {{"name", c.name()},
                        {"scene", c.scene().file.string()},
                        {"calibration", calibration_summary(c.scene())},
                        {"weight", c.weight()},
                        {"temperature_K", c.temperature_K()},
                        {"striker_velocity_source", c.velocity_source()},
                        {"curve_points", c.curve().size()}};
    if (!c.curve().empty()) {
      std::vector<double> rates;
      for (const auto& p : c.curve()) rates.push_back(p.strain_rate_1_s);
      std::sort(rates.begin(), rates.end());
      t["strain_rate_1_s"] = rates[rates.size() / 2];
    }
    // The fitted travel from the incident gauge to the specimen and back, as the overlay lays the
    // reflected pulse: 2d/c_I plus the lab's excess (measurement.reflected_time), if any.
    const KolskySetup& setup = c.measured().setup;
    const double d = setup.incident_distance_m;
    t["round_trip_s"] = 2 * d / run.nuisance_of(k, run.current).incident_wave_speed_m_s +
                        2 * d * setup.excess_delay_s_per_m;
    const auto cb = c.compare(run.before[k]), ca = c.compare(run.after[k]);
    for (std::size_t i = 0; i < cb.size(); ++i) {
      t["nrmse_" + cb[i].pulse + "_before"] = cb[i].nrmse;
      t["nrmse_" + cb[i].pulse + "_after"] = ca[i].nrmse;
    }
    const std::vector<double> misfit = c.misfit_over_noise(run.after[k]);
    for (std::size_t j = 0; j < misfit.size(); ++j)
      t["misfit_over_noise_" + c.fitted_windows()[j].name] = misfit[j];
    tests.push_back(t);
  }
  return tests;
}

}  // namespace

nlohmann::json fit_material(const FitRun& run) {
  const FitSpec& spec = run.spec;
  nlohmann::json material = spec.material_document;
  const auto final_law = run.law_values(run.current);
  for (std::size_t i = 0; i < spec.free.size(); ++i)
    set_law_parameter(material, spec.free[i].name, final_law[i]);
  std::string tests;
  for (const auto& c : run.cases) tests += (tests.empty() ? "" : ", ") + c->name();
  std::string stage_names;
  for (const auto& s : run.stages)
    stage_names += (stage_names.empty() ? "" : " then ") + to_string(s.stage);
  material["source"] = "shpb " + std::string(kVersion) + " fit of campaign " +
                       run.campaign.display + " (tests: " + tests + "; stages: " + stage_names +
                       "), started from " + spec.material_display +
                       (spec.material.source.empty() ? "" : " (" + spec.material.source + ")");
  if (material.contains("name"))
    material["name"] = material["name"].get<std::string>() + " (fitted)";
  // Each fitted parameter's 95 % interval, as summary.json gives it (fit/fit_bootstrap.hpp).
  nlohmann::json uncertainty = nlohmann::json::object();
  for (std::size_t i = 0; i < spec.free.size() && i < run.intervals.size(); ++i) {
    const ParameterInterval& iv = run.intervals[i];
    if (!iv.known) continue;
    uncertainty[spec.free[i].name] = {{"interval_95", {iv.lower, iv.upper}},
                                      {"method", iv.method},
                                      {"weakly_identified", iv.weak}};
  }
  if (!uncertainty.empty()) material["uncertainty"] = uncertainty;
  return material;
}

nlohmann::json fit_summary(const FitRun& run) {
  nlohmann::json s;
  s["campaign"] = run.campaign.display;
  s["material"] = run.spec.material_display;
  s["model"] = std::string(to_string(run.spec.material.model));
  s["loss"] = to_string(run.spec.loss);
  s["threads"] = run.threads;
  s["relative_step"] = run.relative_step;
  s["parameters"] = parameters_json(run);
  s["correlation"] = correlation_json(run);
  // Null when no refit was drawn (--bootstrap 0): no seed was used.
  s["bootstrap"] = nullptr;
  if (run.bootstrap.draws > 0)
    s["bootstrap"] = {{"refits", run.bootstrap.draws},
                      {"finished", run.bootstrap.estimates.size()},
                      {"failed", run.bootstrap.failed},
                      {"seed", run.bootstrap.seed},
                      {"simulations", run.bootstrap.simulations},
                      {"wall_time_s", run.bootstrap.wall_time_s}};
  nlohmann::json stages = nlohmann::json::array();
  double signals_time = 0, signals_cpu = 0;
  long signal_simulations = 0, evaluations = 0;
  for (const auto& st : run.stages) {
    stages.push_back(stage_json(run, st));
    if (st.stage == FitStage::kSignals) {
      signals_time += st.wall_time_s, signals_cpu += st.cpu_time_s;
      signal_simulations += st.simulations;
    }
    evaluations += st.result.evaluations;
  }
  s["stages"] = stages;
  s["tests"] = tests_json(run);
  s["evaluations"] = evaluations;
  s["simulations"] = run.simulations;
  s["simulations_per_second"] = signals_time > 0 ? signal_simulations / signals_time : 0.0;
  s["simulations_per_cpu_second"] = signals_cpu > 0 ? signal_simulations / signals_cpu : 0.0;
  s["wall_time_s"] = seconds_since(run.started);
  s["cpu_time_s"] = cpu_seconds();
  s["warnings"] = run.warnings;
  s["version"] = kVersion;
  return s;
}

void write_fit_curves(const FitRun& run, const std::filesystem::path& file) {
  const MaterialSpec law0 = run.spec.material,
                     law1 = run.after_curve.empty() ? law0 : run.law_with(run.after_curve),
                     law2 = run.law_with(run.law_values(run.current));
  namespace k = schema::fit_curves;  // the column names (src/core/output_schema.json)
  CsvWriter w(file, {k::test, k::time_s, k::true_strain, k::true_plastic_strain, k::strain_rate_1_s,
                     k::temperature_K, k::stress_measured_Pa, k::stress_start_Pa,
                     k::stress_curve_Pa, k::stress_fitted_Pa});
  for (const auto& c : run.cases) {
    // A law's flow stress at each point; a law without one (viscoelastic) carries the stress of
    // its response to the test's processed strain history, driven from the test's start.
    const ProcessedHistory& h = c->history();
    const auto law_stress = [&](const MaterialSpec& m) {
      std::vector<double> along;
      std::vector<double> out;
      for (const CurvePoint& p : c->curve()) {
        const auto flow = law_flow_stress(m, p.plastic_strain, p.strain_rate_1_s, p.temperature_K);
        if (!flow && along.empty()) along = law_stress_along(m, h.time_s, h.true_strain, h.tension);
        out.push_back(flow ? *flow : along[p.sample]);
      }
      return out;
    };
    const std::vector<double> s0 = law_stress(law0), s1 = law_stress(law1), s2 = law_stress(law2);
    for (std::size_t i = 0; i < c->curve().size(); ++i) {
      const CurvePoint& p = c->curve()[i];
      const std::vector<double> v = {p.time_s,
                                     p.true_strain,
                                     p.plastic_strain,
                                     p.strain_rate_1_s,
                                     p.temperature_K,
                                     p.stress_Pa,
                                     s0[i],
                                     s1[i],
                                     s2[i]};
      w.row(c->name(), 1, v);
    }
  }
  w.close();
}

void write_fit_signals(const FitRun& run, const std::filesystem::path& file) {
  namespace k = schema::fit_signals;
  CsvWriter w(file, {k::test, k::gauge, k::pulse, k::time_s, k::measured_strain, k::start_strain,
                     k::fitted_strain});
  for (std::size_t k = 0; k < run.cases.size(); ++k) {
    const auto& m = run.cases[k]->measured();
    for (const auto& p : run.cases[k]->windows()) {
      const auto& meas = p.transmitted ? m.transmitted : m.incident;
      const auto& b = p.transmitted ? run.before[k].transmitted : run.before[k].incident;
      const auto& a = p.transmitted ? run.after[k].transmitted : run.after[k].incident;
      const std::string key = run.cases[k]->name() + "," + p.gauge + "," + p.name;
      for (std::size_t i = p.begin; i < p.end; ++i) {
        const std::vector<double> v = {m.time_s[i], meas[i], b[i], a[i]};
        w.row(key, 3, v);
      }
    }
  }
  w.close();
}

void write_fit_outputs(const FitRun& run, const std::filesystem::path& dir) {
  write_text_file(dir / "fit.json", fit_material(run).dump(2) + "\n");
  const nlohmann::json summary = fit_summary(run);
  write_fit_curves(run, dir / schema::fit_curves::kFile);
  write_fit_signals(run, dir / schema::fit_signals::kFile);
  write_text_file(dir / "summary.json", summary.dump(2) + "\n");
}

}  // namespace shpb
