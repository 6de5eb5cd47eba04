#include "analysis/test_processing.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "analysis/reduction.hpp"

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
  o.align = m.align;
  o.primary = m.primary;
  o.rate_window = m.rate_window;
  return o;
}

ProcessedTest process_test(const Scene& scene, const GaugeSignals& signals,
                           const KolskySetup& setup, const ProcessingOptions& options) {
  ProcessedTest t;
  ProcessingResult& r = t.result;
  ProcessingOptions o = options;
  if (scene.measurement)
    t.corrections = o.corrections = {scene.measurement->corrections.friction,
                                     scene.measurement->corrections.inertia};
  const BarSpec& specimen = scene.bars[*scene.specimen];
  o.specimen = {specimen.length_m, specimen.area_m2, specimen.material.density_kg_m3};
  if (options.tension) {
    GaugeSignals negated = signals;
    for (auto& g : negated.strain)
      for (double& x : g) x = -x;
    r = process_signals(negated, setup, o);
  } else {
    r = process_signals(signals, setup, o);
  }
  t.removed = r.corrections_removed;
  // The move to the faces (docs/methods.md §5) and the reduction (§6) know elastic bars and
  // viscoelastic ones (§5.1). A bar with another law (bilinear, Johnson–Cook) is reduced as an
  // elastic bar of its Young's modulus, which holds while it does not yield.
  for (const std::size_t b : {*scene.specimen + 1, *scene.specimen - 1})  // incident first
    if (const MaterialSpec& m = scene.bars[b].material;
        !m.is_elastic() && m.model != MaterialModel::kViscoelastic)
      r.warnings.insert(r.warnings.begin(),
                        "bar \"" + scene.bars[b].name + "\" has a " +
                            std::string(enum_name(kMaterialModelNames, m.model)) +
                            " law: its pulses are moved to the specimen and reduced as in an "
                            "elastic bar of its Young's modulus, which holds only while the bar "
                            "does not yield");
  if (options.tension)
    for (auto* v : {&r.incident, &r.reflected, &r.transmitted})
      for (double& x : *v) x = -x;
  const bool one_wave = options.primary == PrimaryReduction::kOneWave;
  if (options.tension || one_wave) {  // true values of the primary reduction (docs/methods.md §6)
    Curve& c = r.curve;
    true_values(one_wave ? c.strain_1wave : c.strain,
                one_wave ? c.stress_1wave_Pa : c.stress_3wave_Pa, options.tension, c.true_strain,
                c.true_stress_Pa);
  }
  return t;
}

}  // namespace shpb
