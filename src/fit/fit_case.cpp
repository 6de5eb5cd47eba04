#include "fit/fit_case.hpp"

#include <algorithm>
#include <cmath>

#include "analysis/gauge_signals.hpp"
#include "analysis/processing.hpp"
#include "analysis/signal_checks.hpp"
#include "analysis/test_processing.hpp"
#include "core/error.hpp"
#include "core/interrupt.hpp"
#include "core/json_value.hpp"
#include "model/law_parameters.hpp"
#include "model/scene_validation.hpp"
#include "model/test_setup.hpp"
#include "solver/simulation.hpp"

namespace shpb {
namespace {

// Curve samples past this true plastic strain (the usual 0.2 % offset of a yield point): before
// it the law's A is all that matters and the elastic compliance of the set-up dominates.
constexpr double kMinPlasticStrain = 0.002;
// And only while loading at a steady rate: at least this fraction of the plateau strain rate.
constexpr double kMinRateFraction = 0.5;
// The fitted windows end this fraction of the measured pulse's length before its end. There the
// specimen has unloaded and leaves its contacts with the bars: the instants of those releases and
// of the specimen's later impacts jump with the law under asynchronous steps (and with its own
// adaptive step under either stepping), which makes the residuals there a rough function of the
// parameters. Measured on the synthetic campaign (tools/fit_noise_seeds): with the windows to the
// pulse's end + 20 % the asynchronous fit ends 0–37 % off; ending at the pulse's end, 1–18 %; 5 %
// before it, within the standard errors (docs/methods.md §9).
constexpr double kTailCut = 0.05;

// Whether the curve's sample at face time t is computed from a sample at a clipped channel's clip
// level: the incident, reflected or transmitted pulse's sample there (t less each pulse's shift to
// the faces), or its neighbour that the sub-sample shift interpolates with. Such a stress is the
// cut-off pulse's, not the specimen's.
bool reads_clipped(const MeasuredPulses& m, const ProcessingResult& pr, double t) {
  const auto& time = m.time_s;
  auto at = [&](const std::optional<ClippedSamples>& clipped, double shift) {
    if (!clipped) return false;
    const double x = (t - shift - time.front()) / m.dt_s;
    if (!(x >= 0) || x > static_cast<double>(time.size() - 1)) return false;
    const auto lo = static_cast<std::size_t>(std::floor(x));
    return clipped->at[lo] || clipped->at[std::min(lo + 1, time.size() - 1)];
  };
  return at(m.incident_clipped, pr.shift_incident_s) ||
         at(m.incident_clipped, pr.shift_reflected_s) ||
         at(m.transmitted_clipped, pr.shift_transmitted_s);
}

}  // namespace

FitCase::FitCase(const CampaignTest& test, const Campaign& campaign, const FitSpec& spec,
                 const GaugeSignals* signals_in)
    : test_(test), scene_(read_scene(test.scene)) {
  const JsonValue where(campaign.document.at("tests").at(std::stoul(test.json_path.substr(6))),
                        campaign.display, test.json_path);
  const JsonValue scene_entry(where.json().at("scene"), campaign.display,
                              json_child_path(test.json_path, "scene"));
  if (!scene_.measurement)
    throw scene_entry.error("the scene has no measurement: a fit needs measured signals");
  const TestRoles roles = test_roles(scene_);
  if (!roles.striker || !roles.incident || *roles.striker >= *roles.incident)
    throw scene_entry.error("the scene needs a striker, an incident bar and a specimen");
  const std::size_t s = *scene_.specimen, striker = *roles.striker;
  striker_ = striker;
  striker_direction_ = striker_direction(scene_);

  // The specimen becomes the law being fitted, at the test's own temperature.
  BarSpec& specimen = scene_.bars[s];
  MaterialSpec law = spec.material;
  temperature_K_ = law.johnson_cook.initial_temperature_K;
  if (law.model == MaterialModel::kJohnsonCook &&
      specimen.material.model == MaterialModel::kJohnsonCook)
    temperature_K_ = law.johnson_cook.initial_temperature_K =
        specimen.material.johnson_cook.initial_temperature_K;
  specimen.material = law;

  signals_ = signals_in ? *signals_in : read_gauge_signals(*scene_.measurement, {});
  const GaugeSignals& signals = signals_;
  for (const auto& w : signals.warnings) warnings_.push_back(test.name + ": " + w);
  MeasuredPulses found = find_measured_pulses(scene_, signals);
  for (const auto& [clipped, gauge] :
       {std::pair{&found.incident_clipped, found.setup.incident_gauge},
        std::pair{&found.transmitted_clipped, found.setup.transmitted_gauge}})
    if (*clipped)
      warnings_.push_back(
          test.name + ": gauge \"" + gauge + "\": its " +
          std::to_string(std::count_if((*clipped)->at.begin(), (*clipped)->at.end(),
                                       [](signed char a) { return a != 0; })) +
          " samples at the clip level are fitted as bounds (the strain reached at least that "
          "level), and the processed curve is not fitted where it is computed from them");

  // Nuisance starts: the striker as compare takes it, the scene's rise time, no shift.
  if (scene_.measurement->striker_velocity_m_s) {
    start_.striker_velocity_m_s = *scene_.measurement->striker_velocity_m_s;
    velocity_source_ = "scene (measurement.striker_velocity)";
  } else {
    start_.striker_velocity_m_s =
        striker_velocity_from_plateau(found.setup, found.struck_end_plateau);
    velocity_source_ = "inferred from the measured incident plateau";
  }
  scene_.bars[striker].velocity_m_s = striker_direction_ * start_.striker_velocity_m_s;
  start_.rise_time_s = interface_penalty(scene_.contact, striker).rise_time_s.value_or(0.0);
  start_.incident_wave_speed_m_s = scene_.bars[s - 1].material.wave_speed_m_s();
  start_.transmitter_wave_speed_m_s = scene_.bars[s + 1].material.wave_speed_m_s();
  const bool frees_bars =
      std::any_of(spec.nuisance.begin(), spec.nuisance.end(),
                  [](const NuisanceSpec& n) { return nuisance_is_wave_speed(n.kind); });
  // The meshes, once for every run of the fit (a mesh that changed with the parameters would make
  // the residuals jump): the scene's tolerance, else the automatic meshes — not the default
  // tolerance: measured on the synthetic classic-bar copper campaign (records simulated at the
  // automatic meshes), its meshes moved the fitted A 0.6 % and the 95 % interval off the truth
  // (docs/methods.md §1.1 "The default").
  RunOptions run_options;
  run_options.default_tolerance = false;
  resolve_scene(scene_, run_options);
  if (frees_bars && scene_.measurement->reflected_time_s)
    warnings_.push_back(test.name +
                        ": the scene's measurement.reflected_time already adds the lab's excess "
                        "travel time to the pulses; a freed wave speed adds to it (drop one)");

  // The processed curve after equilibrium, as `process` writes it.
  const ProcessingOptions options = processing_options(scene_);
  const ProcessingResult pr = process_test(scene_, signals, found.setup, options).result;
  for (const auto& w : pr.warnings) warnings_.push_back(test.name + ": " + w);
  // Processing has said a turned channel already.
  for (const auto& w : found.warnings)
    if (std::find(pr.warnings.begin(), pr.warnings.end(), w) == pr.warnings.end())
      warnings_.push_back(test.name + ": " + w);
  const Curve& c = pr.curve;
  const JohnsonCookParams& jc = law.johnson_cook;
  const bool heats = law.model == MaterialModel::kJohnsonCook && jc.adiabatic;
  double temperature = temperature_K_, previous_ep = 0;
  std::size_t last_loading = 0;
  for (std::size_t i = 0; i < c.true_strain.size(); ++i)
    if (c.true_strain[i] >= c.true_strain[last_loading]) last_loading = i;
  for (std::size_t i = 0; i < c.true_strain.size(); ++i) {
    const double stress = c.true_stress_Pa[i];
    const double ep = std::max(0.0, c.true_strain[i] - stress / law.youngs_modulus_Pa);
    // Adiabatic heating as the law integrates it: dT = β σ dε_p / (ρ c_p).
    if (heats && ep > previous_ep)
      temperature += jc.taylor_quinney * stress * (ep - previous_ep) /
                     (law.density_kg_m3 * jc.specific_heat_J_kgK);
    previous_ep = std::max(previous_ep, ep);
    // True rate ė/(1 − e) in compression, ė/(1 + e) in tension (the current length).
    const double stretch = options.tension ? 1 + c.strain[i] : 1 - c.strain[i];
    const double rate = c.strain_rate_1_s[i] / std::max(1e-9, stretch);
    // Every loading sample in equilibrium (R ≤ 5 %) counts, before the time to equilibrium too
    // (the rate and plastic-strain floors below cut the ringing front): LANL copper holds R ≤ 5 %
    // for 40 % of its loading, from 33 µs, and its fit is measured on all of them (docs/methods.md
    // §9).
    const bool equilibrium = c.equilibrium_ratio[i] <= kEquilibriumThreshold;
    if (equilibrium && i <= last_loading && ep >= kMinPlasticStrain &&
        c.strain_rate_1_s[i] >= kMinRateFraction * pr.plateau_strain_rate_1_s &&
        !reads_clipped(found, pr, pr.time_s[i]))
      curve_.push_back({pr.time_s[i], c.true_strain[i], ep, rate, temperature, stress, i});
  }
  history_ = {pr.time_s, c.true_strain, options.tension};
  // Bars that disperse (the measurement says so: "pochhammer-chree") carry each simulated pulse
  // through dispersion; "none" (e.g. signals of a 1D simulation) compares the 1D pulses as they
  // are.
  overlay_ = std::make_unique<PulseOverlay>(scene_, std::move(found),
                                            scene_.measurement->dispersion.correction);
}

double& Nuisance::operator[](NuisanceKind k) {
  switch (k) {
    case NuisanceKind::kStrikerVelocity:
      return striker_velocity_m_s;
    case NuisanceKind::kRiseTime:
      return rise_time_s;
    case NuisanceKind::kTimeShift:
      return time_shift_s;
    case NuisanceKind::kIncidentWaveSpeed:
      return incident_wave_speed_m_s;
    case NuisanceKind::kTransmitterWaveSpeed:
      return transmitter_wave_speed_m_s;
    case NuisanceKind::kTransmittedDelay:
      return transmitted_delay_s;
  }
  return striker_velocity_m_s;  // unreachable: every kind is listed
}

std::vector<CampaignTest> fit_tests(const Campaign& campaign) {
  std::vector<CampaignTest> tests = campaign.tests;
  double mean = 0;
  for (const CampaignTest& t : tests) mean += t.weight / static_cast<double>(tests.size());
  for (CampaignTest& t : tests) t.weight /= mean;
  for (std::size_t i = 0; i < tests.size(); ++i)
    for (std::size_t j = 0; j < i; ++j) {
      std::error_code ec;
      if (!std::filesystem::equivalent(tests[i].scene, tests[j].scene, ec)) continue;
      const std::size_t k = std::stoul(tests[i].json_path.substr(6));
      throw JsonValue(campaign.document.at("tests").at(k).at("scene"), campaign.display,
                      json_child_path(tests[i].json_path, "scene"))
          .error_with_value(json_quoted(tests[i].scene.string()),
                            "the scene of test \"" + tests[j].name +
                                "\" again: one record fitted as two independent tests would "
                                "count twice (give a test one entry, and a weight)");
    }
  return tests;
}

void FitCase::set_windows(const Overlay& start) {
  windows_.clear();
  fitted_windows_.clear();
  const MeasuredPulses& m = measured();
  for (const OverlaidPulse& p : start.pulses) {
    if (p.name == "incident") continue;
    windows_.push_back(p);
    const auto& w = p.name == "reflected" ? m.reflected_window : m.transmitted_window;
    OverlaidPulse f = p;
    if (w) {
      const auto cut = static_cast<std::size_t>(kTailCut * static_cast<double>(w->end - w->onset));
      f.end = std::max(p.begin + 1, std::min(p.end, w->end > cut ? w->end - cut : 0));
    }
    fitted_windows_.push_back(f);
  }
}

Overlay FitCase::simulate(const MaterialSpec& law, const Nuisance& nuisance) const {
  Scene scene = scene_;
  const std::size_t s = *scene.specimen, striker = striker_;
  const double temperature = scene.bars[s].material.johnson_cook.initial_temperature_K;
  scene.bars[s].material = law;
  scene.bars[s].material.johnson_cook.initial_temperature_K = temperature;
  scene.bars[striker].velocity_m_s = striker_direction_ * nuisance.striker_velocity_m_s;
  // A bar's wave speed at its own density: E = ρ c0² (docs/methods.md §9, "Unknowns").
  for (const auto& [bar, c0] : {std::pair{s - 1, nuisance.incident_wave_speed_m_s},
                                std::pair{s + 1, nuisance.transmitter_wave_speed_m_s}})
    if (c0 != scene.bars[bar].material.wave_speed_m_s())
      set_instantaneous_modulus(scene.bars[bar].material,
                                scene.bars[bar].material.density_kg_m3 * c0 * c0);
  if (nuisance.rise_time_s > 0 || start_.rise_time_s > 0) {
    auto it = std::find_if(scene.contact.interfaces.begin(), scene.contact.interfaces.end(),
                           [&](const InterfaceOverride& o) { return o.left_bar == striker; });
    if (it == scene.contact.interfaces.end()) {
      scene.contact.interfaces.push_back({});
      it = scene.contact.interfaces.end() - 1;
      it->left_bar = striker;
    }
    it->penalty.stiffness_factor.reset();
    it->penalty.stiffness_N_m.reset();
    it->penalty.rise_time_s = nuisance.rise_time_s;
    if (!(nuisance.rise_time_s > 0)) it->penalty.rise_time_s.reset();
  }
  SimulationOptions options;
  options.record_field = false;
  options.cancel = [] { return interrupted(); };
  const SimulationResult sim = shpb::simulate(scene, options);
  if (!sim.stable) throw NumericalError(scene.file.string() + ": " + sim.failure);
  return overlay_->overlay(scene, sim.gauges, nuisance.time_shift_s, nuisance.transmitted_delay_s);
}

namespace {

// Calls f(p, i, c, peak) for every sample i of each fitted window p, c = √(w / n_p), peak =
// max|m| over that window: the residuals' normalisation, once.
template <class F>
void each_fitted_window_sample(const std::vector<OverlaidPulse>& windows, const MeasuredPulses& m,
                               double weight, F f) {
  for (const OverlaidPulse& p : windows) {
    const auto& meas = p.transmitted ? m.transmitted : m.incident;
    double peak = 0;
    for (std::size_t i = p.begin; i < p.end; ++i) peak = std::max(peak, std::abs(meas[i]));
    const double c = std::sqrt(weight / static_cast<double>(p.end - p.begin));
    for (std::size_t i = p.begin; i < p.end; ++i) f(p, i, c, peak);
  }
}

// The same with f(sim, meas, i, c, peak): the overlay's simulated and the measured strains.
template <class F>
void each_fitted_sample(const std::vector<OverlaidPulse>& windows, const MeasuredPulses& m,
                        const Overlay& o, double weight, F f) {
  each_fitted_window_sample(windows, m, weight,
                            [&](const OverlaidPulse& p, std::size_t i, double c, double peak) {
                              f(p.transmitted ? o.transmitted : o.incident,
                                p.transmitted ? m.transmitted : m.incident, i, c, peak);
                            });
}

}  // namespace

std::vector<double> FitCase::residuals(const Overlay& o) const {
  std::vector<double> r;
  each_fitted_sample(fitted_windows_, measured(), o, test_.weight,
                     [&](const auto& sim, const auto& meas, std::size_t i, double c, double peak) {
                       r.push_back(peak > 0 ? c * residual_at(meas, i, sim[i]).value / peak : 0.0);
                     });
  return r;
}

ClippedSamples::Residual FitCase::residual_at(const std::vector<double>& meas, std::size_t i,
                                              double simulated) const {
  const MeasuredPulses& m = measured();
  const ClippedSamples* clipped = clipped_channel(m, &meas == &m.transmitted);
  return clipped ? clipped->residual(i, simulated, meas[i])
                 : ClippedSamples::Residual{simulated - meas[i], 1};
}

std::vector<double> FitCase::clock_sensitivity(const Overlay& o) const {
  const double dt = measured().dt_s;
  std::vector<double> d;
  each_fitted_sample(
      fitted_windows_, measured(), o, test_.weight,
      [&](const auto& sim, const auto& meas, std::size_t i, double c, double peak) {
        // r = c (s(t − offset) − m)/peak: ∂r/∂offset = −c ṡ/peak (central difference on the grid).
        const std::size_t lo = i > 0 ? i - 1 : i, hi = std::min(i + 1, sim.size() - 1);
        const double slope = (sim[hi] - sim[lo]) / (static_cast<double>(hi - lo) * dt);
        d.push_back(peak > 0 ? -c * residual_at(meas, i, sim[i]).slope * slope / peak : 0.0);
      });
  return d;
}

std::vector<LsCommonError> FitCase::rest_level_errors() const {
  const MeasuredPulses& m = measured();
  std::vector<LsCommonError> out;
  for (const bool transmitted : {false, true}) {
    LsCommonError e;
    e.sd = transmitted ? m.transmitted_rest_sd : m.incident_rest_sd;
    // r = c (s − (x − level))/peak: ∂r/∂level = c/peak on that record's windows, 0 elsewhere.
    each_fitted_window_sample(
        fitted_windows_, m, test_.weight,
        [&](const OverlaidPulse& p, std::size_t, double c, double peak) {
          e.sensitivity.push_back(p.transmitted == transmitted && peak > 0 ? c / peak : 0.0);
        });
    out.push_back(std::move(e));
  }
  return out;
}

std::vector<double> FitCase::misfit_over_noise(const Overlay& o) const {
  const MeasuredPulses& m = measured();
  std::vector<double> out;
  for (const OverlaidPulse& p : fitted_windows_) {
    const auto& meas = p.transmitted ? m.transmitted : m.incident;
    const auto& sim = p.transmitted ? o.transmitted : o.incident;
    const ClippedSamples* clipped = clipped_channel(m, p.transmitted);
    double sum = 0;
    std::size_t n = 0;
    for (std::size_t i = p.begin; i < p.end; ++i)
      if (!clipped || clipped->at[i] == 0) sum += (sim[i] - meas[i]) * (sim[i] - meas[i]), ++n;
    const double noise = (p.transmitted ? m.transmitted_baseline : m.incident_baseline).noise;
    out.push_back(n > 0 && noise > 0 ? std::sqrt(sum / static_cast<double>(n)) / noise : 0.0);
  }
  return out;
}

std::vector<double> FitCase::residual_scales() const {
  std::vector<double> s;
  for (const OverlaidPulse& p : fitted_windows_)
    s.insert(s.end(), p.end - p.begin,
             std::sqrt(test_.weight / static_cast<double>(p.end - p.begin)));
  return s;
}

std::vector<PulseComparison> FitCase::compare(const Overlay& o) const {
  const MeasuredPulses& m = measured();
  std::vector<PulseComparison> out;
  for (const OverlaidPulse& p : windows_) {
    PulseComparison c = compare_pulse(p.transmitted ? m.transmitted : m.incident,
                                      p.transmitted ? o.transmitted : o.incident, m.dt_s, p.begin,
                                      p.end, clipped_channel(m, p.transmitted));
    c.gauge = p.gauge, c.pulse = p.name;
    out.push_back(c);
  }
  return out;
}

}  // namespace shpb
