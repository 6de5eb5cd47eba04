#pragma once
// The meshes a tolerance asks for (docs/methods.md §1.1): the cheapest the gauge error model
// (model/mesh_error_model.hpp) predicts meet it, searched over the bars' element transit, the
// specimen's elements and, where the bars can step together, a Courant number near 1.
#include "model/mesh_error_model.hpp"
#include "model/scene.hpp"

namespace shpb {

// With scene.simulation.tolerance set: every bar without an `elements` of its own gets the element
// count of the cheapest mesh (fewest node updates, discretize()) whose predicted error is at most
// 0.65 × the tolerance (the model's scatter; where no mesh is predicted that low — the bars the
// user meshed, or the record's aliasing of sharp fronts, leave no room for the margin — halfway
// between the lowest predicted error and the tolerance) — the bars at one element transit h/c,
// searched from the coarsest down (the error is not monotone in h: aliasing; no coarser than half
// the rise time of a compliant link, whose energy the bars' steps must carry), the specimen
// searched on its own — written into the scene's bars; returns the prediction. Where the scene sets
// no Courant number and its bars can be meshed to step together, C = 0.9999 at whole divisions of
// their common transit is tried too (not where a record with a specimen holds later passes or
// overlapping pulses), and the cheaper choice written into simulation.courant
// (docs/methods.md §1.1). If no affordable mesh meets the tolerance, the most accurate affordable
// one is kept and its prediction returned (resolve_scene() then refuses the tolerance); a scene
// without a striker is left as it is, its prediction NaN.
GaugeErrorPrediction choose_meshes(Scene& scene);
// The same scene asked for again gets the choice made before (remembered by the whole scene, the
// last 16 per process). forget_mesh_choices() forgets them, so the next choice is searched for
// (its frequency integrals stay remembered: forget_front_errors(), model/front_error.hpp).
void forget_mesh_choices();

}  // namespace shpb
