#pragma once
// How a scene is cut into elements and time steps (docs/methods.md §1, §7): every bar runs with its
// own time step at a Courant number close to 1; the specimen is meshed finely enough for its
// transit. `shpb validate` prints exactly what `shpb simulate` will use: both call discretize().
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

// Finite strain (docs/methods.md §8): a shortening element's critical step h/c shrinks with its
// length (λ h0; the wave speed follows the elastic modulus, the lumped mass stays ρ A0 h0). The
// step of a material-law bar is planned once, bounded from the largest compressive engineering
// strain the run may reach: Δt = C (1 − e_max) h0 / c (the scheduler's steps are fixed per bar).
// The default e_max = 0.5 covers Kolsky specimens (20–40 %) and most pulse shapers at twice the
// specimen's step count; `simulation.max_strain` changes it, and a run whose elements shorten
// past it stops as failed (exit 3) saying so, where the scene set it (else simulate() plans the
// run again for more, solver/simulation.cpp). The geometric stiffening of a stressed element,
// 1 + |τ|/E, raises the effective Courant number by |τ|/(2E) < 0.5 % for |τ|/E < 1 %, which the
// default C = 0.995 leaves room for (the adaptive step takes it beyond, step_control.hpp). Face
// friction acts at the faces and leaves the elements' stiffness and the step alone.
//
// An elastic specimen steps at no more than kElasticSpecimenCourant, whatever the bars take
// (docs/methods.md §3.7): its faces close and open on its clock, and each closing of two ends that
// step together creates the discrete energy ⅛ μ Δt² (a₁ − a₂)² (the merged ends' share of
// ½ m v₋ v₊), which a top mode holds at an amplitude 1/(1 − C²) times its energy's: 100 at C 0.995,
// 10 at 0.95. Measured: a soft (polycarbonate) specimen between aluminium bars at the tolerance's
// C 0.9999 grew without bound in 2 of 25 moduli and gaps, none at 0.995 or 0.95; a stiff
// tungsten-carbide specimen on titanium bars at 0.995 kept an energy error of 0.89 % and 1900
// closings per face, 0.021 % and 140 at 0.95. A law specimen steps lower still (1 − e_max).
inline constexpr double kElasticSpecimenCourant = 0.95;
inline constexpr double kDefaultMaxStrain = 0.5;
// Bar `bar`'s Courant number on its reference element length when the scene's is `courant`.
double bar_courant(const Scene& scene, std::size_t bar, double courant);

struct BarDiscretization {
  int elements = 0;
  double element_length_m = 0;  // h
  double wave_speed_m_s = 0;    // c = sqrt(E_max/ρ), E_max the largest tangent modulus
  double critical_step_s = 0;   // h / c for lumped linear elements (C = 1), reference length h
  double time_step_s = 0;       // this bar's own Δt (asynchronous) or the global one
  double courant = 0;           // c Δt / h
  long steps = 0;               // steps to cover the duration
  double run_steps = 0;         // steps over the run with its free flight (the cost estimate)
};

struct ChainDiscretization {
  std::vector<BarDiscretization> bars;  // in chain order
  double duration_s = 0;  // resolved (scene's, or the default of docs/scene-format.md)
  double sample_rate_Hz = 0;
  Stepping stepping = Stepping::kAsynchronous;
  double memory_estimate_bytes = 0;  // peak memory of the run, outputs included (estimate)
  double node_updates_estimate = 0;  // free flight across initial gaps included
  double record_bytes_estimate = 0;  // the recorded series' share of the memory
};

// The scene's discretization; refuses (InputError naming the entry that drives the cost) a run
// beyond this machine's budget of memory and node updates.
ChainDiscretization discretize(const Scene& scene);

// Whether a discretization's estimates are within that budget.
bool affordable(const ChainDiscretization& d);

// For a search over meshes (model/mesh_choice.cpp), which prices many candidates:
// discretize() for a scene of `duration_s` whose element counts fit an int, without the refusal
// (see affordable()); and the estimates of `d` with bar i discretized as `b` instead — a plan of
// the chain at asynchronous steps, where each bar's step and cost are its own.
ChainDiscretization plan_chain(const Scene& scene, double duration_s);
struct ChainEstimates {
  double memory_bytes = 0, node_updates = 0;
  bool affordable = false;
};
ChainEstimates estimates_with_bar(const ChainDiscretization& d, std::size_t i,
                                  const BarDiscretization& b);

// docs/scene-format.md default duration: every gauge has seen the pulses of interest pass (the
// incident pulse, and left of the specimen the reflected one; model/wave_travel.hpp), plus 10 %.
// Without a striker or gauges: two transits of the longest bar.
double default_duration_s(const Scene& scene);
// The run's duration: the scene's simulation.duration, else default_duration_s.
double run_duration_s(const Scene& scene);

// Time zero is the first contact (docs/outputs.md (conventions)): with initial gaps the run starts
// earlier by the flight time of the first interface to close under the bars' rigid motions.
double first_contact_delay_s(const Scene& scene);

}  // namespace shpb
