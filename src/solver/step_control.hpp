#pragma once
// The adaptive step of a material-law bar with finite strain (docs/methods.md §8.1, "The stable
// step"; the specimen without face friction or radial inertia, simulation.cpp says why): instead
// of one step planned for the shortest element the run may ever produce (λ = 1 − e_max,
// discretization.hpp), the step follows the shortest element reached so far.
//
// Rule. At each of its instants, after its forces are assembled (scheduler.hpp rule 3), the bar
// knows λ_min, the smallest element stretch reached so far, and τ_max, the largest element |τ|
// (running extremes: they never recede). While λ_min ≥ λ_p and τ_max ≤ τ_p, the stretch and
// stress the current step was planned for, the step stays. Otherwise a new phase of constant step
// starts at this instant (rule 1) with
//   λ_p = max(1 − e_max, λ_min − kStepPlanMargin),   τ_p = (1 + kStressPlanMargin) τ_max,
//   Δt = C h0 λ_p / (c g(τ_p)),
// g the geometric stiffening (below; 1 while τ_p is within 1 % of ρc²), and never below the fixed
// plan's step. The first phase is planned for λ_p = 1, τ_p = 0.
//
// Why it is stable. (i) Per instant: the step taken from t_n is planned for a stretch no larger
// than any element's at t_n, so it is within the critical step h0 λ/c of the state it starts from:
// the criterion of the fixed plan (which holds it for every λ ≥ 1 − e_max), evaluated where the bar
// is instead of where it might end; geometric stiffening as there. (ii) Across a
// change: the variable-step central difference, v_{n+1/2} = v_{n−1/2} + ½(Δt_{n−1} + Δt_n) a_n,
// u_{n+1} = u_n + Δt_n v_{n+1/2}, is a sequence of velocity-Verlet phases joined at the full-step
// state (u_n, v_n = v_{n−1/2} + ½Δt_{n−1} a_n), which passes unchanged from one phase to the next.
// For a linear mode of frequency ω a phase of step Δt conserves exactly
//   H_Δt = ½ v² + ½ ω² (1 − ω²Δt²/4) u²   (positive for ωΔt < 2).
// The steps only shrink (λ_min only decreases), so at each change H grows at most by the ratio of
// the u² weights, and over any number of changes these ratios telescope:
//   H_last / H_first ≤ (1 − ω²Δt_last²/4) / (1 − ω²Δt_first²/4) ≤ 1/(1 − C²),
// a bounded factor whatever the number of phases (no exponential growth); a change of a few per
// cent moves it by far less. The energy check of scheduler rule 7 still watches every run.
//
// Global stepping: every bar takes the smallest step any bar needs, and all change together.
#include "solver/chain.hpp"

namespace shpb {

// Stretch below the shortest element at which a new phase is planned: fewer changes against a
// step a little below the largest stable one (2 % of stretch: ~10 phases for a 20 % test).
inline constexpr double kStepPlanMargin = 0.02;

// Geometric stiffening: an element of current stretch λ under Kirchhoff stress τ has the axial
// stiffness (E_t − τ) A0/(h0 λ²) (N = τ A0/λ), so compression (τ < 0) raises its frequency by
// √(1 + |τ|/E) beyond the unstressed element's at λ. A metal's flow stress is under 1 % of E,
// which the Courant number's room covers (discretization.hpp); a polymer's reaches 20–40 % of E
// at large strain: measured, PMMA specimens at 25 m/s then grew their top mode (node velocities of
// ±300 m/s alternating along the specimen, elements crushed to λ < 0.5) and ended 2–18 % off their
// energy. Above this share of E the adaptive step is shortened by the factor, planned for the
// largest |τ| so far times 1 + kStressPlanMargin (fewer phases).
inline constexpr double kGeometricStiffeningRoom = 0.01;
inline constexpr double kStressPlanMargin = 0.1;
double geometric_stiffening(const BarModel& bar, double stress_Pa);

// Step of `bar` planned for element stretch λ and element |τ| (above); own_step_s for a bar with a
// fixed step.
double planned_step_s(const BarModel& bar, double stretch, double stress_Pa);

// Starts a phase of step dt for bar i at its pending instant τ (rule 1) and resets the instant
// at which it is finished (rule 8).
void start_phase(Chain& chain, std::size_t i, double dt);

// The first phase of every bar (before the run).
void plan_first_steps(Chain& chain);

// At τ*, after the stepping bars in [first, last] assembled their forces: re-plans the step of an
// adaptive bar whose shortest element passed its planned stretch (all bars in global stepping).
void replan_steps(Chain& chain, const std::vector<char>& stepping, std::size_t first,
                  std::size_t last);

}  // namespace shpb
