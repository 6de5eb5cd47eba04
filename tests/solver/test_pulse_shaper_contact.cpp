// The pulse shaper's contacts (docs/methods.md §3.6): a 3 mm copper disc squeezed between the
// striker and the incident bar is released once when the striker leaves it. Global stepping
// shows that physics; the asynchronous rigid-link coupling at the disc's step ratio (≈ 10 against
// the steel bars) does not yet: its closed-state force is noisy, the disc's contacts chatter and
// the energy drifts (the hidden test below states what a fix must reach).
#include <catch2/catch.hpp>
#include <filesystem>

#include "solver/simulation.hpp"

using namespace shpb;

namespace {
// The disc may bounce a few times as the striker leaves it (its elastic spring-back of ~1 µm
// against bars separating at ~1 m/s), not once per step: the first closing plus a few bounces.
constexpr long kMaxClosings = 5;
// Closing losses are booked as dissipation; a stable run keeps the rest to well within 0.1 % of
// the striker's energy (the recorders' interpolation).
constexpr double kEnergyTolerance = 1e-3;

Scene pulse_shaper(Stepping stepping) {
  Scene scene = read_scene(std::filesystem::path(SHPB_SOURCE_DIR) / "experiments" / "pulse-shaper" /
                           "scene.json");
  scene.simulation.stepping = stepping;
  return scene;
}

void check_released_once(const SimulationResult& result) {
  REQUIRE(result.stable);
  CHECK(result.energy_error < kEnergyTolerance);
  for (const InterfaceStatistics& i : result.interface_statistics) {
    if (i.name.find("shaper") == std::string::npos) continue;
    INFO(i.name << ": " << i.activations << " closings, " << i.releases << " releases");
    CHECK(i.activations <= kMaxClosings);
    CHECK(i.releases <= i.activations);
  }
}
}  // namespace

TEST_CASE("At global steps the pulse shaper is released once, without chatter",
          "[solver][shaper]") {
  check_released_once(simulate(pulse_shaper(Stepping::kGlobal)));
}

// Known to fail (docs/methods.md §3.6): 134 and 94 closings, and the energy drifts by 0.03 %
// at the shipped 20-element disc and by 32 % at 40 elements.
TEST_CASE("At asynchronous steps the pulse shaper is released once, without chatter",
          "[.][solver][shaper][!mayfail]") {
  check_released_once(simulate(pulse_shaper(Stepping::kAsynchronous)));
}
