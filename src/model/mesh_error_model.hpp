#pragma once
// The gauge error a mesh will give (docs/methods.md §1.1): the relative L2
// error of the gauge signals as recorded (study/recorded_error.hpp) against the study's reference
// (study/reference.hpp), predicted from
// each bar's element transit h/c, its Courant number and the distance the pulse travels in it,
// the pulse's rise time (an interface's `rise_time`, else a step), the sample rate and the
// specimen's elements across its length. With `simulation.tolerance`, choose_meshes()
// (model/mesh_choice.hpp) picks the cheapest meshes the model predicts meet it. Constants measured
// by tools/calibrate_tolerance.cpp.
#include <string>
#include <vector>

#include "model/discretization.hpp"
#include "model/scene.hpp"

namespace shpb {

// The model (docs/methods.md §1.1). A front of jump A reaching a gauge has crossed bars i over
// distances x_i; central differences at Courant number C_i carry frequency ω at the wavenumber
// k_i(ω) = (2/h_i) asin(sin(ω Δt_i/2)/C_i) instead of ω/c_i (none above the mesh's cut-off), so
// the front reaches the gauge through H(ω) = exp(−i Σ x_i (k_i − ω/c_i)). Seen through the record
// (a Gaussian of one sample interval Δs, study/recorded_error.hpp) and the pulse's own rise (an
// exponential of time constant τ), and the gauge's own reading F(ω) (element means interpolated
// between centres), the front's squared error is
//   I = (A²/π) ∫₀^∞ e^{−ω² Δs²} / (1 + ω² τ²) · |F(ω) H(ω) − 1|² / ω² dω,
// and a pulse of duration T_p (2 fronts, norm A² T_p) has e_bars² = front · 2 I / (A² T_p),
// averaged over the gauges (a record that holds the pulses again after a round trip adds their
// fronts and norm; overlapping pulses cancel part of it: docs/methods.md §1.1). The specimen's mesh
// adds e_specimen = specimen · (δ_s/Δs)^order, δ_s = h_s/c_s its element transit, and so does every
// other bar with a material law (a pulse shaper, whose plastic front shapes the pulse: first order
// in its element like the specimen's). The measured constants (tools/calibrate_tolerance.cpp
// re-measures them and prints these values):
struct MeshErrorConstants {
  double front = 1.0;
  double specimen = 0.0;
  double specimen_order = 1.0;
  // 1: the record is a point sample every Δs (gauges.csv without a tolerance), its aliasing of the
  // fronts counted;
  // 0: a record seen through the record's Gaussian before sampling, as the references are.
  double aliasing = 1.0;
};
extern const MeshErrorConstants kMeshErrorConstants;

struct GaugeErrorPrediction {
  double total = 0;        // √(bars² + specimen² + Σ other material-law bars²), a fraction
  double bars = 0;         // the fronts' share
  double specimen = 0;     // the specimen mesh's share
  double rise_time_s = 0;  // τ (0: a step)
  double pulse_s = 0;      // T_p
};

// The prediction for `scene` run on `d` (discretize(scene)). A scene without a striker (no bar
// with a velocity) has no pulse to predict: total = NaN.
GaugeErrorPrediction predict_gauge_error(const Scene& scene, const ChainDiscretization& d,
                                         const MeshErrorConstants& k = kMeshErrorConstants);

}  // namespace shpb
