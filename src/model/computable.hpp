#pragma once
// Whether the quantities a run derives from a scene can be computed with in double precision:
// every value the reader accepts on its own may still combine with others into a wave speed, an
// impedance, an element mass or a penalty stiffness that overflows to infinity or underflows to 0
// (a bar 1e300 mm across, a rise time of 1e-300 us), and the run would then fail at its first
// step. Checked once, by validate_scene(), for every command that runs or describes a scene.
#include "model/discretization.hpp"
#include "model/scene.hpp"

namespace shpb {

// The rule (docs/scene-format.md "Values the solver can compute with"): each derived quantity,
// in SI units, is a normal double, kSmallestComputable ≤ |q| ≤ kLargestComputable. A zero, an
// infinity or a subnormal (its precision lost) is not computable.
inline constexpr double kSmallestComputable = 2.2250738585072014e-308;  // DBL_MIN
inline constexpr double kLargestComputable = 1.7976931348623157e308;    // DBL_MAX

// Throws InputError (exit 2) naming the input that made a derived quantity of the run
// discretized as `d` not computable: of the inputs it is derived from, the one farthest from 1 in
// SI units (orders of magnitude), which is the one hundreds of orders out when a double overflows.
void check_computable(const Scene& scene, const ChainDiscretization& d);

// The same rule for what a reduction derives from the specimen and the bars either side of it
// (docs/methods.md §6): their cross-section areas, the bars' wave speeds and impedances, the stress
// of a unit strain at a bar's gauge on the specimen, E A_bar / A_specimen, and the strain rate of
// a unit strain, c0 / L_specimen. Checked by every command that reduces a test (process, compare,
// fit, and validate for process), which need no discretization: the specimen may have no material.
void check_reduction_computable(const Scene& scene);

}  // namespace shpb
