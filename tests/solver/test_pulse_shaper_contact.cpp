// The pulse shaper's contacts (docs/methods.md §3.6): a 3 mm copper disc squeezed between the
// striker and the incident bar is released once when the striker leaves it. Global stepping
// shows that physics; the asynchronous rigid-link coupling at the disc's step ratio (≈ 10 against
// the steel bars) does not yet: its closed-state force is noisy, the disc's contacts chatter and
// the energy drifts (the hidden test below states what a fix must reach).
#include <catch2/catch.hpp>
#include <cmath>
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
// The disc's plastic front and the bilinear law's kink make the gauges first-order in the disc's
// element (each halving halves the difference to a finer run); 1.5 per halving leaves margin for
// the reference's own error.
constexpr double kMinReductionPerHalving = 1.5;

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
// RMS of a − b over their common samples, divided by the peak of |b|.
double relative_rms(const std::vector<double>& a, const std::vector<double>& b) {
  const std::size_t n = std::min(a.size(), b.size());
  double sum = 0, peak = 0;
  for (std::size_t k = 0; k < n; ++k) {
    sum += (a[k] - b[k]) * (a[k] - b[k]);
    peak = std::max(peak, std::abs(b[k]));
  }
  return std::sqrt(sum / n) / peak;
}
}  // namespace

TEST_CASE("At global steps the pulse shaper is released once, without chatter",
          "[solver][shaper]") {
  check_released_once(simulate(pulse_shaper(Stepping::kGlobal)));
}

TEST_CASE("At global steps the gauges converge with the pulse shaper's mesh", "[solver][shaper]") {
  Scene scene = pulse_shaper(Stepping::kGlobal);
  BarSpec& disc = scene.bars[1];
  REQUIRE(disc.name == "shaper");
  auto gauges = [&](int elements) {
    disc.elements = elements;
    const SimulationResult r = simulate(scene);
    REQUIRE(r.stable);
    return r.gauges;
  };
  const TimeSeries reference = gauges(160);
  for (const char* gauge : {"incident", "transmitted"}) {
    double previous = 0;
    for (int elements : {20, 40, 80}) {
      const double e = relative_rms(gauges(elements).column(gauge), reference.column(gauge));
      WARN(gauge << ", disc at " << elements << " elements: RMS difference to 160 elements " << e);
      if (previous > 0) CHECK(previous / e >= kMinReductionPerHalving);
      previous = e;
    }
  }
}

// Known to fail (docs/methods.md §3.6): 46 and 42 closings at the shipped 20-element disc
// (energy 0.03 %), 134 and 151 at 40 elements (0.2 %), thousands at 160 (5 %).
TEST_CASE("At asynchronous steps the pulse shaper is released once, without chatter",
          "[.][solver][shaper][!mayfail]") {
  check_released_once(simulate(pulse_shaper(Stepping::kAsynchronous)));
}

// Until the asynchronous coupling of §3.6 is fixed, the chatter must not pass silently: a run whose
// energy balance is off by more than 1 % says so. A 160-element disc at asynchronous steps drifts
// by about 5 % (measured); if a fix closes the balance, the warning is simply not due.
TEST_CASE("A run whose energy balance is off says so", "[solver][shaper]") {
  Scene scene = pulse_shaper(Stepping::kAsynchronous);
  REQUIRE(scene.bars[1].name == "shaper");
  scene.bars[1].elements = 160;
  const SimulationResult r = simulate(scene);
  REQUIRE(r.stable);
  bool warned = false;
  for (const std::string& w : r.warnings) warned |= w.find("energy balance") != std::string::npos;
  INFO("energy error " << r.energy_error);
  CHECK(warned == (std::abs(r.energy_error) > 0.01));
}
