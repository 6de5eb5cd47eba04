#pragma once
// The stability map's probe (docs/methods.md §2): the scene's first contact — its striker on
// the bar it hits — cut down to two short bars of equal element length, run long enough for the
// contact to close, hold for 2 L/c and open again. A point is unstable when the total energy
// grows beyond kUnstableEnergyGrowth × its initial value, or the run stops on a non-finite value.
#include <limits>

#include "model/scene.hpp"
#include "study/sweep.hpp"

namespace shpb {

// Criterion: energy growth beyond 10× E(0), or a non-finite value, is unstable. A stable run stays
// within ~1e-2 of E(0) (docs/methods.md §2 reference); an unstable one grows exponentially, so the
// verdict does not hang on the exact factor.
inline constexpr double kUnstableEnergyGrowth = 10;
// Elements per probe bar: short enough to run a point in about a millisecond, long enough that
// the localized contact mode decays into the bar (it spans a few elements for ε_s ≳ k).
inline constexpr int kProbeElements = 20;

// Two bars of the striker's length with kProbeElements elements each (the bars' materials and
// areas, the striker's velocity, or 1 m/s if it has none); duration three transits of the
// slower bar. The probe scene says in `name` what it is.
Scene stability_probe_scene(const Scene& scene);

struct StabilityVerdict {
  double energy_growth = 1;  // max total energy / initial (over what was computed)
  bool stable = true;
  // Closings of the probe's contact after its first: every one comes after the striker's first
  // release (unloading), so this counts the contact's rattle (docs/methods.md §3.7).
  long closings_after_release = 0;
  // What converges where the closings do not (docs/methods.md §3.7): the meetings after the
  // contact's unloading (its first release after its loading peak) and the largest contact force
  // after it over that peak (NaN if it never opened after its peak). A probe of bars of one wave
  // speed ends one transit L/c, the meeting separation, after the striker's release: its meetings
  // are 0 whatever the method, and the force share weighs its rattle.
  long meetings_after_unloading = 0;
  double force_after_unloading_share = std::numeric_limits<double>::quiet_NaN();
};

// Runs `probe` with the point's method, penalty parameters and Courant number.
StabilityVerdict judge_stability(const Scene& probe, const StabilityPoint& point);

// Exact critical Courant number of plain node-to-node penalty between two identical lumped bars
// (k = EA/h, end masses m/2, s = ε_s/k). The contact mode is staggered, u_j = (−1)^j q^j on each
// side, antisymmetric across the contact; the end-node equation gives 1/q − q = 4s and the
// interior ones m ω² = k (2 + q + 1/q), so ω² = (2k/m)(1 + sqrt(1 + 4s²)) and
//   C_crit = 2/(ω h/c) = sqrt(2 / (1 + sqrt(1 + 4 s²))),
// → sqrt(k/ε_s) for ε_s ≫ k (the bar-on-rigid-wall law of docs/methods.md §2 is the same with
// 4s² → s², hence sqrt(2k/ε_s) there: one end mass on the spring instead of two).
double penalty_critical_courant(double stiffness_factor);

// Bipenalty above R_crit: the step tends to 2/√R (docs/methods.md §2), i.e. with R_crit = (2c/h)²
// C_crit → sqrt(R_crit / R); at or below R_crit the bar's own limit C = 1 stays.
double bipenalty_critical_courant(double mass_ratio);

// The largest stable Courant number of a point (its courant ignored) on the probe, by bisection
// on log C between `lo` and `hi` (assumes stable at lo and unstable at hi; returns lo or hi if
// not).
double measured_critical_courant(const Scene& probe, StabilityPoint point, double lo = 1e-3,
                                 double hi = 1.1, int iterations = 14);

}  // namespace shpb
