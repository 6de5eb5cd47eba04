#pragma once
// The dispersion correction's low-pass cut-off: one rule for `process`, `compare`, `fit` and
// `calibrate`.
#include "dispersion/propagation.hpp"
#include "model/scene.hpp"

namespace shpb {

// The dispersion correction's cut-off on the waveguide `w`, f·a/c0 and in Hz: the scene's
// cutoff_fa_c0, its cutoff in Hz, else the default (docs/scene-format.md, measurement.dispersion).
double cutoff_fa_over_c0(const DispersionSpec& ds, const BarWaveguide& w);
double dispersion_cutoff_Hz(const DispersionSpec& ds, const BarWaveguide& w);
// The scene key that sets it, for messages: measurement.dispersion.cutoff_fa_c0 or .cutoff.
const char* dispersion_cutoff_key(const DispersionSpec& ds);

}  // namespace shpb
