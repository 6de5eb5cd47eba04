#pragma once
// End segments: the cure of the asynchronous rigid link between bars on different steps
// (docs/methods.md §3.6). Resetting the slow bar's end to the frame (§3.4) does work no force did;
// where the fast bar's end is light and stiff (a pulse shaper on steel) that creates energy
// (bonded, it grows without bound; measured too where the tied pair's mode is resolved by the slow
// step). The slow bar's kSegmentElements end elements, with their nodes, then step on the fast
// bar's clock: the tie always joins two ends stepping together (the global-step merged node, no
// reset, no interpolated end load), and the change of clock moves to the joint, the slow bar's
// node where the segment starts. The joint is the slow bar's own node; at every fast instant it
// takes the impulse κ N of its segment element and moves on a straight line between instants, its
// pending position shifted by (τ_pending − τ) Δv (scheduler rule 6 applied to it): an
// asynchronous variational integrator (Lew, Marsden, Ortiz & West 2003), whose element impulses
// reach both their nodes at one instant (momentum exact) and whose energy error stays bounded. The
// tied pair's mode, where the slow bar cannot follow it (above its cut-off 2c/h), decays into the
// slow bar by e^(−κ) per element, cosh(κ/2) = ω_m h/(2c): three elements keep the joint away from
// it (one is not enough: measured, it resonates).
#include <vector>

#include "model/scene.hpp"
#include "solver/chain.hpp"
#include "solver/contact.hpp"

namespace shpb {

inline constexpr int kSegmentElements = 3;
// Measured on the pulse shaper's disc ties without segments: at ratios of 1.43 and 1.7 (discs of
// 48 elements on steel of 0.135 and 0.17 mm) they chattered (962/886 closings and energy 2e-2;
// 411/452, 6e-3), at 1.01 and 1.02 (30 and 24 elements) not; equal bars are at 1 (the mini-Kolsky
// striker on its bar, 1.02, keeps its coupling: segments there doubled its energy error).
inline constexpr double kLightStiffEnd = 1.2;
// A law specimen's face is unloaded, for its end segment to start (start_release_segments), once
// it is open and the slow bar's end element carries less than this share of the face's largest
// force. Measured (docs/validation.md, the 144 set-ups of "A law specimen that stays elastic"):
// thin wafers open within the loading with more than 10 % of it there; 25 m/s copper specimens
// opened with 1-10 % there, amid the unloading's own energy error, and switching then created
// 0.07-0.08 % more (first runs 0.43-0.49 -> 0.51-0.55 % off, repeated where the coupling of §3.4
// was not); at 1 % none, every set-up repeated exactly as without. The shipped experiments' faces
// reach it within 0-7 µs of their first release.
inline constexpr double kUnloadedShare = 0.01;

// Gives the slow bar of each asynchronous localized tie (rigid links; finite links where the fast
// bar is squeezed between two others, a pulse shaper or a specimen) with a light, stiff
// fast end (its pair's (k1 + k2)/(m1 + m2) above kLightStiffEnd × k1/m1) an end segment on the fast
// bar's clock, where that is supported: a slow bar with fixed steps, elastic or a law bar that is
// not the specimen (its segment's law steps on the fast clock; not with friction or radial
// inertia), a fast bar with fixed steps (an elastic specimen too), no cut end within the segment
// (a gauge within it reads it on its own clock: segmented_element_strain). `law_specimen`:
// a specimen with a material law (on its adaptive step too) takes them as well (simulation.cpp
// says when); else its faces' segments wait in chain.release_segments for start_release_segments.
void plan_end_segments(Chain& chain, const Scene& scene, bool law_specimen);

// At an instant τ, before anything steps there (scheduler rule 11): a waiting segment at a law
// specimen's face starts at the first instant of its clock (the specimen) at which the face is
// open after its loading (kUnloadedShare), so the run until then is the one without it. After
// the release the slow bar's end and the specimen's were pinned together by the slow end's reset
// to the frame (rules 4–5) and switched the face 20-170 times as often as the global steps, one
// clock, at the same meshes (classic and LANL copper experiments, docs/methods.md §3.7). Its nodes
// (the joint aside) go from the slow bar's pending instant back to τ on their straight paths and
// step on the clock from there.
void start_release_segments(Chain& chain, const std::vector<char>& stepping, double tau);

// At an instant τ of the segment's clock bar (which steps), in take_instant's order: `prepare`
// puts a tied segment end at the frame (rule 4) and assembles the segment's element forces with
// the joint on its straight path at τ; `end_state` is the segment end for the tie solve (stepping
// with the clock bar's kick); `finish` applies the joint's impulse (a force if the slow bar steps
// at τ too, else rule 6) and advances the segment's nodes; the segment's energy at τ goes into
// the interface state (strain in `prepare`, kinetic in `finish`). Returns the node updates.
void prepare_segment(Chain& chain, EndSegment& seg, double tau, bool bar_stepping);
EndState segment_end_state(const Chain& chain, const EndSegment& seg, double tau);
void apply_segment_end(Chain& chain, const EndSegment& seg, double dv, double force);
long finish_segment(Chain& chain, EndSegment& seg, double tau, bool bar_stepping);

// The strain of element `element` of bar `bar` (with end segments) at τ, an instant of that bar, as
// a gauge reads it: a segment's nodes, which are at their clock's pending instant (nodes_tau ≥ τ),
// taken at τ on their straight paths; the joint's element, whose two nodes step on two clocks and
// whose stretch zigzags with the segment element's impulses (measured: 2–5 % low on a plateau, read
// at the bar's instants), as the mean of its neighbours.
double segmented_element_strain(const Chain& chain, std::size_t bar, int element, double tau);

}  // namespace shpb
