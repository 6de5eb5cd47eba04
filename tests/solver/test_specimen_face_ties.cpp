// The specimen's faces at asynchronous steps (docs/methods.md §3.7): a light, stiff specimen end
// (a 0.2 mm aluminium element) tied by the rigid link to a steel bar stepping ten times slower is
// the pulse shaper's case of §3.6. With the coupling of §3.4 at the faces, the elastic classic
// scene blew up near C = 1 (the tolerance's own choice, C 0.9999, and --courant 0.9995 at the
// automatic meshes: energy × 10³ after a few hundred closings); with the steel's end segments on
// the specimen's clock it keeps its energy at every Courant number a run may take.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <string>

#include "model/scene_validation.hpp"
#include "solver/simulation.hpp"
#include "test_scenes.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_solver_test_specimen_face_ties {

using namespace shpb;

namespace {
// A stable run books its closing losses; what is left is the recorders' interpolation between the
// two clocks (measured 1e-4…4e-3 on this scene): well within the half per cent a gauge can bear.
constexpr double kEnergyTolerance = 5e-3;

Scene elastic_classic() {
  return read_scene(std::filesystem::path(SHPB_SOURCE_DIR) /
                    "tools/bench_scenes/elastic-classic.json");
}

void check_stable(const Scene& scene) {
  const SimulationResult r = simulate(scene);
  INFO(r.failure);
  REQUIRE(r.stable);
  CHECK(r.energy_error < kEnergyTolerance);
  // Both specimen faces are covered by the steel's end segments.
  for (const InterfaceStatistics& i : r.interface_statistics) {
    if (i.name.find("specimen") == std::string::npos) continue;
    INFO(i.name);
    CHECK(i.segment_elements > 0);
  }
}
}  // namespace

TEST_CASE("the elastic classic scene is stable at the Courant number its tolerance chooses",
          "[solver][contact][specimen-faces]") {
  for (const double tolerance : {0.005, 0.035, 0.1}) {
    Scene scene = elastic_classic();
    scene.simulation.tolerance = tolerance;
    resolve_scene(scene);
    INFO("tolerance " << tolerance);
    check_stable(scene);
  }
}

TEST_CASE("the elastic classic scene is stable up to C = 1 at its automatic meshes",
          "[solver][contact][specimen-faces]") {
  for (const double courant : {0.995, 0.9995, 0.9999, 1.0}) {
    Scene scene = elastic_classic();
    scene.simulation.courant = courant;
    INFO("Courant " << courant);
    check_stable(scene);
  }
}

// After a law specimen's faces release, at asynchronous steps the slow bar's end was reset to the
// frame on its own instants (§3.4, rules 4-5) and pinned to the specimen's end: the classic
// experiment's faces closed 1004 / 1043 times after their release, where the global steps at the
// same meshes, one clock at each face, close 53 / 43 times. The count of such a grazing contact is
// no converged quantity (§3.7): it varies with the bars' mesh and step by itself (global steps:
// 53 / 43 at these meshes, 162 / 99 at the default global ones, x 3.1 / 2.3; 529 / 284 at the
// --tolerance 0.5 % ones), so the bound is that spread, not a count (with end segments once the
// faces are unloaded: 112 / 119).
constexpr double kGrazingCountSpread = 4;

