#pragma once
// The reference a pareto run's gauge signals are measured against: the exact solution
// where the scene has one, else a converged fine-mesh run. The error is the relative L2 norm of
// the difference over every gauge and every sample of the comparison window.
#include <functional>
#include <optional>
#include <string>

#include "model/scene.hpp"
#include "solver/simulation.hpp"
#include "study/sweep.hpp"

namespace shpb {

struct GaugeReference {
  std::string description;  // written to summary.json: which reference, and why
  bool exact = false;
  double window_end_s = 0;  // samples at t < window_end_s are compared
  // Exact: strain of gauge `column` (index in the run's gauge columns) at time t. Fine mesh:
  // the reference run's gauges on the same sample grid.
  std::function<double(std::size_t column, double t)> strain;
  // Exact: the same strain as a record sees it (study/recorded_error.hpp), the exact signal
  // convolved with a Gaussian of standard deviation sigma_s, fronts at their exact arrival times.
  std::function<double(std::size_t column, double t, double sigma_s)> recorded;
  TimeSeries fine;
  // Fine mesh: the reference run's gauges as a record sees them (study/recorded_error.hpp),
  // smoothed on its oversampled grid (kReferenceOversampling) and kept on the run's sample grid.
  TimeSeries recorded_fine;
  double wall_time_s = 0;  // of the fine-mesh run
};

// A striker on a bar of the same material and area, both elastic, gauges on the bar only
// (docs/methods.md §4): a square strain pulse −V/(2c0) lasting 2L_s/c0 passes each gauge; compared
// until the reflection from the bar's far end reaches the first gauge. Else nullopt.
std::optional<GaugeReference> exact_reference(const Scene& scene);

// Mesh resolution factor of the fine-mesh reference: twice the finest of the sweep.
inline constexpr double kReferenceResolution = 8;
// … except the specimen's, kept at the sweep's finest: the runs' gauge error is mostly the bars'.
// Classic experiment, bars at 8 ×: the specimen at 1/4, 1, 4 × differs from 8 × by 0.5, 0.15,
// 0.06 % of the gauge norm, where the sweep's runs are 2–6 % off; 4 × costs 40 % of the 8 × run
// (measured, docs/validation.md "Accuracy against cost").
inline constexpr double kReferenceSpecimenResolution = 4;

// The fine-mesh reference run records its gauges at this multiple of the scene's sample rate, so
// that its fronts, sharper than a sample at 8 ×, are seen through the record's Gaussian at their
// own times and not where the sample grid falls on them (docs/methods.md §1.1); every
// kReferenceOversampling-th sample is the study's point-sample reference.
inline constexpr int kReferenceOversampling = 8;

// The fine-mesh reference run: localized bipenalty, asynchronous stepping, at `resolution` ×
// the automatic mesh (the specimen at most kReferenceSpecimenResolution ×).
ParetoCase fine_reference_case(double resolution);
Scene fine_reference_scene(const Scene& scene, double resolution);

// The reference from that run's outcome: its gauges over the whole recording (recorded at
// kReferenceOversampling × the scene's sample rate).
GaugeReference fine_mesh_reference(const Scene& scene, double resolution, bool stable,
                                   const std::string& failure, TimeSeries gauges,
                                   double wall_time_s);

// Runs the fine-mesh reference scene and keeps its gauges as the reference.
GaugeReference fine_mesh_reference(const Scene& scene, double resolution,
                                   const SimulationOptions& options);

// √(Σ (ε − ε_ref)²) / √(Σ ε_ref²) over the gauges and the samples of the window (callers take
// it of stable runs only); NaN if the run is shorter than a fine-mesh reference.
double gauge_error(const TimeSeries& gauges, const GaugeReference& reference);

}  // namespace shpb
