#pragma once
// Scenes built in code for the solver tests (no reader needed): elastic bars end to end.
#include <cmath>
#include <numbers>
#include <string>

#include "model/scene.hpp"

namespace shpb::test {

inline MaterialSpec elastic(double E, double rho, std::string name = "elastic") {
  MaterialSpec m;
  m.name = std::move(name);
  m.density_kg_m3 = rho;
  m.youngs_modulus_Pa = E;
  m.poisson_ratio = 0.29;
  return m;
}

inline MaterialSpec steel() { return elastic(200e9, 8000, "steel"); }

inline BarSpec bar(std::string name, MaterialSpec m, double length_m, double area_m2, int elements,
                   double velocity = 0) {
  BarSpec b;
  b.name = std::move(name);
  b.material = std::move(m);
  b.length_m = length_m;
  b.area_m2 = area_m2;
  b.diameter_m = std::sqrt(4 * area_m2 / std::numbers::pi);
  b.elements = elements;
  b.velocity_m_s = velocity;
  return b;
}

inline Scene chain(std::vector<BarSpec> bars, double duration_s, ContactMethod method,
                   Stepping stepping, double sample_rate_Hz = 10e6) {
  Scene s;
  s.name = "test";
  s.file = "test.json";
  s.bars = std::move(bars);
  s.contact.method = method;
  s.simulation.duration_s = duration_s;
  s.simulation.sample_rate_Hz = sample_rate_Hz;
  s.simulation.stepping = stepping;
  return s;
}

}  // namespace shpb::test
