#pragma once
// How a scene is cut into elements and time steps (docs/methods.md §1, §7): every bar runs with its own
// time step at a Courant number close to 1; the specimen is meshed finely enough for its transit.
// `shpb validate` prints exactly what `shpb simulate` will use: both call discretize().
#include <vector>

#include "model/scene.hpp"

namespace shpb {

// Default Courant number c·Δt/h of every bar. Lumped central difference is exact at C = 1 and
// stable up to it; exactly C = 1 with a bipenalty mass ratio R = R_crit is marginally unstable
// (docs/methods.md §2), and the tied-bar plateau ringing is 0.41 % at 0.999 and 0.86 % at 0.98.
inline constexpr double kDefaultCourant = 0.995;
// Automatic meshes: bars at ~1 mm elements (the classic SHPB resolution, docs/methods.md §1), the
// specimen ten times finer and with at least 50 elements across its length, so its ring-up and
// its own wave transits are resolved.
inline constexpr double kBarElementLength_m = 1e-3;
inline constexpr int kMinBarElements = 20;
inline constexpr double kSpecimenElementLength_m = 1e-4;
inline constexpr int kMinSpecimenElements = 50;

struct BarDiscretization {
  int elements = 0;
  double element_length_m = 0;  // h
  double wave_speed_m_s = 0;    // c = sqrt(E_max/ρ), E_max the largest tangent modulus
  double critical_step_s = 0;   // h / c for lumped linear elements (C = 1)
  double time_step_s = 0;       // this bar's own Δt (asynchronous) or the global one
  double courant = 0;           // c Δt / h
  long steps = 0;               // steps to cover the duration
};

struct ChainDiscretization {
  std::vector<BarDiscretization> bars;  // in chain order
  double duration_s = 0;                // resolved (scene's, or the default of docs/scene-format.md)
  double sample_rate_Hz = 0;
  Stepping stepping = Stepping::kAsynchronous;
  double memory_estimate_bytes = 0;  // peak memory of the run, outputs included (estimate)
  double node_updates_estimate = 0;  // free flight across initial gaps included
};

ChainDiscretization discretize(const Scene& scene);

// docs/scene-format.md default duration: the striker's pulse (2 L_s/c_s long) has travelled from the
// first interface to the last gauge and passed it, plus 10 %. Without gauges: two transits of
// the longest bar.
double default_duration_s(const Scene& scene);

// Time zero is the first contact (docs/outputs.md (conventions)): with initial gaps the run starts
// earlier by the flight time of the first interface to close under the bars' rigid motions.
double first_contact_delay_s(const Scene& scene);

}  // namespace shpb
