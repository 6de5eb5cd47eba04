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

// A Johnson–Cook specimen of the solver tests: the strength constants of Al 6061-T6 (Johnson & Cook
// 1985, as in specimens/al6061-t6.json), adiabatic (the default), handbook-rounded E and ρ.
inline MaterialSpec johnson_cook_aluminium() {
  MaterialSpec m = elastic(68.9e9, 2700, "al6061");
  m.model = MaterialModel::kJohnsonCook;
  m.johnson_cook.A_Pa = 324e6;
  m.johnson_cook.B_Pa = 114e6;
  m.johnson_cook.n = 0.42;
  m.johnson_cook.C = 0.002;
  m.johnson_cook.m = 1.34;
  m.johnson_cook.melting_temperature_K = 925;
  return m;
}

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

// A short Kolsky test: a 0.1 m striker (15 m/s against the plastic specimen, else 5 m/s), 0.3 m
// steel bars with a gauge at their middle, a 5 mm specimen in 23 elements, Johnson–Cook
// (johnson_cook_aluminium) or elastic; 200 µs, localized bipenalty.
inline Scene short_kolsky(bool plastic, Stepping stepping) {
  const double A = 2.85e-4, Lb = 0.3;
  const MaterialSpec soft = plastic ? johnson_cook_aluminium() : elastic(70e9, 2700, "al");
  BarSpec striker = bar("striker", steel(), 0.1, A, 100, plastic ? 15.0 : 5.0);
  BarSpec incident = bar("incident", steel(), Lb, A, 300);
  incident.gauges.push_back({"incident", 0.15});
  BarSpec specimen = bar("specimen", soft, 5e-3, 7.85e-5, 23);
  BarSpec transmitter = bar("transmitter", steel(), Lb, A, 300);
  transmitter.gauges.push_back({"transmitted", 0.15});
  Scene scene = chain({striker, incident, specimen, transmitter}, 200e-6,
                      ContactMethod::kLocalizedBipenalty, stepping);
  scene.specimen = 2;
  return scene;
}

}  // namespace shpb::test
