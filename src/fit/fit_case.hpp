#pragma once
// One test of a fit campaign, prepared once: its scene with the law being fitted as the specimen
// (at the test's own temperature), its measured pulses, its processed curve after equilibrium,
// and the compared windows. Then, for given law and nuisance values: one simulation laid over the
// measurement as `compare` does (analysis/pulse_overlay.hpp), and its residuals.
#include <memory>
#include <string>
#include <vector>

#include "analysis/comparison.hpp"
#include "analysis/gauge_signals.hpp"
#include "analysis/pulse_overlay.hpp"
#include "fit/least_squares.hpp"
#include "model/campaign.hpp"
#include "model/fit_spec.hpp"
#include "model/scene.hpp"

namespace shpb {

// A processed sample after equilibrium: what the law must reproduce in the curve stage.
struct CurvePoint {
  double time_s = 0;
  double true_strain = 0, plastic_strain = 0;  // ε_p = ε − σ/E
  double strain_rate_1_s = 0;                  // true strain rate
  double temperature_K = 0;  // test temperature + adiabatic rise (if the law says)
  double stress_Pa = 0;      // true stress (3-wave)
  std::size_t sample = 0;    // its index in the processed history (FitCase::history())
};

// The whole processed test from its start (a curve point's history): what a law without a flow
// stress is driven along (model/law_parameters.hpp law_stress_along).
struct ProcessedHistory {
  std::vector<double> time_s, true_strain;
  bool tension = false;
};

// A test's nuisance values. The wave speeds start at the scene's bars' c0, the rest as FitCase
// says; every kind of NuisanceKind has its member.
struct Nuisance {
  double striker_velocity_m_s = 0;
  double rise_time_s = 0;
  double time_shift_s = 0;
  double incident_wave_speed_m_s = 0, transmitter_wave_speed_m_s = 0;
  double transmitted_delay_s = 0;  // the transmitted channel's record later than the incident's
  double& operator[](NuisanceKind k);
  double operator[](NuisanceKind k) const { return const_cast<Nuisance&>(*this)[k]; }
};

// The campaign's tests as a fit counts them. Weights are relative: divided by their mean, so the
// fitted law and its convergence do not depend on their scale (1 and 1e-10 fit alike). A scene
// listed twice is refused (InputError naming the second entry): one record fitted as two
// independent tests would count twice and shrink the standard errors by √2.
std::vector<CampaignTest> fit_tests(const Campaign& campaign);

class FitCase {
 public:
  // Reads the scene and its measurement (InputError names the scene or the campaign entry).
  // `signals`, when given, stand for the measured record (a bootstrap draw, fit/fit_bootstrap.hpp).
  FitCase(const CampaignTest& test, const Campaign& campaign, const FitSpec& spec,
          const GaugeSignals* signals = nullptr);

  const std::string& name() const { return test_.name; }
  double weight() const { return test_.weight; }
  const Scene& scene() const { return scene_; }
  const MeasuredPulses& measured() const { return overlay_->measured(); }
  const Nuisance& start() const { return start_; }
  const std::string& velocity_source() const { return velocity_source_; }
  double temperature_K() const { return temperature_K_; }
  const std::vector<CurvePoint>& curve() const { return curve_; }
  const ProcessedHistory& history() const { return history_; }
  const std::vector<std::string>& warnings() const { return warnings_; }
  // The measured record as read (time base and every gauge's strain).
  const GaugeSignals& signals() const { return signals_; }

  // The windows compared (reflected, transmitted: compare's, the measured pulse ±20 %), fixed from
  // the simulation at the start so that every evaluation has the same residuals; the fitted
  // windows are the same, ending kTailCut of the pulse's length before the measured pulse ends
  // (docs/methods.md §9, "Smooth residuals").
  void set_windows(const Overlay& start);
  const std::vector<OverlaidPulse>& windows() const { return windows_; }
  const std::vector<OverlaidPulse>& fitted_windows() const { return fitted_windows_; }

  // One simulation with `law` as the specimen and the nuisance values. NumericalError if unstable.
  Overlay simulate(const MaterialSpec& law, const Nuisance& nuisance) const;
  // √(w / n_p) (s − m) / max|m| over each fitted window: Σ r² = w Σ_pulses NRMSE².
  // A sample of a clipped channel at its clip level says only that the strain reached it: its
  // residual is the censored one (ClippedSamples, analysis/signal_checks.hpp; Tobit 1958).
  std::vector<double> residuals(const Overlay& o) const;
  ClippedSamples::Residual residual_at(const std::vector<double>& measured_strain, std::size_t i,
                                       double simulated) const;
  std::vector<double> residual_scales() const;  // √(w / n_p) per residual
  // ∂r/∂t of the residuals in the clock offset (the simulation later by t), from the compared
  // simulated pulses' slopes; and the measured clock's standard deviation from the record noise.
  std::vector<double> clock_sensitivity(const Overlay& o) const;
  double clock_sd_s() const { return measured().incident_front_sd_s; }
  // The incident and transmitted records' rest-level errors over the fitted residuals.
  std::vector<LsCommonError> rest_level_errors() const;
  // compare's figures per window (NRMSE, ratios) for the overlay.
  std::vector<PulseComparison> compare(const Overlay& o) const;
  // Per fitted window: the RMS of simulated − measured strain over its record's noise (the
  // baseline's), samples at a clip level left out; about 1 where the law reproduces the pulse
  // within the noise, 0 for a record without noise.
  std::vector<double> misfit_over_noise(const Overlay& o) const;

 private:
  CampaignTest test_;
  Scene scene_;
  std::unique_ptr<PulseOverlay> overlay_;
  std::size_t striker_ = 0;
  double striker_direction_ = 1;  // +1 launched to the right, −1 pulled left (tension)
  Nuisance start_;                // the striker velocity a speed, launched in striker_direction_
  std::string velocity_source_;
  double temperature_K_ = 0;
  std::vector<CurvePoint> curve_;
  ProcessedHistory history_;
  std::vector<OverlaidPulse> windows_, fitted_windows_;
  std::vector<std::string> warnings_;
  GaugeSignals signals_;
};

}  // namespace shpb
