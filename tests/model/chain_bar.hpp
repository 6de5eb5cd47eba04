#pragma once
// A bar of a hand-worked chain for the model's tests (test_test_setup.cpp, test_wave_travel.cpp):
// steel-like, c0 = 5000 m/s (E = 200 GPa, ρ = 8000 kg/m³), 1 cm² cross-section.
#include <string>

#include "model/scene.hpp"

namespace shpb_test {

inline shpb::BarSpec bar(const std::string& name, double length_m, double velocity_m_s = 0) {
  shpb::BarSpec b;
  b.name = name;
  b.material.density_kg_m3 = 8000;
  b.material.youngs_modulus_Pa = 200e9;
  b.length_m = length_m;
  b.area_m2 = 1e-4;
  b.diameter_m = 0.0113;
  b.velocity_m_s = velocity_m_s;
  return b;
}

}  // namespace shpb_test
