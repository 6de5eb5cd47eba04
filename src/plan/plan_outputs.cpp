#include "plan/plan_outputs.hpp"

#include <algorithm>
#include <cmath>

#include "analysis/gauge_signals.hpp"
#include "analysis/reduction.hpp"
#include "core/checked_write.hpp"
#include "core/csv_writer.hpp"
#include "model/scene_writer.hpp"
#include "output_schema.hpp"
#include "version.hpp"

namespace shpb {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

// A value in SI units as the scene reader reads it back bit for bit (the shortest text that
// round-trips), so that `simulate DIR/scene.json` runs the verified set-up itself: rounded to four
// digits, a 156.25 mm striker became 156.2 mm, was meshed otherwise and missed equilibrium.
std::string si_text(double si, const char* unit) { return format_double(si) + " " + unit; }

// A material given as a path relative to the scene, relative to the output folder instead.
void rebase_material(nlohmann::json& bar, const nlohmann::json& scene, const fs::path& from,
                     const fs::path& to) {
  if (!bar.contains("material") || !bar["material"].is_string()) return;
  const std::string s = bar["material"];
  if (scene.contains("materials") && scene["materials"].contains(s)) return;
  bar["material"] = rebased_path(s, from, to);
}

// The scene file as given with the plan's values, ready for `simulate` from the output folder.
nlohmann::json planned_json(const PlanResult& r, const PlanInput& in, const fs::path& final_dir) {
  nlohmann::json j = in.json;
  j.erase("plan");
  j.erase("measurement");  // the record of a shot not yet fired
  const fs::path from = in.scene.file.parent_path();
  if (j.contains("calibration"))
    j["calibration"] = rebased_path(j["calibration"].get<std::string>(), from, final_dir);
  auto& bars = j["bars"];
  const PlanCandidate& c = r.chosen;
  bars[0]["length"] = si_text(c.striker_length_m, "m");
  bars[0]["velocity"] = si_text(c.striker_velocity_m_s, "m/s");
  if (c.shaper >= 0) {
    nlohmann::json shaper = {{"name", "shaper"}};
    if (in.spec.scene_has_shaper) shaper = bars[1];
    const auto& text = in.spec.shaper_materials[c.shaper].text;
    if (!text.empty()) shaper["material"] = text;
    shaper["length"] = si_text(c.shaper_thickness_m, "m");
    shaper.erase("area");
    shaper["diameter"] = si_text(c.shaper_diameter_m, "m");
    if (in.spec.scene_has_shaper)
      bars[1] = shaper;
    else
      bars.insert(bars.begin() + 1, shaper);
  }
  if (in.spec.specimen_length)
    for (auto& b : bars)
      if (b["name"] == in.scene.bars[*in.scene.specimen].name)
        b["length"] = si_text(c.specimen_length_m, "m");
  for (auto& b : bars) rebase_material(b, in.json, from, final_dir);
  // A duration the planned pulse outlasts, extended as the verification run was (planned_scene).
  const auto& given = in.scene.simulation.duration_s;
  if (given && r.scene.simulation.duration_s && *r.scene.simulation.duration_s > *given)
    j["simulation"]["duration"] = si_text(*r.scene.simulation.duration_s, "s");
  return j;
}

// The smallest value of the 1–2–5 series at least x.
double series_125(double x) {
  const double decade = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * decade >= x * (1 - 1e-12)) return m * decade;
  return 10 * decade;
}

// The bridge of `gauge`'s channel in the scene's measurement, or a quarter bridge with the
// scene format's defaults (docs/scene-format.md#measurement).
BridgeSpec bridge_of(const Scene& s, const std::string& gauge, bool* given) {
  *given = false;
  if (s.measurement)
    for (const auto& ch : s.measurement->channels)
      if (ch.gauge == gauge && ch.bridge) {
        *given = true;
        return *ch.bridge;
      }
  return BridgeSpec{};
}

