#pragma once
// The assembled chain the scheduler runs: bars (set-up + state) and the interfaces between
// neighbours (interface k joins bar k's right end to bar k+1's left end).
#include <vector>

#include "solver/bar.hpp"
#include "solver/contact.hpp"

namespace shpb {

struct Chain {
  std::vector<BarModel> bars;
  std::vector<BarState> states;
  std::vector<InterfaceModel> interfaces;
  std::vector<InterfaceState> interface_states;
  std::vector<double> contact_dissipated_J;  // per interface, cumulative
  std::vector<long> final_step;              // per bar: its last instant is at or beyond the end
  double start_time_s = 0;  // simulation clock at τ = 0 (≤ 0: first contact at t = 0)
  double end_tau_s = 0;     // τ of the end of the recording
  double max_penetration_m = 0;
  // The largest interpenetration in elements: over the smaller of the interface's two neighbouring
  // elements (a compliant contact between 1 mm bar elements is judged on 1 mm, not on a
  // specimen's).
  double max_penetration_elements = 0;

  double bar_tau(std::size_t i) const { return states[i].step * bars[i].time_step_s; }
};

}  // namespace shpb
