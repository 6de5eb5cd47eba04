#pragma once
// Plausibility checks of a valid scene: things that can be simulated but probably are not what
// the user wants, found from 1D wave travel times (docs/methods.md §4): pulses overlapping at a
// gauge, a duration that ends before the pulses have passed the gauges, nothing moving, measured
// files that are not there. `shpb validate` prints them as warnings; they never stop a run.
#include <string>
#include <vector>

#include "model/scene.hpp"

namespace shpb {

// `duration_s` is the resolved duration (the scene's or the default).
std::vector<std::string> scene_warnings(const Scene& scene, double duration_s);

}  // namespace shpb
