// The gauge error as a record sees it (study/recorded_error.hpp, docs/methods.md §1.1) against
// references seen the same way (study/reference.hpp): the exact square pulse smoothed analytically
// at its exact arrival times, the fine-mesh reference recorded at kReferenceOversampling × the
// sample rate. Both must converge with the mesh, where point-sampled references leave a floor.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>

#include "model/scene.hpp"
#include "solver/simulation.hpp"
#include "study/recorded_error.hpp"
#include "study/reference.hpp"
#include "study/sweep.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_study_test_recorded_error {

namespace fs = std::filesystem;

namespace {

const fs::path kExperiments = fs::path(SHPB_SOURCE_DIR) / "experiments";

shpb::SimulationOptions quiet_options() {
  shpb::SimulationOptions options;
  options.record_field = false;
  return options;
}

}  // namespace

TEST_CASE("The striker-on-bar's recorded error converges to the exact solution without a floor",
          "[recorded_error]") {
  // Central differences spread a front over a width that falls with h: the recorded error falls at
  // order 1 or more (docs/methods.md §1.1). Against the step point-sampled at the sample times it
  // stalled near 0.7 % from 2 ×; order 0.8 over 1 → 4 × leaves room for the model's scatter.
  constexpr double kMinimumOrder = 0.8;
  const shpb::Scene scene = shpb::read_scene(kExperiments / "striker-on-bar" / "scene.json");
  const auto exact = shpb::exact_reference(scene);
  REQUIRE(exact);
  REQUIRE(exact->recorded);
  const auto error_at = [&](double factor) {
    const shpb::SimulationResult r =
        shpb::simulate(shpb::scene_at_resolution(scene, factor), quiet_options());
    REQUIRE(r.stable);
    return shpb::recorded_gauge_error(r.gauges, *exact);
  };
  const double e1 = error_at(1), e4 = error_at(4);
  INFO("recorded error at 1 x " << 100 * e1 << " %, at 4 x " << 100 * e4 << " %");
  CHECK(std::log2(e1 / e4) / 2 >= kMinimumOrder);
}

TEST_CASE("The fine-mesh reference, recorded at a multiple of the sample rate, converges",
          "[recorded_error]") {
  // The LANL PMMA mini-Kolsky test: a 10 us pulse, 100 samples, whose fronts are sharper than a
  // sample at 8 x. Seen through the record's Gaussian on the oversampled grid, the 4 x and 8 x
  // references approach the 16 x one at order ≥ 1 (the bars' dispersion, docs/methods.md §1.1);
  // point-sampled at the record's rate they did not (8 x was 1.7 % from 16 x).
  constexpr double kMinimumOrder = 1;
  const shpb::Scene scene =
      shpb::read_scene(kExperiments / "lanl-pmma13-mini-kolsky" / "scene.json");
  const shpb::SimulationOptions options = quiet_options();
  const shpb::GaugeReference r4 = shpb::fine_mesh_reference(scene, 4, options);
  const shpb::GaugeReference r8 = shpb::fine_mesh_reference(scene, 8, options);
  const shpb::GaugeReference r16 = shpb::fine_mesh_reference(scene, 16, options);
  // Every kReferenceOversampling-th sample is the point-sample reference, on the scene's grid.
  REQUIRE(r16.fine.samples() == r16.recorded_fine.samples());
  CHECK(r16.fine.time_s[1] == Approx(1 / scene.simulation.sample_rate_Hz));
  const double d4 = shpb::recorded_reference_difference(r4, r16),
               d8 = shpb::recorded_reference_difference(r8, r16);
  INFO("4 x: " << 100 * d4 << " %, 8 x: " << 100 * d8 << " % from the 16 x reference");
  CHECK(std::log2(d4 / d8) >= kMinimumOrder);
}

TEST_CASE("The study keeps bonded interfaces bonded", "[recorded_error]") {
  // A glued specimen carries tension: swapping it for a contact changes the experiment (the
  // striker pulled away separates and the gauges read zero), so no contact method is compared on
  // it.
  const shpb::Scene scene = shpb::read_scene(kExperiments / "tension-bonded" / "scene.json");
  for (const shpb::ParetoCase& c : shpb::pareto_cases({}, {}, {1.0})) {
    const shpb::Scene s = shpb::scene_for(scene, c);
    for (std::size_t k = 0; k + 1 < s.bars.size(); ++k)
      CHECK(shpb::interface_method(s.contact, k) == shpb::ContactMethod::kBonded);
  }
  const shpb::Scene fine = shpb::fine_reference_scene(scene, shpb::kReferenceResolution);
  for (std::size_t k = 0; k + 1 < fine.bars.size(); ++k)
    CHECK(shpb::interface_method(fine.contact, k) == shpb::ContactMethod::kBonded);
}

}  // namespace tests_study_test_recorded_error
