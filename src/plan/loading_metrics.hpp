#pragma once
// What a planned test must meet and what a simulated record says about its loading, judged by
// `shpb plan`'s search (plan/plan_search.hpp) and written by its outputs.
#include <span>
#include <string>
#include <vector>

#include "analysis/processing.hpp"  // kEquilibriumThreshold
#include "core/time_series.hpp"
#include "model/scene.hpp"
#include "solver/simulation.hpp"

namespace shpb {

// The criteria of a planned test (docs/methods.md §12): the specimen's strain rate within
// ±kRateBand of the target over at least kBandFraction of the loading, force equilibrium of the
// bars' forces on the faces (R ≤ kEquilibriumRatio, process's criterion) before
// kEquilibriumFraction of it, and the target strain reached.
inline constexpr double kRateBand = 0.10;
inline constexpr double kBandFraction = 0.50;
inline constexpr double kEquilibriumRatio = kEquilibriumThreshold;
inline constexpr double kEquilibriumFraction = 0.25;
// Of simulation.max_strain, the mean strain a planned test may reach
// (LoadingMetrics::strain_limit).
inline constexpr double kSimulableStrainFraction = 0.9;

struct PlanTargets {
  double rate_1_s = 0;
  double strain = 0.15;
  bool IsValid(std::string* error) const;  // a positive rate, a strain in (0, 1)
};

// A specimen rate below this fraction of the target is no loading yet (or any more).
inline constexpr double kLoadingOnsetFraction = 0.1;

// What a simulated record says about a loading: the specimen's rate and strain
// (SimulationResult::specimen), and the equilibrium of the forces the bars put on its faces (the
// forces a lab's gauges measure: incident + reflected at the front, transmitted at the back).
struct LoadingMetrics {
  double onset_s = 0, end_s = 0;  // the loading: rate first ≥ 10 % of the target → strain maximum
  double plateau_rate_1_s = 0;    // median strain rate over the loading
  double band_fraction = 0;       // of the loading with the rate within ±kRateBand of the target
  double rate_spread = 0;         // standard deviation of the rate over the loading / the target
  double equilibrium_s = 0;       // from the onset until |R| ≤ kEquilibriumRatio to the end
  double equilibrium_fraction = 1;  // equilibrium_s over the loading's duration
  double strain_reached = 0;        // largest engineering strain of the run
  // The mean of the positive rate over the loading: the mean `process` quotes (its loading ends
  // at the strain maximum too, docs/methods.md §6).
  double test_mean_rate_1_s = 0;
  double target_strain = 0.15;
  // The largest mean strain a plan may take the specimen to: kSimulableStrainFraction of the
  // strain its steps are planned for (simulation.max_strain). The shortest element runs ahead of
  // the mean, and a finer mesh stops there (exit 3): measured, a plan at a mean of 0.499 on the
  // search's meshes compressed an element past 0.5 on the 0.5 % meshes.
  double strain_limit = 1;
  bool meets() const;  // every criterion
  // The smallest relative margin by which the band, equilibrium and strain criteria are met
  // (negative: one is missed).
  double slack() const;
  // How far from meeting each criterion, relative to its threshold (0 when met).
  struct Shortfalls {
    double strain = 0, strain_limit = 0, band = 0, equilibrium = 0;
  };
  Shortfalls shortfalls() const;
  // How far from meeting them (0 when met): the sum of the relative shortfalls.
  double shortfall() const;
};
LoadingMetrics loading_metrics(const TimeSeries& specimen, std::span<const double> front_force_N,
                               std::span<const double> back_force_N, const PlanTargets& targets);
// The forces of the bars on the specimen's faces in a run of `scene`: its interfaces' with the
// specimen's neighbours (compression positive).
struct FaceForces {
  const std::vector<double>& front;
  const std::vector<double>& back;
};
FaceForces face_forces(const SimulationResult& run, const Scene& scene);
// loading_metrics of a run of `scene`, with its face forces.
LoadingMetrics loading_metrics(const SimulationResult& run, const Scene& scene,
                               const PlanTargets& targets);

}  // namespace shpb
