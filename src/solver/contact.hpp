#pragma once
// Contact interfaces between neighbouring bars: common data and the dispatch to one method per
// file (contact_penalty.cpp, contact_bipenalty.cpp, contact_localized_bipenalty.cpp).
//
// Sign conventions: the gap g = gap0 + u_right − u_left (g < 0 is penetration); forces are the
// forces the interface applies to each end node; the reported contact force is compression
// positive (docs/outputs.md).
#include <limits>

#include "model/discretization.hpp"
#include "model/penalty_links.hpp"
#include "model/scene.hpp"

namespace shpb {

// One side of an interface at the instant τ being solved.
struct EndState {
  double u = 0;           // absolute displacement of the end node [m]
  double v = 0;           // absolute velocity of the end node (half-step) [m/s]
  double free_force = 0;  // f̃: the bar's own force on the end node [N]
  double mass = 0;        // lumped end-node mass m_b [kg]
  bool stepping = false;  // the bar takes a step at τ and uses the force solved now
  double kick_s = 0;      // the stepping bar's velocity kick length at τ (Δt, or Δt/2 at n = 0)
  double step_s = 0;      // the bar's Δt
  double next_tau = 0;    // its next instant: τ + Δt if stepping, its pending one if ahead

  // Full-step velocity at τ (velocity-Verlet): v_{n−1/2} + (kick − Δt/2) f̃/m for a stepping end
  // (v_0 itself at n = 0). An end that is ahead is on its step's straight path, whose velocity
  // v_{m−1/2} is the full-step one at the step's middle, τ_m − Δt/2: at τ it is
  // v_{m−1/2} + (τ − τ_m + Δt/2) f̃/m, on the same footing as the stepping end's. Its chord
  // velocity alone was up to half a step off (Δt/2 · f̃/m): a closing between an end that steps and
  // one ahead then took the wrong impulse, which fed the ends' top mode where a striker grazes a
  // bar at a step ratio near 1 (docs/methods.md §3.4, "An end that is ahead at a closing").
  double velocity_now(double tau) const {
    return stepping ? v + (kick_s - 0.5 * step_s) * free_force / mass
                    : v + (tau - next_tau + 0.5 * step_s) * free_force / mass;
  }
};

// Immutable parameters of one interface, derived from the neighbours (docs/methods.md §2–3).
struct InterfaceModel {
  std::string name;  // "<left>-<right>"
  ContactMethod method = ContactMethod::kLocalizedBipenalty;
  double gap0_m = 0;
  // Link stiffness ε_s,i and mass penalty ε_m,i = ε_s,i / R_i; i = 0 left link, 1 right link.
  // Node-to-node methods use index 0 for their single link.
  double stiffness_N_m[2] = {0, 0};
  double mass_penalty_kg[2] = {0, 0};
  // Localized bipenalty only: true when the scene gives a penalty parameter explicitly, and the
  // links are then the seed paper's finite ones (contact_localized_finite.cpp); false selects
  // the rigid-link limit ε_s, ε_m → ∞ (contact_localized_bipenalty.cpp).
  bool finite_links = false;
  // Finite links: side i's end follows its half-frame (ε_m,i ≥ its end-node mass: the stiff
  // links) or the half-frame follows the end (compliant links); contact_localized_finite.cpp.
  bool end_follows_frame[2] = {false, false};
  bool tied = false;  // penalty and node-to-node bipenalty: bilateral link (PenaltyParams::tied)
  // Closings after the unloading that come more than this after the last opening start a new
  // meeting (InterfaceState::Unloading): the shorter elastic transit L/c₀ of the two neighbours,
  // at a specimen's face (shorter than its bars) the specimen's (docs/methods.md §3.7).
  double meeting_separation_s = 0;
};

// Mutable state of one interface.
struct InterfaceState {
  bool active = false;
  // Localized bipenalty: frame point (absolute displacement of the contact point, measured
  // like the left bar's end) at τ_frame and its velocity since then; the right end sits at
  // frame − gap0 + offset.
  double frame_u = 0, frame_v = 0, frame_tau = 0;
  double offset = 0;
  // The frame's velocity over the union step that ended at frame_tau (frame_v is the one after
  // it): a tied end's discrete kinetic energy there is ½ m_b v_before v_after
  // (solver/recorders.cpp).
  double frame_v_before = 0;
  // Finite links (contact_localized_finite.cpp): link i's extension d_i = u_f − (end i) at
  // link_tau[i] and its rate over side i's step: its next instant if its end follows the frame
  // (the link is integrated), its last one if not (d is measured).
  double link_d[2] = {0, 0}, link_v[2] = {0, 0}, link_tau[2] = {0, 0};
  // Results of the last solve.
  double force_N = 0;       // compression positive
  double peak_force_N = 0;  // the largest force_N so far (scheduler.cpp, book_solve)
  double gap_m = 0;         // total gap g
  double energy_J = 0;      // potential + penalty kinetic energy held by the links
  // An end segment on this tie's clock (solver/end_segment.hpp): its kinetic and strain energy at
  // the last solve, recorded with the interface (it steps at the interface's instants).
  double segment_kinetic_J = 0, segment_strain_J = 0;
  long activations = 0, releases = 0;

