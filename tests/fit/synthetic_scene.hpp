// The synthetic campaign's test set-up, shared by the fit's recovery test, the smoothness test of
// the simulated signals, tools/smoothness and tools/fit_noise_seeds: a short, coarse Kolsky bar
// (Ti-6Al-4V bars, 2 mm elements) so each simulation takes milliseconds; 150 mm striker (60 µs
// pulse), gauges 250 mm from the specimen (pulses do not overlap).
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "model/scene.hpp"
#include "solver/simulation.hpp"

namespace shpb_test {

inline nlohmann::json synthetic_scene(double velocity_m_s, const std::filesystem::path& specimen,
                                      const std::string& stepping) {
  nlohmann::json s = nlohmann::json::parse(R"({
    "bars": [
      {"name": "striker", "material": "ti", "length": "150 mm", "diameter": "9.47 mm",
       "elements": 75},
      {"name": "incident", "material": "ti", "length": "500 mm", "diameter": "9.47 mm",
       "elements": 250, "gauges": [{"name": "incident", "position": "250 mm"}]},
      {"name": "specimen", "length": "4 mm", "diameter": "6.34 mm", "elements": 12},
      {"name": "transmitter", "material": "ti", "length": "500 mm", "diameter": "9.47 mm",
       "elements": 250, "gauges": [{"name": "transmitted", "position": "250 mm"}]}],
    "specimen": "specimen",
    "materials": {"ti": {"model": "elastic", "density": "4416 kg/m3",
                         "youngs_modulus": "109.3 GPa", "poisson_ratio": 0.33}},
    "simulation": {"duration": "230 us", "sample_rate": "10 MHz"}})");
  s["bars"][0]["velocity"] = std::to_string(velocity_m_s) + " m/s";
  s["bars"][2]["material"] = specimen.string();
  s["simulation"]["stepping"] = stepping;
  return s;
}

// The synthetic campaign's truth: the copper's Johnson–Cook A, B, n, C as the file gives them.
constexpr double kTruthA = 90e6, kTruthB = 292e6, kTruthN = 0.31, kTruthC = 0.025;
// 1 % of the peak: the noise of a good strain-gauge record (and of the specification).
constexpr double kNoiseFraction = 0.01;

// Writes into `dir` three simulated tests of `copper` (a Johnson–Cook material file) at about
// 1000, 2000 and 4000 /s with white noise of kNoiseFraction of each gauge's peak (test k drawn
// from seed `seed + k`), their scenes with those signals as the measurement, the start law (the
// file with A, B, n, C 20 % off) and campaign.json freeing A, B, n, C. `rate_filter` is the law's
// strain_rate_filter in the truth and the start alike. Returns campaign.json's path.
inline std::filesystem::path write_synthetic_campaign(const std::filesystem::path& dir,
                                                      const std::filesystem::path& copper,
                                                      const std::string& rate_filter,
                                                      const std::string& stepping, unsigned seed) {
  namespace fs = std::filesystem;
  using nlohmann::json;
  const double velocities[] = {13.5, 18.5, 28.0};  // ≈ 1000, 2000, 4000 /s in this set-up
  json truth = json::parse(std::ifstream(copper));
  truth["strain_rate_filter"] = rate_filter;
  const fs::path truth_law = dir / "truth-law.json";
  std::ofstream(truth_law) << truth.dump(1);
  json campaign = {{"name", "synthetic OFHC copper"}, {"tests", json::array()}};
  for (unsigned k = 0; k < 3; ++k) {
    const fs::path truth_file = dir / ("truth" + std::to_string(k) + ".json");
    std::ofstream(truth_file) << synthetic_scene(velocities[k], truth_law, stepping).dump(1);
    const shpb::Scene scene_truth = shpb::read_scene(truth_file);
    const shpb::SimulationResult sim = shpb::simulate(scene_truth);
    if (!sim.stable) throw std::runtime_error("synthetic truth: " + sim.failure);
    std::mt19937 rng(seed + k);  // seeded: the campaign is reproducible
    std::normal_distribution<double> normal(0.0, 1.0);
    std::vector<std::vector<double>> gauges;
    for (const char* g : {"incident", "transmitted"}) {
      std::vector<double> x = sim.gauges.column(g);
      double peak = 0;
      for (double v : x) peak = std::max(peak, std::abs(v));
      for (double& v : x) v += kNoiseFraction * peak * normal(rng);
      gauges.push_back(x);
    }
    const std::string csv = "measured" + std::to_string(k) + ".csv";
    {
      std::ofstream out(dir / csv);
      out.precision(17);
      out << "time_s,incident,transmitted\n";
      for (std::size_t i = 0; i < sim.gauges.samples(); ++i)
        out << sim.gauges.time_s[i] << ',' << gauges[0][i] << ',' << gauges[1][i] << '\n';
    }
    json scene = synthetic_scene(velocities[k], truth_law, stepping);
    scene["measurement"] = {
        {"file", csv},
        {"format", "csv"},
        {"time", {{"column", "time_s"}, {"unit", "s"}}},
        {"channels",
         {{{"gauge", "incident"}, {"column", "incident"}, {"unit", "strain"}},
          {{"gauge", "transmitted"}, {"column", "transmitted"}, {"unit", "strain"}}}},
        {"dispersion", {{"correction", "none"}}},  // 1D signals: nothing to undo or add
        {"striker_velocity", std::to_string(velocities[k]) + " m/s"}};
    // Built by append: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string.
    std::string name = "scene", label = "v";
    name += std::to_string(k);
    name += ".json";
    label += std::to_string(k);
    std::ofstream(dir / name) << scene.dump(1);
    campaign["tests"].push_back({{"scene", name}, {"name", label}});
  }
  json start = truth;
  start["A"] = 1.2 * kTruthA, start["B"] = 0.8 * kTruthB, start["n"] = 1.2 * kTruthN,
  start["C"] = 0.8 * kTruthC;
  std::ofstream(dir / "start.json") << start.dump(1);
  campaign["material"] = "start.json";
  campaign["free"] = {{"A", {"20 MPa", "300 MPa"}},
                      {"B", {"50 MPa", "800 MPa"}},
                      {"n", {0.05, 0.95}},
                      {"C", {0.001, 0.2}}};
  std::ofstream(dir / "campaign.json") << campaign.dump(1);
  return dir / "campaign.json";
}

}  // namespace shpb_test