TEST_CASE("a law specimen's released faces switch at asynchronous steps as at global ones",
          "[solver][contact][specimen-faces]") {
  Scene scene =
      read_scene(std::filesystem::path(SHPB_SOURCE_DIR) / "experiments/classic-al6061/scene.json");
  resolve_scene(scene);  // the meshes of the default tolerance, as `shpb simulate` runs it
  const SimulationResult async = simulate(scene);
  REQUIRE(async.stable);
  REQUIRE(async.discretization.stepping == Stepping::kAsynchronous);
  // The same meshes, at global steps.
  for (std::size_t i = 0; i < scene.bars.size(); ++i)
    scene.bars[i].elements = async.bars[i].elements;
  scene.simulation.stepping = Stepping::kGlobal;
  const SimulationResult global = simulate(scene);
  REQUIRE(global.stable);
  for (std::size_t k = 1; k < async.interface_statistics.size(); ++k) {
    const InterfaceStatistics &a = async.interface_statistics[k],
                              &g = global.interface_statistics[k];
    INFO(a.name << ": " << a.activations - 1 << " closings after the release asynchronous, "
                << g.activations - 1 << " global");
    // The first closing is the loading's; those after the first release are the rattle.
    CHECK(a.activations - 1 <= kGrazingCountSpread * std::max<long>(1, g.activations - 1));
  }
}

// A law specimen's faces keep the coupling of §3.4 through the loading (end segments once they
// are unloaded only). At the first contact the
// neighbour's tied end moves with the frame over the specimen's many steps between two of its
// own; its energy there is the frame's discrete kinetic energy (§3.4): booked from the end's own
// half-step velocities instead, the PMMA mini-Kolsky showed 0.71-0.83 % at C 0.9995-1 for one
// energy sample at that contact.
TEST_CASE("a viscoelastic specimen keeps its energy balance up to C = 1",
          "[solver][contact][specimen-faces]") {
  for (const double courant : {0.995, 0.9995, 0.9999, 1.0}) {
    Scene scene = read_scene(std::filesystem::path(SHPB_SOURCE_DIR) /
                             "experiments/lanl-pmma13-mini-kolsky/scene.json");
    scene.simulation.courant = courant;
    INFO("Courant " << courant);
    const SimulationResult r = simulate(scene);
    INFO(r.failure);
    REQUIRE(r.stable);
    CHECK(r.energy_error < kEnergyTolerance);
  }
}

// Viscoelastic bars (PMMA, two Maxwell arms) on a soft viscoelastic specimen, a quarter-length
// version of a polymer bar set: the bar ends are the slow sides of the faces' ties and carry a
// material law. The frame moves on the specimen's instants with the ahead bar's end load (§3.4,
// rule 4); taken as the bar's last assembled force, up to a whole bar step old, it did work no
// bar did: after the unloading the faces rattled (116 / 102 closings) and the energy grew by a
// third of the striker's by 0.5 ms (global steps: 6e-8). Carried along the end element's path with
// the instantaneous stiffness, the faces release once, as at global steps.
TEST_CASE("viscoelastic bars keep the energy balance at a soft specimen's faces",
          "[solver][contact][specimen-faces]") {
  const std::string text = R"({"name": "polymer bars", "specimen": "specimen",
    "bars": [
      {"name": "striker", "material": "pmma", "length": 0.25, "diameter": 0.02, "velocity": 2.0},
      {"name": "incident", "material": "pmma", "length": 0.625, "diameter": 0.02,
       "gauges": [{"name": "gi", "distance_to_specimen": 0.325}]},
      {"name": "specimen", "material": "rubbery", "length": 0.01, "diameter": 0.02},
      {"name": "transmitter", "material": "pmma", "length": 0.375, "diameter": 0.02,
       "gauges": [{"name": "gt", "distance_to_specimen": 0.05}]}],
    "materials": {
      "pmma": {"model": "viscoelastic", "density": 1190, "poisson_ratio": 0.35,
               "long_term_modulus": 3e9, "arms": [{"modulus": 1.5e9, "relaxation_time": 1e-3},
                                                  {"modulus": 1.2e9, "relaxation_time": 2e-5}]},
      "rubbery": {"model": "viscoelastic", "density": 1150, "poisson_ratio": 0.4,
                  "long_term_modulus": 1e9, "arms": [{"modulus": 2e9, "relaxation_time": 3e-5}]}},
    "simulation": {"duration": 5e-4, "sample_rate": 1e7}})";
  const Scene scene = read_scene_text(text, "polymer-bars.json");
  REQUIRE(scene.simulation.stepping == Stepping::kAsynchronous);
  const SimulationResult r = simulate(scene);
  INFO(r.failure);
  REQUIRE(r.stable);
  CHECK(r.energy_error < kEnergyTolerance);
}