// Scope settings from the predicted signals (docs/commands.md#plan): the range holds the peak
// with headroom, the incident rise spans kSamplesPerRise samples, the record holds the pulses
// from the trigger to the transmitted pulse's end twice over, the trigger fires at a tenth of the
// incident peak.
Json scope_settings(const PlanResult& r, const Scene& original, Json& gauges) {
  constexpr double kRangeHeadroom = 1.25;  // clipping costs the test: a quarter above the peak
  constexpr double kSamplesPerRise = 20;   // a rise resolved well enough to time it
  constexpr double kTriggerFraction = 0.1;
  constexpr double kPretrigger = 0.2;      // of the record, for the baseline
  constexpr double kRecordHeadroom = 2.0;  // for a slower pulse than predicted
  const TimeSeries& g = r.verified.gauges;
  const std::string incident = r.scene.bars[*r.scene.incident_bar()].gauges.at(0).name;
  const std::string transmitted = r.scene.bars[*r.scene.transmitter_bar()].gauges.at(0).name;
  double range = 0, trigger = 0, rise = 0, t_trigger = 0, t_end = 0;
  for (std::size_t c = 0; c < g.columns.size(); ++c) {
    const auto& x = g.values[c];
    bool given = false;
    const BridgeSpec bridge = bridge_of(original, g.columns[c], &given);
    const double volts = 1 / volts_to_strain(bridge);
    std::size_t kp = 0;
    for (std::size_t k = 0; k < x.size(); ++k)
      if (std::abs(x[k]) > std::abs(x[kp])) kp = k;
    const double peak = x.empty() ? 0 : x[kp];
    gauges.push_back(
        {{"gauge", g.columns[c]},
         {"peak_strain", peak},
         {"peak_V", peak * volts},
         {"bridge", given ? "the scene's" : "quarter bridge, factor 2, 10 V, gain 1"}});
    range = std::max(range, std::abs(peak * volts));
    if (peak == 0) continue;
    std::size_t k10 = 0, k90 = 0;
    while (k10 < kp && std::abs(x[k10]) < 0.1 * std::abs(peak)) ++k10;
    while (k90 < kp && std::abs(x[k90]) < 0.9 * std::abs(peak)) ++k90;
    if (g.columns[c] == incident) {
      rise = g.time_s[k90] - g.time_s[k10];
      trigger = kTriggerFraction * peak * volts;
      t_trigger = g.time_s[k10];
    }
    if (g.columns[c] == transmitted) {
      std::size_t k = x.size() - 1;
      while (k > kp && std::abs(x[k]) < 0.1 * std::abs(peak)) --k;
      t_end = g.time_s[k];
    }
  }
  const double rate = series_125(std::max(1e6, kSamplesPerRise / std::max(rise, 1e-9)));
  const double record = series_125(kRecordHeadroom * std::max(t_end - t_trigger, 1e-6));
  return {{"range_V", series_125(kRangeHeadroom * std::max(range, 1e-6))},
          {"sample_rate_Hz", rate},
          {"record_length_s", record},
          {"record_samples", std::ceil(record * rate)},
          {"pretrigger_s", kPretrigger * record},
          {"trigger_channel", incident},
          {"trigger_level_V", trigger},
          {"trigger_slope", trigger < 0 ? "falling" : "rising"},
          {"incident_rise_s", rise}};
}

Json candidate_json(const PlanCandidate& c, const PlanInput& in) {
  Json j = {{"striker_length_m", c.striker_length_m},
            {"striker_velocity_m_s", c.striker_velocity_m_s},
            {"shaper", nullptr},
            {"specimen_length_m", c.specimen_length_m}};
  if (c.shaper >= 0) {
    const auto& text = in.spec.shaper_materials[c.shaper].text;
    j["shaper"] = {{"material", text.empty() ? in.scene.bars[1].name : text},
                   {"thickness_m", c.shaper_thickness_m},
                   {"diameter_m", c.shaper_diameter_m}};
  }
  return j;
}

}  // namespace

std::vector<std::string> plan_warnings(const PlanResult& r, const PlanTargets& targets) {
  // The criteria put the median rate over the loading (to the strain maximum) on the target;
  // `process` quotes the mean over the same loading, which a rate without a plateau (one that
  // falls as a hardening specimen's stress rises, rate ≈ (v − 2c ε_T)/L_s) pulls away from it.
  std::vector<std::string> w;
  const LoadingMetrics& m = r.metrics;
  const double R = targets.rate_1_s;
  if (std::abs(m.test_mean_rate_1_s - R) <= kRateBand * R) return w;
  const BarSpec& striker = r.scene.bars[0];
  char line[600];
  std::snprintf(line, sizeof line,
                "the pulse loads the specimen on to strain %.3g (target %.3g): over the whole "
                "loading, to the strain maximum, its rate averages %.4g 1/s (%+.0f %% of the "
                "target), the mean `process` will quote, while its median is %.4g 1/s",
                m.strain_reached, targets.strain, m.test_mean_rate_1_s,
                100 * (m.test_mean_rate_1_s / R - 1), m.plateau_rate_1_s);
  std::string text = line;
  const double needed = striker_length_for(targets.strain, R, striker.material.wave_speed_m_s());
  if (m.strain_reached > kStrainOvershoot * targets.strain && needed < striker.length_m) {
    std::snprintf(line, sizeof line,
                  "; a shorter striker (about %.3g m: 2L/c = strain/rate, plan.striker.length) "
                  "ends the loading nearer the target strain",
                  needed);
    text += line;
  }
  w.push_back(text);
  return w;
}

