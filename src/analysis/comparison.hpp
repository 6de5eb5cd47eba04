#pragma once
// Simulated against measured, pulse by pulse: both signals on one uniform time grid,
// compared inside one window of samples. Shifts are simulated minus measured (positive: the
// simulated pulse comes later); ratios are simulated over measured.
#include <cstddef>
#include <span>
#include <string>

namespace shpb {

struct PulseComparison {
  std::string gauge;
  std::string pulse;  // incident | reflected | transmitted
  double window_start_s = 0, window_end_s = 0;
  double arrival_shift_s = 0;  // lag of the cross-correlation maximum (sub-sample, parabolic)
  double peak_ratio = 1;       // largest |ε| in the window (front oscillations included)
  double plateau_ratio = 1;    // plateau level (pulse_window.hpp plateau_level): robust peak
  double duration_ratio = 1;   // full width at half of the peak
  double rise_time_measured_s = 0, rise_time_simulated_s = 0;  // 10 % → 90 % of the peak
  double nrmse = 0;                                            // RMS(sim − meas) / max |meas|
  double correlation = 1;                                      // Pearson coefficient in the window
};

struct ClippedSamples;  // analysis/signal_checks.hpp

// Compares simulated with measured over samples [begin, end) of a grid of step dt_s. The
// cross-correlation lag is searched within ± half the window. A clipped measured channel's samples
// at its clip level (`clipped`) count in the NRMSE by their censored residual, 0 where the
// simulation reaches the level (as fit's residuals take them): the cut plateau is not an error of
// the simulation.
PulseComparison compare_pulse(std::span<const double> measured, std::span<const double> simulated,
                              double dt_s, std::size_t begin, std::size_t end,
                              const ClippedSamples* clipped = nullptr);

// 10 % → 90 % rise time of the first excursion to the peak of |x| in [begin, end), in samples
// (linear interpolation between samples).
double rise_time_samples(std::span<const double> x, std::size_t begin, std::size_t end);

// Full width at half of the peak of |x| in [begin, end), in samples: first to last crossing.
double half_peak_width_samples(std::span<const double> x, std::size_t begin, std::size_t end);

}  // namespace shpb
