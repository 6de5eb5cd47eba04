// The synthetic campaign's test set-up, shared by the fit's recovery test, the smoothness test of
// the simulated signals and tools/smoothness: a short, coarse Kolsky bar (Ti-6Al-4V bars, 2 mm
// elements) so each simulation takes milliseconds; 150 mm striker (60 µs pulse), gauges 250 mm
// from the specimen (pulses do not overlap).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

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

}  // namespace shpb_test
