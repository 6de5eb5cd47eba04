#pragma once
// What a study sweeps: the cases of the accuracy-against-cost sweep and the grid of the
// stability map, and how one case turns a scene into the scene that is run.
#include <string>
#include <vector>

#include "core/enum_names.hpp"
#include "model/scene.hpp"

namespace shpb {

// One run of the accuracy-against-cost sweep.
struct ParetoCase {
  ContactMethod method = ContactMethod::kLocalizedBipenalty;
  Stepping stepping = Stepping::kAsynchronous;
  double resolution = 1;  // factor on every bar's element count (1: the automatic mesh)
  // Localized bipenalty with finite links (the default ε_s and R given explicitly,
  // contact_localized_finite.cpp) instead of the rigid-link limit: a method of its own.
  bool finite_links = false;
};

// The case's method as pareto.csv and summary.json name it: "localized-bipenalty-finite" for
// finite links, else the contact method.
std::string method_name(const ParetoCase& c);

// Mesh resolution factors: 1/4 … 4 of the automatic mesh, in factors of two.
inline const std::vector<double> kParetoResolutions = {0.25, 0.5, 1, 2, 4};

// "1/4", "1/2", "1", "2", … (factors in summaries and descriptions).
std::string format_factor(double factor);

// Every method × stepping × resolution, restricted to `methods` / `steppings` when not empty
// (the --contact / --stepping options of `shpb study`); localized bipenalty also with finite
// links, asynchronous.
std::vector<ParetoCase> pareto_cases(const std::vector<ContactMethod>& methods,
                                     const std::vector<Stepping>& steppings,
                                     const std::vector<double>& resolutions = kParetoResolutions);

// The scene with every bar's element count (given or automatic, model/discretization.hpp)
// multiplied by `factor` (at least one element).
Scene scene_at_resolution(const Scene& scene, double factor);

// The scene of one pareto case: method at every interface, stepping, resolution.
Scene scene_for(const Scene& scene, const ParetoCase& c);

// One point of the stability map.
struct StabilityPoint {
  ContactMethod method = ContactMethod::kPenalty;
  double stiffness_factor = 1;  // ε_s / (EA/h) of the stiffer neighbour
  double mass_ratio = 0;        // R / R_crit (bipenalty methods; 0 for plain penalty)
  double courant = 1;           // c·Δt/h of every bar
  bool tied = false;            // plain penalty acting in tension too (linear limit)
  // Δt_striker / Δt_bar of the probe, asynchronous stepping (the bar meshed finer by this
  // factor); 1: both bars at one step.
  double step_ratio = 1;
};

// Step ratios of the localized-bipenalty map: equal steps, 2, π (the non-integer benchmark of
// docs/methods.md §3), and a bar against a specimen ten times finer: 9.95 (the elastic classic
// scene at its tolerance's meshes, docs/methods.md §3.7) and exactly 10.
inline const std::vector<double> kStepRatios = {1, 2, 3.141592653589793, 9.95, 10};

// The stability grid: ε_s/k from 1e-2 to 1e6 (two points per decade), C from 0.1 to
// 1.05 (with the near-exact 0.995, 0.9995 and 0.9999 a run or a tolerance may choose), and for the
// bipenalty methods R/R_crit from 0.25 to 4; localized bipenalty at every step ratio of
// kStepRatios, finite links and the rigid-link limit (ε_s/k and R/R_crit 0 in the map).
inline const std::vector<double> kStiffnessFactors = {
    1e-2, 3e-2, 1e-1, 3e-1, 1, 3, 10, 30, 1e2, 3e2, 1e3, 3e3, 1e4, 3e4, 1e5, 3e5, 1e6};
inline const std::vector<double> kCourantNumbers = {0.1,    0.15,   0.2, 0.25, 0.3,  0.4,  0.5,
                                                    0.6,    0.7,    0.8, 0.9,  0.95, 0.98, 0.995,
                                                    0.9995, 0.9999, 1.0, 1.02, 1.05};
inline const std::vector<double> kMassRatios = {0.25, 0.5, 0.9, 1, 1.5, 2, 3, 4};

// `refine` > 1 puts refine − 1 more points between neighbours on the stiffness axis (evenly in
// log) and the Courant axis (evenly): refine 2 gives 33 × 31 points per line instead of 17 × 16.
std::vector<StabilityPoint> stability_grid(const std::vector<ContactMethod>& methods,
                                           int refine = 1);

// The sweeps of `shpb study --sweep`: accuracy against cost (pareto.csv), the stability map
// (stability.csv) or the Monte Carlo of a planned test (study/monte_carlo_sweep.hpp); the names are
// those of the command line, plan.json and summary.json.
enum class Sweep { kPareto, kStability, kMonteCarlo };
inline constexpr EnumName<Sweep> kSweepNames[] = {{"pareto", Sweep::kPareto},
                                                  {"stability", Sweep::kStability},
                                                  {"monte-carlo", Sweep::kMonteCarlo}};
inline std::string to_string(Sweep s) { return std::string(enum_name(kSweepNames, s)); }

}  // namespace shpb