  // What follows the interface's unloading, its first release after its loading peak (the
  // largest force so far: a larger one later starts the count again), booked by every solve
  // (book_unloading): the closings after it, the meetings among them (closings after the faces
  // were open longer than the model's meeting separation) and the largest force after it
  // (summary.json interfaces[], docs/methods.md §3.7).
  struct Unloading {
    double release_s = std::numeric_limits<double>::quiet_NaN();  // NaN: not unloaded yet
    long closings = 0, meetings = 0;
    double largest_force_N = 0;
    double last_release_s = std::numeric_limits<double>::quiet_NaN();
  } unloading;
  // activations and releases at the last solve booked: a solve may close and open at once
  long booked_activations = 0, booked_releases = 0;

  // A localized interface closes at τ: its frame starts at the left end's position u with the
  // velocity v, and the remaining gap (< |ġ|Δt, or a penetration ≤ |ġ|Δt if the contact was
  // missed by a neighbour's step) is kept as the rest offset: no node is moved, no energy is
  // created (docs/methods.md §3.2).
  void close_frame(double u, double v, double tau) {
    active = true;
    ++activations;
    frame_u = u;
    frame_v = v;
    frame_tau = tau;
    offset = gap_m;
  }
};

// Contact predicted one step ahead, so that no penetration is ever created: an open interface
// closes at τ when its ends do not separate (ġ = v₂ − v₁ ≤ 0) and would meet before the next
// instant, g + ġΔ ≤ 0. Ends that separate stay open whatever the gap: a release leaves the rest
// offset's penetration (≤ |ġ|Δt), and closing on it would merge separating ends by a tensile
// impulse.
inline bool closes_within(double gap_m, double v_left, double v_right, double step_s) {
  const double rate = v_right - v_left;
  return rate <= 0 && gap_m + rate * step_s <= 0;
}

// What a solve returns: forces to add to the stepping end nodes, velocity jumps of a
// momentum-consistent activation (both ends, absolute), and the energy it dissipated.
struct ContactResult {
  double force_left_N = 0, force_right_N = 0;
  double dv_left = 0, dv_right = 0;  // velocity jumps applied before the forces
  double dissipated_J = 0;
};

// Books a solve of the interface at τ in state.unloading; called before the state's peak force is
// updated by the solve's force.
void book_unloading(const InterfaceModel& model, InterfaceState& state, double tau);

InterfaceModel make_interface_model(std::string name, ContactMethod method,
                                    const PenaltyParams& params, double gap0_m,
                                    const NeighbourInfo& left, const NeighbourInfo& right);
// The interface between bars[k] and bars[k + 1] as every run builds it: method and penalty
// parameters from the scene (per-interface overrides win), derived values from the end elements
// of the discretization. `simulate` builds its chain with it and `validate` prints it.
InterfaceModel interface_model(const Scene& scene, const ChainDiscretization& d, std::size_t k);

// Localized bipenalty in the tied state: where the end node of side `side` (0 left, 1 right)
// must be at τ (absolute displacement), or NaN when the interface is open. The scheduler puts a
// stepping end there before assembling its forces (rule 4 of scheduler.hpp). With finite links
// an end that follows its half-frame sits behind it by the link's extension d_i(τ), on its linear
// path; an end that does not is left to its bar (contact_localized_finite.cpp).
inline double tied_end_position(const InterfaceModel& model, const InterfaceState& state, int side,
                                double tau) {
  const bool rigid_frame =
      model.method == ContactMethod::kLocalizedBipenalty || model.method == ContactMethod::kBonded;
  if (!state.active || !rigid_frame || (model.finite_links && !model.end_follows_frame[side]))
    return std::numeric_limits<double>::quiet_NaN();
  double uf = state.frame_u + (tau - state.frame_tau) * state.frame_v;
  if (model.finite_links)
    uf -= state.link_d[side] - (state.link_tau[side] - tau) * state.link_v[side];
  return side == 0 ? uf : uf - model.gap0_m + state.offset;
}

// Solves the interface at τ. `frame_next_tau` is the next instant at which either neighbour
// will need the interface (localized bipenalty advances its frame on the union of instants).
ContactResult solve_contact(const InterfaceModel& model, InterfaceState& state, EndState left,
                            EndState right, double tau, double frame_next_tau);

ContactResult solve_penalty(const InterfaceModel& model, InterfaceState& state,
                            const EndState& left, const EndState& right);
ContactResult solve_bipenalty(const InterfaceModel& model, InterfaceState& state,
                              const EndState& left, const EndState& right);
ContactResult solve_localized_bipenalty(const InterfaceModel& model, InterfaceState& state,
                                        EndState left, EndState right, double tau,
                                        double frame_next_tau);
ContactResult solve_localized_finite(const InterfaceModel& model, InterfaceState& state,
                                     EndState left, EndState right, double tau,
                                     double frame_next_tau);

}  // namespace shpb
