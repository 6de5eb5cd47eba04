#pragma once
// The uncertain inputs of a measured test (measurement.uncertainty, docs/methods.md §10): what
// each one is and how its drawn value changes the test a draw reduces (analysis/uncertainty.hpp).
#include <functional>
#include <vector>

#include "analysis/gauge_signals.hpp"
#include "analysis/kolsky_setup.hpp"
#include "analysis/processing.hpp"
#include "analysis/uncertainty.hpp"
#include "model/scene.hpp"

namespace shpb {

// A draw's perturbed test: the scene (bars, gauges, friction), the options (cut-off, shifts) and
// the factor of each channel's strain (nominal over drawn bridge product).
struct DrawState {
  Scene scene;
  ProcessingOptions options;
  std::vector<double> channel_factor;
};

struct Input {
  UncertainInput info;
  bool positive = true;  // a drawn value ≤ 0 has no meaning (fails the draw)
  std::function<void(double, DrawState&)> apply;
};

// The test's uncertain inputs, in the order they are applied to a draw: the bridge factors, the
// bars, the gauges' positions, then timing, dispersion cut-off and friction.
std::vector<Input> inputs_of(const Scene& scene, const MeasurementSpec& m,
                             const GaugeSignals& signals, const ProcessingOptions& options,
                             const KolskySetup& setup);

}  // namespace shpb
