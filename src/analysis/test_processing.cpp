#include "analysis/test_processing.hpp"

#include <algorithm>
#include <cmath>

namespace shpb {

ProcessingOptions processing_options(const Scene& scene) {
  ProcessingOptions o;
  o.scene_file = scene.file.string();
  if (!scene.measurement) return o;
  const MeasurementSpec& m = *scene.measurement;
  o.dispersion = m.dispersion;
  o.windows = m.windows;
  o.load_drop = m.load_drop.value_or(kDefaultLoadDrop);
  o.tension = m.tension;
  return o;
}

ProcessedTest process_test(const Scene& scene, const GaugeSignals& signals,
                           const KolskySetup& setup, const ProcessingOptions& options) {
  ProcessedTest t;
  ProcessingResult& r = t.result;
  if (options.tension) {
    GaugeSignals negated = signals;
    for (auto& g : negated.strain)
      for (double& x : g) x = -x;
    r = process_signals(negated, setup, options);
  } else {
    r = process_signals(signals, setup, options);
  }
  if (scene.measurement)
    t.corrections = {scene.measurement->corrections.friction,
                     scene.measurement->corrections.inertia};
  const BarSpec& specimen = scene.bars[*scene.specimen];
  t.removed = apply_specimen_corrections(
      r.curve, signals.dt_s, {specimen.length_m, specimen.area_m2, specimen.material.density_kg_m3},
      t.corrections);
  if (t.corrections.friction || t.corrections.inertia)
    r.peak_stress_Pa =
        *std::max_element(r.curve.stress_3wave_Pa.begin(), r.curve.stress_3wave_Pa.end());
  if (options.tension) {
    for (auto* v : {&r.incident, &r.reflected, &r.transmitted})
      for (double& x : *v) x = -x;
    Curve& c = r.curve;
    for (std::size_t i = 0; i < c.strain.size(); ++i) {
      c.true_strain[i] = std::log1p(c.strain[i]);  // elongation: ln(1 + e)
      c.true_stress_Pa[i] = c.stress_3wave_Pa[i] * (1 + c.strain[i]);
    }
  }
  return t;
}

}  // namespace shpb
