#pragma once
// The asynchronous scheduler: every bar advances with its own time step, interfaces are solved on
// the union of their neighbours' instants (docs/methods.md §3; after Dvořák et al. 2023, CMAME
// 413:116110). Global stepping is the special case where every bar has the same Δt.
//
// Contract (τ is the time since the start of the run; the simulation clock is t = t_start + τ):
//  1. Bar i owns its step Δt_i and its instants τ_{i,n} = n·Δt_i (a product, never a running
//     sum). Its state sits at exactly one instant: displacements at τ_{i,n}, velocities over
//     (τ_{i,n−1}, τ_{i,n}). An adaptive bar (step_control.hpp) may start a new phase of constant
//     step at one of its own instants τ_{i,p}, right after assembling there (rule 3); its
//     instants are then τ_{i,p} + (n − p)·Δt_i, still a product within the phase.
//  2. The scheduler always processes the earliest pending instant τ* = min_i τ_{i,n}. Every bar
//     whose pending instant equals τ* (to kSameInstant·Δt) steps at τ*, together. A bar that
//     steps alone keeps stepping alone while its next instant comes before every other bar's
//     pending one: those instants (the specimen's between two bar instants) run in a tight
//     loop, each exactly as rules 3–7 say, without repeating the search.
//  3. A bar stepping at τ* first assembles its internal forces at τ*; then each adjacent
//     interface is solved at τ* (once, even if both neighbours step); then the bar records its
//     outputs at τ* and advances one step.
//  4. Before assembling, a stepping end tied to a closed localized-bipenalty frame is reset to
//     the frame's displacement at τ* (the frame moves on the union of instants; this stops gap
//     drift), behind it by its link's extension for finite links whose end follows the frame
//     (tied_end_position, contact_localized_finite.cpp). A neighbour that does not step at τ* is
//     ahead: τ_{j,m} − Δt_j ≤ τ* < τ_{j,m} (rule 2 picked the minimum). Its end displacement at τ*
//     is interpolated on its current step, on which the central-difference path is linear (exact);
//     its free end force is recomputed from the interpolated displacements (exact for elastic bars;
//     the last stress of a material law, carried along the end element's path with its
//     instantaneous stiffness where that bar has the longer step of the tie: docs/methods.md §3.7).
//  5. A solved interface force is applied only by the sides stepping at τ*; a side that is ahead
//     used the force solved at its own instant ("each partition takes its own full step with its
//     latest multiplier").
//  6. Velocity jumps of a momentum-consistent contact activation are applied to both ends at τ*:
//     to a stepping end's v_{n−1/2}; to an ahead end's velocity, moving its displacement at
//     τ_{j,m} so that its path from τ* on follows the new velocity.
//  7. Recorders take each bar's instants and each interface solve and interpolate linearly onto
//     the output grids. An energy grid point is complete when every bar and interface has passed
//     it; there the energy is checked: a non-finite total, a total above kEnergyGrowthLimit ×
//     E(0) or a strain energy above kStrainGrowthLimit × E(0) stops the run as unstable
//     (docs/commands.md, exit 3) with what was computed until then.
//  8. A bar is finished after it has taken its instant at or beyond the end of the recording;
//     the run ends when every bar is finished.
//  9. Cancellation is polled every kCancelPollInstants instants (throws Interrupted).
// 10. A lone bar at rest skips: when the bar of the tight loop (rule 2) is quiet (every node at
//     rest, docs/methods.md §7), it and both neighbours have no initial velocity, each neighbour's
//     end node and end element are at rest, and each interface is a rigid link open with a gap or
//     tied with its frame at rest, its instants change nothing but its step count (the neighbours
//     do not step meanwhile); it goes straight to the loop's last instant and takes that one,
//     whose record at rest stands for the skipped ones. Outputs are bit-identical (a test pins
//     it): the specimen before the incident pulse reaches it. Not in a chain with end segments.
// 11. A tie with an end segment (end_segment.hpp) is solved at its clock bar's instants only,
//     both ends stepping there; the slow bar's rule 4 and its own instants leave the segment
//     alone; the joint takes its impulse as a force if its bar steps, else by rule 6. A law
//     specimen's face takes its segment at the first instant of the specimen at which the face
//     is unloaded (start_release_segments), before that instant's rule 4.
#include <functional>
#include <string>

#include "solver/chain.hpp"
#include "solver/recorders.hpp"

namespace shpb {

// Two instants closer than this fraction of the smaller step are the same instant.
inline constexpr double kSameInstant = 1e-9;
// A run is unstable when its total energy grows beyond kEnergyGrowthLimit × E(0), or the bars'
// strain energy alone beyond kStrainGrowthLimit × E(0). Energy enters only as the bars' initial
// velocities. The total includes what the contact links hold, and a node-to-node bipenalty link,
// stable but ringing, holds up to ~10² × E(0) in its mass penalty (measured 67 × on the striker-on-
// bar set-up of docs/methods.md §2); an unstable run grows past any such bound. The bars' strain
// energy cannot exceed E(0) while the energy is conserved (a stable run stays within ~1e-2 of it),
// and it is checked alone because a mode at the Nyquist frequency has a negative central-difference
// kinetic energy ½ m v₋ v₊ that cancels it in the total while unilateral contacts cap its growth:
// measured on a soft elastic specimen at C 0.9999, a total of 108 × E(0) with the strain energy at
// 1260 × E(0), and the run was called stable.
inline constexpr double kEnergyGrowthLimit = 1e3;
inline constexpr double kStrainGrowthLimit = 10;
inline constexpr long kCancelPollInstants = 4096;

struct ScheduleOutcome {
  bool stable = true;
  std::string failure;
  double checked_until_s = 0;  // simulation time up to which outputs are valid
  double energy_error = 0;
};

// `subcycle` false searches rule 2 at every instant (the plain loop; tests compare the two);
// `subcycle_at_rest` false takes every instant of a bar at rest (rule 10; the same comparison).
ScheduleOutcome run_schedule(Chain& chain, ChainRecorders& recorders,
                             const std::function<void(double)>& progress,
                             const std::function<bool()>& cancel, bool subcycle = true,
                             bool subcycle_at_rest = true);

}  // namespace shpb
