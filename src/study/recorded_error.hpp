#pragma once
// The gauge error as a record at the scene's sample rate can show it (docs/methods.md §1.1, "Gauge
// error model"): the relative L2 norm of the difference to the study's reference
// (study/reference.hpp) after both are smoothed by a Gaussian of one sample interval. The study's
// own norm (gauge_error) compares point samples: a step front (a striker's impact) falls between
// two samples, and the one sample that straddles it counts a difference of up to the whole jump
// whatever the mesh — measured on the striker-on-bar exact solution at 4 x the automatic mesh,
// 2.4 % of its 2.4 % error comes from the 7 samples at the two fronts, and the norm converges at
// order 0.25–0.4 for that reason alone. A recorded front is never sharper than a sample (the
// digitiser's bandwidth, the gauge's length): smoothed by one sample, the same runs converge at
// order 1–2 to the reference, and what is left is the bars' dispersion.
#include "solver/simulation.hpp"
#include "study/reference.hpp"

namespace shpb {

// √(Σ (ε̃ − ε̃_ref)²) / √(Σ ε̃_ref²) over the gauges and the samples of the window, ε̃ the signal
// smoothed by a Gaussian of standard deviation one sample interval (truncated at 4 σ, normalised
// by the weights inside the window at its ends); the reference as recorded: an exact one smoothed
// analytically at its own arrival times, a fine-mesh one on its oversampled grid (reference.hpp).
// `filtered`: the run's gauges were recorded through that Gaussian already (a run with a
// tolerance, model/scene.hpp gauges_filtered), so they are compared as they are.
// NaN where gauge_error() is NaN.
double recorded_gauge_error(const TimeSeries& gauges, const GaugeReference& reference,
                            bool filtered = false);

// Relative L2 difference of two fine-mesh references as recorded (both oversampled and
// smoothed), against b: how far a reference itself is from a finer one.
double recorded_reference_difference(const GaugeReference& a, const GaugeReference& b);

}  // namespace shpb
