#pragma once
// The standard check of a bar set-up (docs/methods.md §5): the bars pushed together without a
// specimen, one pulse recorded at a near and a far gauge. The near gauge's pulse is moved to the
// far gauge with Pochhammer–Chree dispersion and, beside it, by a plain time shift Δz/c0; the RMS
// difference from the far record (fraction of its peak) says how well each describes the bars.
#include <string>
#include <vector>

#include "analysis/gauge_signals.hpp"
#include "dispersion/propagation.hpp"
#include "model/scene.hpp"

namespace shpb {

struct BarCheckSetup {
  std::string near_gauge, far_gauge;
  double distance_m = 0;   // along the bars, near → far
  BarWaveguide waveguide;  // of the near gauge's bar
  // The way near → far bar by bar: each bar's waveguide and the distance in it (calibrated bars
  // of one nominal material differ slightly in wave speed and Poisson ratio).
  std::vector<std::pair<BarWaveguide, double>> path;
};

// Bars whose wave speeds differ by up to 5 % are checked as one set (density and diameter equal):
// their impedances then differ by as much, and the interface reflects at most 2.5 % of the pulse.
inline constexpr double kBarsTogetherSpeedSpread = 0.05;

// The first and last gauges along the chain that have a signal. InputError naming the scene if
// fewer than two, or if the bars between them differ in density or diameter, or in wave speed by
// more than kBarsTogetherSpeedSpread.
BarCheckSetup resolve_bar_check(const Scene& scene, const std::vector<std::string>& available);

struct BarCheckResult {
  std::vector<double> time_s;  // the compared window at the far gauge, on the signals' clock
  std::vector<double> far_measured, far_dispersion, far_time_shift;
  double rms_dispersion = 0, rms_time_shift = 0;  // fraction of the far pulse's peak
  double cutoff_Hz = 0;
  std::vector<std::string> warnings;
};

BarCheckResult check_bars_together(const GaugeSignals& signals, const BarCheckSetup& setup,
                                   const DispersionSpec& dispersion, const std::string& scene_file);

}  // namespace shpb
