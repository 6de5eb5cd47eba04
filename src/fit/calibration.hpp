#pragma once
// `shpb calibrate`: the bars measured from a lab's calibration shots (docs/methods.md §11). Each
// shot is an ordinary scene without a specimen and with a measurement:
//  - bars apart: one bar gauged, its far end free. The first pulse at the first gauge is the
//    source; the record holds it again after reflections at the far end (−, 2(L − x)) and at the
//    struck end (+, 2L), each dispersed over its way (Pochhammer–Chree, dispersion/propagation).
//  - bars together: the incident bar in contact with the transmitter bar. The source pulse crosses
//    the interface, passes the transmitter's gauges and comes back from its free far end.
// The model of every later pulse is the source moved along its way bar by bar, times the channel's
// gain, delayed by the channel's delay; the unknowns (each gauged bar's wave speed and Poisson
// ratio, each gauge's position, each other channel's gain and delay relative to the source's) are
// fitted by least squares (fit/least_squares.hpp, Ceres). Standard uncertainties come from the
// Jacobian J at the optimum, s² (JᵀJ)⁻¹ with s² = Σr²/(N' − P), N' the low-passed residuals'
// independent count (each record is low-passed as its model is); directions of J whose singular
// value (columns scaled to unit norm) is below kWeakDirection of the largest are what the shots
// cannot determine: they are named and their parameters get no uncertainty.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "model/calibration.hpp"
#include "model/scene.hpp"

namespace shpb {

// A direction of the scaled Jacobian this much weaker than the strongest is not determined: a
// parameter moved along it changes the residuals 1000 × less than the best-determined combination,
// i.e. within the noise of any real record.
inline constexpr double kWeakDirection = 1e-3;

// Bounds of the fitted values around the nominal: a wave speed or a gauge position beyond them is a
// wrong scene (another bar, another gauge), not a calibration.
inline constexpr double kWaveSpeedRange = 0.1;  // ±10 %
inline constexpr double kMaxChannelDelay_s = 20e-6;

struct CalibrationShot {
  Scene scene;
  std::string display;  // the scene as named on the command line
};

struct CalibrateOptions {
  int threads = 0;
  int max_iterations = 60;
  std::function<void(const std::string&)> progress;
};

struct FittedParameter {
  std::string name;  // "bars.incident.wave_speed_m_s", "gauges.tr.delay_s", ...
  double nominal = 0, value = 0;
  std::optional<double> sd;  // null: the shots do not determine it
};

// One shot's measured records and the model at the nominal and fitted values (figures, residuals).
struct ShotSignals {
  std::string scene, kind;  // kind: "bars apart" | "bars together"
  std::string source_gauge;
  std::vector<double> time_s;
  std::vector<double> source;  // the source pulse (its record outside the pulse zeroed)
  std::vector<std::string> gauges;
  std::vector<std::vector<double>> measured, nominal, fitted;
  std::vector<std::vector<char>> fitted_window;  // the samples the fit compares
  double rms_nominal = 0, rms_fitted = 0;        // over the compared samples, of the source peak
};

struct CalibrationFit {
  Calibration calibration;
  std::vector<FittedParameter> parameters;
  std::vector<ShotSignals> shots;
  double reciprocal_condition = 0;        // smallest over largest singular value (scaled J)
  std::vector<std::string> undetermined;  // one line per weak direction
  std::vector<std::string> warnings;
  int iterations = 0;
  bool converged = false;
  std::size_t residuals = 0;
};

// InputError naming a scene that is no calibration shot (a specimen, gauges on more than two bars,
// no pulse, a record too short for any returning pulse); NumericalError if the solver fails.
CalibrationFit calibrate_bars(const std::vector<CalibrationShot>& shots,
                              const CalibrateOptions& options);

}  // namespace shpb
