#pragma once
// The test a scene describes, resolved once (after calibration and command-line overrides) for
// every command: which bar is the striker, the pulse shapers, the incident bar, the specimen and
// the transmitter bar; how far each gauge's pulse travels to the specimen face it loads; the
// striker's velocity. `validate` prints it, `simulate`, `compare` and `fit` launch the striker
// from it, `process`, `compare` and `fit` move the pulses by it (docs/scene-format.md "Roles").
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "model/scene.hpp"

namespace shpb {

struct TestRoles {
  // The bar launched at the chain: the first moving bar with a bar on its right; in a scene where
  // no bar moves (a measured test), the first bar, if it lies left of the incident bar.
  std::optional<std::size_t> striker;
  std::vector<std::size_t> shapers;  // bars between the striker and the incident bar
  std::optional<std::size_t> incident, specimen, transmitter;  // left of, and right of, it
};

TestRoles test_roles(const Scene& scene);

// The striker of a run: the first moving bar, if its motion loads the bar on its right — it moves
// into it, or pulls it through a bonded interface without a gap (a tension test).
std::optional<std::size_t> striker_bar(const Scene& scene);

// Whether any interface is ever loaded by the initial velocities: two neighbours closing, or a
// bonded pair moving apart. Without one, every bar moves rigidly for ever (an all-zero record).
bool any_interface_loaded(const Scene& scene);

// The distance a pulse travels in the bars from the gauge at `position_m` on bar `bar` to the
// specimen face it loads: to the right end of the last bar before the specimen, or from the left
// end of the first bar after it, through every bar in between. Gaps are not counted: a pulse
// travels in the bars, and a gap has closed before it crosses the interface. nullopt without a
// specimen or for a gauge on the specimen.
std::optional<double> distance_to_specimen_m(const Scene& scene, std::size_t bar,
                                             double position_m);
// The bar lengths between bar `bar` and the specimen (0 for its neighbours): the part of a
// distance to the specimen that is not on the gauge's own bar.
double bars_between_m(const Scene& scene, std::size_t bar);

// Where a gauge given by its distance to the specimen (`distance_to_specimen`) sits on bar `bar`
// (not the specimen), from the bar's left end: the inverse of distance_to_specimen_m, so that a
// bar cut or lengthened keeps the gauge at its distance. `problem`: empty when the distance lies on
// the bar, within [B, B + length] (B: bars_between_m), else what is expected.
struct GaugePlacement {
  double position_m = 0;
  std::string problem;
};
GaugePlacement place_gauge_at_distance(const Scene& scene, std::size_t bar, double distance_m);

// The striker velocity the scene gives for its test: `measurement.striker_velocity`, else the
// striker bar's own speed; nullopt if neither is set. Always a speed (> 0).
std::optional<double> scene_striker_speed_m_s(const Scene& scene);

// The direction the striker is launched in (+1 to the right, −1 to the left): the scene's striker
// velocity's sign; when the striker is at rest, −1 for a `"test": "tension"` measurement (the
// striker pulls), else +1.
double striker_direction(const Scene& scene);

}  // namespace shpb
