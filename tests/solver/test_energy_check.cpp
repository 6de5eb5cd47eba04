// The run's energy check (scheduler.hpp, rule 7): a run called stable has kept its energy. A mode
// at the Nyquist frequency has a negative central-difference kinetic energy ½ m v₋ v₊ that cancels
// its strain energy in the total, and unilateral contacts can cap its growth, so a check of the
// total alone let a blown-up run end "stable" with its energy two orders of magnitude off.
#include <catch2/catch.hpp>
#include <string>

#include "model/scene.hpp"
#include "model/scene_validation.hpp"
#include "solver/simulation.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_solver_test_energy_check {

using namespace shpb;

namespace {
// A stable run stays within ~1e-3 of its energy on such a scene (the same scene with a 1 mm or
// 5 mm striker gap); the run's own warning starts at 1 %.
constexpr double kStableEnergyError = 0.01;

// A 5 mm polycarbonate specimen, 0.074 of the aluminium bars' impedance, between Ø12.7 mm bars; a
// 2 mm striker gap. At its tolerance's meshes (C 0.9999, the specimen's faces on end segments) its
// faces rattle after the unloading, and from ~620 µs its stress grows with an e-fold of ~7 µs.
constexpr const char* kSoftSpecimen = R"({
  "name": "soft specimen",
  "bars": [
    {"name": "striker", "material": "al7075", "length": "250 mm", "diameter": "12.7 mm",
     "velocity": "10 m/s", "gap": "2 mm"},
    {"name": "incident", "material": "al7075", "length": "1500 mm", "diameter": "12.7 mm",
     "gauges": [{"name": "gi", "position": "750 mm"}]},
    {"name": "specimen", "material": "pc", "length": "5 mm", "diameter": "10 mm"},
    {"name": "transmitter", "material": "al7075", "length": "1000 mm", "diameter": "12.7 mm",
     "gauges": [{"name": "gt", "distance_to_specimen": "300 mm"}]}
  ],
  "specimen": "specimen",
  "materials": {
    "al7075": {"model": "elastic", "density": "2810 kg/m3", "youngs_modulus": "71.7 GPa",
               "poisson_ratio": 0.33},
    "pc": {"model": "elastic", "density": "1200 kg/m3", "youngs_modulus": "2.4 GPa",
           "poisson_ratio": 0.37}
  },
  "simulation": {"duration": "1200 us", "sample_rate": "10 MHz"}
})";
}  // namespace

TEST_CASE("a run called stable has kept its energy (a Nyquist mode capped by contacts too)",
          "[solver][energy]") {
  Scene scene = read_scene_text(kSoftSpecimen, "soft-specimen.json");
  resolve_scene(scene);
  const SimulationResult r = simulate(scene);
  INFO("stable " << r.stable << ", energy error " << r.energy_error << ", " << r.failure);
  CHECK((!r.stable || r.energy_error < kStableEnergyError));
}

}  // namespace tests_solver_test_energy_check
