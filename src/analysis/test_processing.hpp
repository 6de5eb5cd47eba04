#pragma once
// A scene's test reduced as `process` reduces it: the options from its measurement block, the
// sign convention of a tension test and the specimen corrections, in one place for `process`
// (one test and campaigns) and `fit`'s curve stage, so that both fit the same curve.
#include "analysis/gauge_signals.hpp"
#include "analysis/processing.hpp"
#include "analysis/specimen_corrections.hpp"
#include "model/scene.hpp"

namespace shpb {

// From the scene's `measurement` (docs/scene-format.md): dispersion, windows, load drop, the test
// (compression or tension); the defaults without one.
ProcessingOptions processing_options(const Scene& scene);

struct ProcessedTest {
  ProcessingResult result;
  SpecimenCorrections corrections;  // as the measurement asks (none without one)
  CorrectionReport removed;         // what the corrections took out of the true stress
};

// process_signals() with the specimen corrections (docs/methods.md §8) the scene asks for, applied
// before the curve's peaks are read. A tension test: the reduction is linear in the strains, so
// negated signals reduce as a compression test whose "compression positive" outputs read tension
// positive; the pulses are negated back and the true values follow the tensile formulas
// (ln(1 + e), σ (1 + e)).
ProcessedTest process_test(const Scene& scene, const GaugeSignals& signals,
                           const KolskySetup& setup, const ProcessingOptions& options);

}  // namespace shpb
