#pragma once
// How a scene is cut into elements and time steps (METHODS.md §1, §7): every bar runs with its own
// time step at a Courant number close to 1; the specimen is meshed finely enough for its transit.
// `shpb validate` prints exactly what `shpb simulate` will use: both call discretize().
#include <vector>

#include "model/scene.hpp"

namespace shpb {

struct BarDiscretization {
  int elements = 0;
  double element_length_m = 0;  // h
  double critical_step_s = 0;   // h / c for lumped linear elements (C = 1)
  double time_step_s = 0;       // this bar's own Δt (asynchronous) or the global one
  double courant = 0;           // c Δt / h
};

struct ChainDiscretization {
  std::vector<BarDiscretization> bars;  // in chain order
  double duration_s = 0;                // resolved (scene's, or the default of DESIGN.md §3)
  double sample_rate_Hz = 0;
  Stepping stepping = Stepping::kAsynchronous;
};

ChainDiscretization discretize(const Scene& scene);

}  // namespace shpb
