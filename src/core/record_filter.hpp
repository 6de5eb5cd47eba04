#pragma once
// The record's Gaussian (docs/methods.md §1.1): what a record at sample interval Δs can resolve,
// a Gaussian of standard deviation Δs. The study's recorded error sees runs and references
// through it; a run with a tolerance records its gauges through it before sampling, as a
// digitiser's anti-alias filter does (solver/recorders.hpp).
#include <span>
#include <vector>

namespace shpb {

// x smoothed by a Gaussian of standard deviation `sigma` samples (truncated at 4 σ, normalised by
// the weights inside the record at its ends), kept every `stride`-th sample from the first (a
// signal recorded at `stride` × the sample rate is smoothed with sigma = stride).
std::vector<double> record_smoothed(std::span<const double> x, int sigma = 1, int stride = 1);

}  // namespace shpb
