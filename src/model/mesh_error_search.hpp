#pragma once
// The parts of the gauge error model (model/mesh_error_model.hpp) that the mesh search
// (model/mesh_choice.cpp) uses beyond predict_gauge_error(): a prediction remembered across the
// candidates and bounded against the search's target, the shares it adds up, and when the model
// falls short near C = 1.
#include <cstddef>
#include <limits>
#include <map>
#include <memory>
#include <vector>

#include "model/discretization.hpp"
#include "model/front_error.hpp"
#include "model/mesh_error_model.hpp"
#include "model/scene.hpp"

namespace shpb {

// Whether bar i is the scene's specimen.
inline bool is_specimen(const Scene& scene, std::size_t i) {
  return scene.specimen && *scene.specimen == i;
}

// What a search computes once: the bars' share by bar meshes and steps (the specimen is on no
// pulse's path in the model, so a search over specimen meshes finds the bars' share here instead
// of re-integrating it), and the frequency weights.
struct SearchCache {
  // The sum of the gauges' integrals, or (exact false) a lower bound on it that shows the bars
  // alone miss the search's target.
  struct Bars {
    double sum;
    bool exact;
  };
  std::map<std::vector<double>, Bars> bars;
  std::shared_ptr<const FrequencyWeights> weights;
};

// How much of the prediction to compute: all of it, or a lower bound on the bars' share that is
// enough to tell that a mesh misses `above` (then total is that bound).
struct PredictMode {
  double above = std::numeric_limits<double>::infinity();
  // The bound on the bars' share shows a miss whatever the specimen (a search reuses it for every
  // specimen mesh).
  bool bars_alone = false;
};

// predict()'s result, and whether its bars' share is exact (else the bound PredictMode allows).
struct Predicted : GaugeErrorPrediction {
  bool bars_exact = true;
};

// The prediction for `scene` run on `d`, its integrals remembered in `cache` (none: a cache of its
// own) and computed as far as `mode` asks.
Predicted predict(const Scene& scene, const ChainDiscretization& d, const MeshErrorConstants& k,
                  SearchCache* cache, PredictMode mode = {});

// The predicted error from the bars' share, the specimen's and Σ e² of the other law bars.
double combined_error(double bars, double specimen, double others);

// e_law of a material-law bar meshed as `b` for records of sample interval Δs (the model's
// first-order specimen term, docs/methods.md §1.1).
double law_bar_share(const BarDiscretization& b, double sample_s, const MeshErrorConstants& k);

// Σ e_law² of the material-law bars other than the specimen (pulse shapers).
double other_law_bars(const Scene& scene, const ChainDiscretization& d, double sample_s,
                      const MeshErrorConstants& k);

// Whether some gauge's record weighs what the specimen's faces do to a front more than the
// experiments the model was calibrated on do: it holds a later pass (later_passes(),
// mesh_error_model.cpp), or the reflected pulse overlaps the incident one (overlap_norm_share()).
// Near C = 1, where the bars carry fronts almost exactly, that is what is left, and the model has
// no term for it: measured/predicted 1.15–1.27 on the classic and tension experiments; 1.3–1.8 on a
// 2 ms record of the classic set-up, on 0.5 m bars under its 0.3 m striker, and on the tension
// test with its gauges 0.1 m from the specimen; at C = 0.995 0.80–1.09 on those; without a
// specimen 0.98 (a 2 ms record of the striker-on-bar) (docs/methods.md §1.1).
bool faces_weighed_more(const Scene& scene);

}  // namespace shpb
