// The gauge-error model's frequency integrals are remembered across runs by every number they read
// (model/front_error.hpp, docs/methods.md §1.1): a prediction or a mesh choice made after another
// scene's (made twice: an integral is kept from the second time it is asked for) is the one made
// afresh, bit for bit, whatever changed between them.
#include <catch2/catch.hpp>
#include <filesystem>
#include <optional>
#include <utility>
#include <vector>

#include "model/discretization.hpp"
#include "model/front_error.hpp"
#include "model/mesh_choice.hpp"
#include "model/mesh_error_model.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_model_test_front_error {

using namespace shpb;

namespace {

Scene classic() {
  return read_scene(std::filesystem::path(SHPB_SOURCE_DIR) /
                    "experiments/classic-al6061/scene.json");
}
constexpr std::size_t kStriker = 0, kIncident = 1, kSpecimen = 2, kTransmitter = 3;

// The classic bars meshed by hand at 5 mm elements (a coarse mesh, where dispersion shows), the
// incident bar `stretch` times as long with as many times the elements: the same element length,
// wave speed, step and Courant number, the gauge at the same place in its element — only the
// distances the fronts travel differ.
Scene meshed(double stretch) {
  Scene s = classic();
  s.simulation.courant = 0.995;
  s.bars[kStriker].elements = 60;
  s.bars[kIncident].elements = static_cast<int>(400 * stretch);
  s.bars[kIncident].length_m *= stretch;
  s.bars[kSpecimen].elements = 20;
  s.bars[kTransmitter].elements = 400;
  return s;
}

struct Choice {
  std::vector<int> elements;
  std::optional<double> courant;
  GaugeErrorPrediction p;
};
Choice choose(Scene s) {
  s.simulation.tolerance = kDefaultTolerance;
  const GaugeErrorPrediction p = choose_meshes(s);
  Choice c{{}, s.simulation.courant, p};
  for (const BarSpec& b : s.bars) c.elements.push_back(b.elements);
  return c;
}

// Bit for bit: the remembered integral is the very double integrating it again gives.
void require_same(const Choice& a, const Choice& b) {
  REQUIRE(a.elements == b.elements);
  REQUIRE(a.courant == b.courant);
  REQUIRE(a.p.total == b.p.total);
  REQUIRE(a.p.bars == b.p.bars);
  REQUIRE(a.p.specimen == b.p.specimen);
}

}  // namespace

TEST_CASE(
    "A front's dispersion grows with the distance it travels: a bar twice as long at the same "
    "elements is predicted a larger error, whether its shorter self was predicted before or not",
    "[model][mesh-choice]") {
  const Scene short_bar = meshed(1), long_bar = meshed(2);
  forget_front_errors();
  const double fresh = predict_gauge_error(long_bar, discretize(long_bar)).bars;
  forget_front_errors();
  predict_gauge_error(short_bar, discretize(short_bar));  // kept from the second time
  const double shorter = predict_gauge_error(short_bar, discretize(short_bar)).bars;
  const double remembered = predict_gauge_error(long_bar, discretize(long_bar)).bars;
  REQUIRE(remembered == fresh);
  // The phase error Σ x_i (k_i − ω/c_i) accumulates along the path (docs/methods.md §1.1).
  REQUIRE(remembered > shorter);
}

TEST_CASE(
    "The error the model predicts is relative: a faster striker gets the same predicted error, "
    "whether the slower one's was predicted before or not",
    "[model][mesh-choice]") {
  Scene faster = meshed(1);
  faster.bars[kStriker].velocity_m_s *= 1.3;
  forget_front_errors();
  const GaugeErrorPrediction fresh = predict_gauge_error(faster, discretize(faster));
  forget_front_errors();
  const Scene slower = meshed(1);
  predict_gauge_error(slower, discretize(slower));  // kept from the second time
  const GaugeErrorPrediction before = predict_gauge_error(slower, discretize(slower));
  const GaugeErrorPrediction remembered = predict_gauge_error(faster, discretize(faster));
  REQUIRE(remembered.total == fresh.total);
  // The pulse's amplitude A cancels in e = √(2 I / (A² T_p)) (docs/methods.md §1.1).
  REQUIRE(fresh.total == before.total);
}

TEST_CASE(
    "A mesh choice made after another scene's is the one made afresh: the striker's velocity "
    "changed, a bar's length drawn again",
    "[model][mesh-choice]") {
  const Scene base = classic();
  Scene faster = base, drawn = base;
  faster.bars[kStriker].velocity_m_s *= 1.3;
  drawn.bars[kIncident].length_m += 0.7e-3;  // a length measured 0.7 mm longer
  // The choice for `changed`, made afresh and made after the base scene's.
  const auto fresh_and_remembered = [&](const Scene& changed) {
    forget_front_errors();
    const Choice fresh = choose(changed);
    forget_front_errors();
    choose(base);
    choose(base);  // its integrals kept from the second time they are asked for
    return std::make_pair(fresh, choose(changed));
  };
  const auto [fresh_faster, remembered_faster] = fresh_and_remembered(faster);
  require_same(remembered_faster, fresh_faster);
  // The pulse's amplitude cancels in the relative error: the base scene's choice.
  forget_front_errors();
  require_same(fresh_faster, choose(base));
  const auto [fresh_drawn, remembered_drawn] = fresh_and_remembered(drawn);
  require_same(remembered_drawn, fresh_drawn);
  // The longer bar is predicted on its own paths, not on the base scene's.
  forget_front_errors();
  REQUIRE(fresh_drawn.p.bars != choose(base).p.bars);
}

}  // namespace tests_model_test_front_error