TEST_CASE("a gauge next to an elastic specimen's bonded face keeps the tie's end segment",
          "[solver][contact][specimen-faces]") {
  // A tension bar, every joint bonded: an aluminium striker pulled at 5 m/s from the incident bar
  // (tension V/(2 c0) for 2 L_s/c0, docs/methods.md §4), a titanium specimen wider than the bars
  // (Z ratio 3.7) and a gauge 3 mm from its face, within the incident bar's end segment. Withheld
  // for that gauge, the face kept the coupling of §3.4 and blew up (strain energy 10 × the
  // initial at 816 us). Exact (1D, elastic): long after the specimen's ring-up (a few of its
  // transits) the faces carry the incident force, so every gauge reads V/(2 c0).
  const double E = 70e9, rho = 2700, c0 = std::sqrt(E / rho), V = 5, Ls = 0.3;
  const double area = 3.1416e-4, strain = V / (2 * c0), pulse = 2 * Ls / c0;
  const MaterialSpec al = test::elastic(E, rho, "aluminium"), ti = test::elastic(114e9, 4430, "ti");
  Scene scene = test::chain(
      {test::bar("striker", al, Ls, area, 175, -V), test::bar("incident", al, 1.2, area, 700),
       test::bar("specimen", ti, 0.004, 2.25 * area, 24),
       test::bar("transmitter", al, 0.6, area, 350)},
      1.4e-3, ContactMethod::kBonded, Stepping::kAsynchronous);
  scene.bars[1].gauges = {{"near", 1.197}, {"incident", 0.6}};
  scene.bars[3].gauges = {{"transmitted", 0.3}};
  scene.specimen = 2;
  SimulationOptions options;
  options.stabilize = false;  // the asynchronous run itself, not a repeat at global steps
  const SimulationResult r = simulate(scene, options);
  INFO(r.failure);
  REQUIRE(r.stable);
  CHECK(r.energy_error < kEnergyTolerance);
  // The plateau's second half at each gauge: the incident pulse, and at the face and behind the
  // specimen the force it hands on (1 - r^(n+1) of it after n transits, r = -0.57: within 10⁻⁴
  // after 15).
  constexpr double kPlateauTolerance = 0.01;  // the bars' dispersion at C = 0.995 on a step front
  const auto mean = [&](const std::string& gauge, double from, double to) {
    const std::vector<double>& t = r.gauges.time_s;
    const std::vector<double>& x = r.gauges.column(gauge);
    double sum = 0;
    int n = 0;
    for (std::size_t k = 0; k < t.size(); ++k)
      if (t[k] >= from && t[k] <= to) sum += x[k], ++n;
    return sum / n;
  };
  const double travel = 0.004 / std::sqrt(114e9 / 4430);  // the specimen's transit
  CHECK(mean("incident", 0.6 / c0 + 0.5 * pulse, 0.6 / c0 + 0.9 * pulse) / strain ==
        Approx(1).margin(kPlateauTolerance));
  CHECK(mean("near", 1.197 / c0 + 0.5 * pulse, 1.197 / c0 + 0.9 * pulse) / strain ==
        Approx(1).margin(kPlateauTolerance));
  const double at_transmitted = 1.2 / c0 + travel + 0.3 / c0;
  CHECK(mean("transmitted", at_transmitted + 0.5 * pulse, at_transmitted + 0.9 * pulse) / strain ==
        Approx(1).margin(kPlateauTolerance));
  // The incident bar's end at the specimen takes its segment, the gauge notwithstanding.
  CHECK(r.interface_statistics[1].segment_elements > 0);
}

}  // namespace tests_solver_test_specimen_face_ties
