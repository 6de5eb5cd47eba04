#pragma once
// The assembled chain the scheduler runs: bars (set-up + state) and the interfaces between
// neighbours (interface k joins bar k's right end to bar k+1's left end).
#include <vector>

#include "solver/bar.hpp"
#include "solver/contact.hpp"

namespace shpb {

// The end elements of a slow bar stepping on a light, stiff tied neighbour's clock
// (solver/end_segment.hpp, docs/methods.md §3.6).
struct EndSegment {
  std::size_t bar = 0;        // the slow bar that owns the elements
  int end = 0;                // its end: 0 left (interface bar − 1), 1 right (interface bar)
  std::size_t clock_bar = 0;  // the tied neighbour whose instants the segment takes
  std::size_t interface = 0;  // the tie
  int elements = 0;
  // The current instant's joint: its displacement on its path and its segment element's force.
  double joint_w = 0, joint_force_N = 0;
  // The instant the segment's nodes (the joint aside) are at: its clock's pending one, ahead of
  // the slow bar's instants between two of the clock's (finish_segment).
  double nodes_tau = 0;
  // The instant the segment started at: 0 from the start of the run, else the instant a law
  // specimen's face was unloaded (start_release_segments); the slow bar's and the clock's step
  // counts then.
  double from_tau = 0;
  long bar_steps_before = 0, clock_steps_before = 0;
};

struct Chain {
  std::vector<BarModel> bars;
  std::vector<BarState> states;
  std::vector<InterfaceModel> interfaces;
  std::vector<InterfaceState> interface_states;
  std::vector<double> contact_dissipated_J;  // per interface, cumulative
  std::vector<long> final_step;  // per bar: its last instant is at or beyond the end (this phase)
  double end_tau_s = 0;          // τ of the end of the recording (τ = 0: the first contact)
  double max_penetration_m = 0;
  // The largest interpenetration in elements: over the smaller of the interface's two neighbouring
  // elements (a compliant contact between 1 mm bar elements is judged on 1 mm, not on a
  // specimen's).
  double max_penetration_elements = 0;

  bool global_stepping = false;  // every bar takes the same steps (an adaptive one sets them)
  std::vector<EndSegment> segments;
  std::vector<int> interface_segment;  // per interface: its index in segments, or −1
  // End segments at a law specimen's faces that start once the face is unloaded
  // (end_segment.hpp, docs/methods.md §3.7); moved to `segments` then.
  std::vector<EndSegment> release_segments;

  const EndSegment* segment_at(std::size_t interface) const {
    const int k = interface < interface_segment.size() ? interface_segment[interface] : -1;
    return k < 0 ? nullptr : &segments[k];
  }

  // τ of bar i's pending instant: a product within its phase of constant step (scheduler rule 1).
  double bar_tau(std::size_t i) const {
    const BarState& s = states[i];
    return s.phase_tau + static_cast<double>(s.step - s.phase_step) * s.dt;
  }
};

}  // namespace shpb
