#pragma once
// 1D travel times of bar waves along the chain (docs/methods.md §4), each bar at its own c0, time
// zero at the striker's impact (docs/outputs.md (conventions)). The one source of the default
// duration (discretization.hpp), validate's overlap and duration warnings (scene_checks.hpp) and
// compare's extension of the duration, so shpb never warns about a duration it chose itself.
#include <cstddef>
#include <optional>

#include "model/scene.hpp"
#include "model/test_setup.hpp"  // striker_bar

namespace shpb {

// From (bar a, position xa) to (bar b, position xb), a <= b, through every bar in between.
double travel_time_s(const Scene& scene, std::size_t a, double xa, std::size_t b, double xb);

// The longest one-way transit L/c0 of any bar of the chain (0 without bars).
double longest_transit_s(const Scene& scene);

// The striker's pulse length, 2 L/c0.
double striker_pulse_s(const Scene& scene, std::size_t striker);

// When the gauge at `position` on bar `bar` (right of the striker) has seen the pulses of interest
// pass: the incident pulse, and left of the specimen also the pulse reflected from its front face.
double pulses_passed_s(const Scene& scene, std::size_t striker, std::size_t bar, double position);

// The latest of those over every gauge right of the striker; nullopt without a striker or gauges.
std::optional<double> pulses_passed_s(const Scene& scene);

}  // namespace shpb
