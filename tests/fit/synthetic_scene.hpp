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

#include "core/units.hpp"
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

// The classic Kolsky bar (experiments/classic-al6061: maraging steel C350 bars 2 m × 19.05 mm,
// 300 mm striker, gauges at mid-length) with a 5 mm × 10 mm specimen of `specimen`.
inline nlohmann::json classic_scene(double velocity_m_s, const std::filesystem::path& specimen,
                                    const std::string& stepping) {
  nlohmann::json s = nlohmann::json::parse(R"({
    "bars": [
      {"name": "striker", "material": "steel", "length": "300 mm", "diameter": "19.05 mm"},
      {"name": "incident", "material": "steel", "length": "2 m", "diameter": "19.05 mm",
       "gauges": [{"name": "incident", "position": "1 m"}]},
      {"name": "specimen", "length": "5 mm", "diameter": "10 mm"},
      {"name": "transmitter", "material": "steel", "length": "2 m", "diameter": "19.05 mm",
       "gauges": [{"name": "transmitted", "position": "1 m"}]}],
    "specimen": "specimen",
    "materials": {"steel": {"model": "elastic", "density": "8080 kg/m3",
                            "youngs_modulus": "200 GPa", "poisson_ratio": 0.29}},
    "simulation": {"duration": "800 us", "sample_rate": "10 MHz"}})");
  s["bars"][0]["velocity"] = std::to_string(velocity_m_s) + " m/s";
  s["bars"][2]["material"] = specimen.string();
  s["simulation"]["stepping"] = stepping;
  return s;
}

// A synthetic campaign's set-up: the bars, the strikers' speeds and the record noise, white or
// coloured (first-order low-pass of white noise with this correlation time in samples, scaled to
// the same standard deviation).
struct SyntheticSetup {
  bool classic_bars = false;
  std::vector<double> velocities = {13.5, 18.5, 28.0};  // ≈ 1000, 2000, 4000 /s on the short bars
  double noise_fraction = 0.01;
  double noise_correlation_samples = 0;  // 0: white
  double start_offset = 0.2;             // A, n started this fraction high, B, C low
};

// The synthetic campaign's truth: the copper's Johnson–Cook A, B, n, C as the file gives them.
constexpr double kTruthA = 90e6, kTruthB = 292e6, kTruthN = 0.31, kTruthC = 0.025;
// 1 % of the peak: the noise of a good strain-gauge record (and of the specification).
constexpr double kNoiseFraction = 0.01;