namespace {

Json predicted_json(const LoadingMetrics& m) {
  return {{"plateau_rate_1_s", m.plateau_rate_1_s},
          {"band_fraction", m.band_fraction},
          {"rate_spread", m.rate_spread},
          {"loading_start_s", m.onset_s},
          {"loading_end_s", m.end_s},
          {"equilibrium_s", m.equilibrium_s},
          {"equilibrium_fraction", m.equilibrium_fraction},
          {"strain_reached", m.strain_reached},
          {"test_mean_rate_1_s", m.test_mean_rate_1_s}};
}

}  // namespace

void write_plan_outputs(const PlanResult& r, const PlanInput& in, const PlanTargets& targets,
                        const PlanOptions& options, const std::string& scene_shown,
                        const fs::path& dir, const fs::path& final_dir) {
  write_text_file(dir / "scene.json", planned_json(r, in, final_dir).dump(2) + "\n");
  const Scene& s = in.scene;
  PlanCandidate given{
      s.bars[0].length_m,          s.bars[0].velocity_m_s, in.spec.scene_has_shaper ? 0 : -1, 0, 0,
      s.bars[*s.specimen].length_m};
  if (in.spec.scene_has_shaper) {
    given.shaper_thickness_m = s.bars[1].length_m;
    given.shaper_diameter_m = s.bars[1].diameter_m;
  }
  const LoadingMetrics& m = r.metrics;
  Json gauges = Json::array();
  Json scope = scope_settings(r, s, gauges);
  Json j = {
      {"version", kVersion},
      {"command", "plan"},
      {"scene", scene_shown},
      {"targets",
       {{"strain_rate_1_s", targets.rate_1_s},
        {"strain", targets.strain},
        {"rate_band", kRateBand},
        {"band_fraction_min", kBandFraction},
        {"equilibrium_ratio_max", kEquilibriumRatio},
        {"equilibrium_before_fraction", kEquilibriumFraction}}},
      {"feasible", r.feasible},
      {"changes", r.changes},
      {"chosen", candidate_json(r.chosen, in)},
      {"scene_values", candidate_json(given, in)},
      {"predicted", predicted_json(m)},
      {"warnings", plan_warnings(r, targets)},
      {"unshaped", nullptr},
      {"shaped", nullptr},
      {"gauges", gauges},
      {"scope", scope},
      {"search",
       {{"method", "velocity by secant per geometry; grid of geometries, then compass search"},
        {"search_tolerance", options.search_tolerance},
        {"verify_tolerance", options.verify_tolerance},
        {"candidates", r.path.size()},
        {"simulations", r.simulations},
        {"wall_time_s", r.wall_time_s}}}};
  for (const auto& [key, side] : {std::pair{"unshaped", &r.unshaped}, {"shaped", &r.shaped}})
    if (*side)
      j[key] = {{"chosen", candidate_json((*side)->candidate, in)},
                {"meets", (*side)->meets},
                {"changes", (*side)->changes},
                {"predicted", predicted_json((*side)->metrics)}};
  write_text_file(dir / "summary.json", j.dump(2) + "\n");
  namespace k = schema::plan_path;  // the column names (src/core/output_schema.json)
  CsvWriter path(dir / k::kFile, {k::step, k::striker_length_m, k::striker_velocity_m_s, k::shaper,
                                  k::shaper_thickness_m, k::shaper_diameter_m, k::specimen_length_m,
                                  k::plateau_rate_1_s, k::band_fraction, k::equilibrium_fraction,
                                  k::strain_reached, k::changes, k::meets});
  for (std::size_t i = 0; i < r.path.size(); ++i) {
    const auto& p = r.path[i];
    const auto& c = p.candidate;
    path.row({double(i), c.striker_length_m, c.striker_velocity_m_s, double(c.shaper),
              c.shaper_thickness_m, c.shaper_diameter_m, c.specimen_length_m,
              p.metrics.plateau_rate_1_s, p.metrics.band_fraction, p.metrics.equilibrium_fraction,
              p.metrics.strain_reached, double(p.changes), double(p.meets)});
  }
  path.close();
  namespace l = schema::plan_loading;
  const FaceForces f = face_forces(r.verified, r.scene);
  const std::vector<double> ratio = equilibrium_ratio(f.front, f.back);  // process's R (§6)
  const TimeSeries& sp = r.verified.specimen;
  const auto& strain = sp.column("strain");
  const auto& rate = sp.column("strain_rate_1_s");
  CsvWriter loading(dir / l::kFile, {l::time_s, l::strain, l::strain_rate_1_s, l::front_force_N,
                                     l::back_force_N, l::equilibrium_ratio, l::loading});
  for (std::size_t k = 0; k < sp.time_s.size(); ++k) {
    const double t = sp.time_s[k];
    loading.row({t, strain[k], rate[k], f.front[k], f.back[k], ratio[k],
                 double(t >= m.onset_s && t <= m.end_s && m.end_s > m.onset_s)});
  }
  loading.close();
  fs::create_directories(dir / "simulation");
  write_simulation_outputs(r.verified, r.scene, dir / "simulation");
}

}  // namespace shpb