// Writes into `dir` three simulated tests of `copper` (a Johnson–Cook material file) at about
// 1000, 2000 and 4000 /s with white noise of kNoiseFraction of each gauge's peak (test k drawn
// from seed `seed + k`), their scenes with those signals as the measurement, the start law (the
// file with A, B, n, C 20 % off) and campaign.json freeing A, B, n, C. `rate_filter` is the law's
// strain_rate_filter in the truth and the start alike. Returns campaign.json's path.
// `setup` chooses other bars, speeds and noise. The truth is the file's own law: its free
// parameters are whichever of A, B, n, C it has.
inline std::filesystem::path write_synthetic_campaign(const std::filesystem::path& dir,
                                                      const std::filesystem::path& copper,
                                                      const std::string& rate_filter,
                                                      const std::string& stepping, unsigned seed,
                                                      const SyntheticSetup& setup = {}) {
  namespace fs = std::filesystem;
  using nlohmann::json;
  const std::vector<double>& velocities = setup.velocities;
  const auto scene_of = [&](double v, const fs::path& law) {
    return setup.classic_bars ? classic_scene(v, law, stepping) : synthetic_scene(v, law, stepping);
  };
  json truth = json::parse(std::ifstream(copper));
  truth["strain_rate_filter"] = rate_filter;
  const fs::path truth_law = dir / "truth-law.json";
  std::ofstream(truth_law) << truth.dump(1);
  json campaign = {{"name", "synthetic OFHC copper"}, {"tests", json::array()}};
  for (unsigned k = 0; k < velocities.size(); ++k) {
    const fs::path truth_file = dir / ("truth" + std::to_string(k) + ".json");
    std::ofstream(truth_file) << scene_of(velocities[k], truth_law).dump(1);
    const shpb::Scene scene_truth = shpb::read_scene(truth_file);
    const shpb::SimulationResult sim = shpb::simulate(scene_truth);
    if (!sim.stable) throw std::runtime_error("synthetic truth: " + sim.failure);
    std::mt19937 rng(seed + k);  // seeded: the campaign is reproducible
    std::normal_distribution<double> normal(0.0, 1.0);
    // Coloured: e_i = φ e_(i−1) + √(1 − φ²) w_i keeps the white noise's standard deviation.
    const double phi = setup.noise_correlation_samples > 0
                           ? std::exp(-1.0 / setup.noise_correlation_samples)
                           : 0.0;
    std::vector<std::vector<double>> gauges;
    for (const char* g : {"incident", "transmitted"}) {
      std::vector<double> x = sim.gauges.column(g);
      double peak = 0, e = normal(rng);
      for (double v : x) peak = std::max(peak, std::abs(v));
      for (double& v : x) {
        v += setup.noise_fraction * peak * e;
        e = phi * e + std::sqrt(1 - phi * phi) * normal(rng);
      }
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
    json scene = scene_of(velocities[k], truth_law);
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
  // The start: A and n high, B and C low by start_offset (the truth's values in SI from its file).
  json start = truth;
  const double f = setup.start_offset;
  const auto pa = [&](const char* key) {
    return truth[key].is_string()
               ? shpb::parse_quantity(truth[key].get<std::string>(), shpb::Dimension::kPressure)
               : truth[key].get<double>();
  };
  const double a = pa("A"), b = pa("B"), n = truth["n"], c = truth["C"];
  start["A"] = (1 + f) * a, start["B"] = (1 - f) * b, start["n"] = (1 + f) * n,
  start["C"] = (1 - f) * c;
  std::ofstream(dir / "start.json") << start.dump(1);
  campaign["material"] = "start.json";
  // Bounds far from the truth (SI numbers): [A/5, 3A], [B/5, 3B], n in [0.05, 0.95], [C/25, 8C].
  campaign["free"] = {
      {"A", {a / 5, 3 * a}}, {"B", {b / 5, 3 * b}}, {"n", {0.05, 0.95}}, {"C", {c / 25, 8 * c}}};
  std::ofstream(dir / "campaign.json") << campaign.dump(1);
  return dir / "campaign.json";
}

// The Al 6061-T6 campaign (docs/validation.md, shpb fit, "A second law"): the synthetic set-up's
// three tests of specimens/al6061-t6.json with B 10 % above the file's 114 MPa as the truth,
// started from the file itself; A, B, n free and each test's striker velocity within ±5 %, C fixed.
constexpr double kAlTruthA = 324e6, kAlTruthB = 125.4e6, kAlTruthN = 0.42, kAlFileB = 114e6;
inline std::filesystem::path write_al6061_campaign(const std::filesystem::path& dir,
                                                   const std::filesystem::path& file,
                                                   const std::string& rate_filter,
                                                   const std::string& stepping, unsigned seed) {
  using nlohmann::json;
  json law = json::parse(std::ifstream(file));
  law["B"] = kAlTruthB;
  std::ofstream(dir / "al-truth.json") << law.dump(1);
  SyntheticSetup setup;
  setup.start_offset = 0;
  const std::filesystem::path path =
      write_synthetic_campaign(dir, dir / "al-truth.json", rate_filter, stepping, seed, setup);
  json start = json::parse(std::ifstream(file));
  start["strain_rate_filter"] = rate_filter;
  std::ofstream(dir / "start.json") << start.dump(1);
  json campaign = json::parse(std::ifstream(path));
  // Bounds far from the truth, as the copper campaign's (SI numbers).
  campaign["free"] = {{"A", {kAlTruthA / 5, 3 * kAlTruthA}},
                      {"B", {kAlFileB / 5, 3 * kAlFileB}},
                      {"n", {0.05, 0.95}}};
  campaign["nuisance"] = {{"striker_velocity", "5 %"}};
  std::ofstream(path) << campaign.dump(1);
  return path;
}

}  // namespace shpb_test
