#include "solver/bar.hpp"

#include <cmath>

namespace shpb {

BarModel make_bar_model(std::string name, const MaterialSpec& material, double length_m,
                        double area_m2, int elements, double time_step_s, double velocity_m_s) {
  BarModel b;
  b.name = std::move(name);
  b.nodes = elements + 1;
  b.full_nodes = b.nodes;
  b.element_length_m = length_m / elements;
  b.area_m2 = area_m2;
  b.density_kg_m3 = material.density_kg_m3;
  b.youngs_modulus_Pa = material.youngs_modulus_Pa;
  b.wave_speed_m_s = material.wave_speed_m_s();
  b.stiffness_N_m = b.youngs_modulus_Pa * area_m2 / b.element_length_m;
  b.time_step_s = time_step_s;
  b.courant = b.wave_speed_m_s * time_step_s / b.element_length_m;
  b.initial_velocity_m_s = velocity_m_s;
  const double m = b.density_kg_m3 * area_m2 * b.element_length_m;
  b.mass_kg.assign(b.nodes, m);
  b.mass_kg.front() = b.mass_kg.back() = 0.5 * m;
  b.inverse_mass.resize(b.nodes);
  for (int i = 0; i < b.nodes; ++i) b.inverse_mass[i] = 1.0 / b.mass_kg[i];
  b.diameter_m = 2 * std::sqrt(area_m2 / M_PI);
  if (!material.is_elastic()) {
    b.law = make_material_law(material);
    b.volume_change_per_stress = (1 - 2 * material.poisson_ratio) / b.law->max_tangent_modulus_Pa();
  }
  return b;
}

BarState make_bar_state(const BarModel& bar, bool full_model) {
  BarState s;
  s.dt = bar.time_step_s;
  s.w.assign(bar.nodes, 0.0);
  s.v.assign(bar.nodes, 0.0);
  s.force.assign(bar.nodes, 0.0);
  s.stress_Pa.assign(bar.elements(), 0.0);
  if (bar.law) {
    s.strain_next.assign(bar.elements(), 0.0);
    s.law_stress.assign(bar.elements(), 0.0);
    s.axial_force_N.assign(bar.elements(), 0.0);
    s.log_anchor_d.assign(bar.elements(), 0.0);
    s.log_anchor_value.assign(bar.elements(), 0.0);
    s.log_anchor_inverse.assign(bar.elements(), 1.0);
    s.points.resize(bar.elements());
    bar.law->initialize(s.points);
  }
  if (full_model) {
    s.lo = 0;
    s.hi = bar.nodes - 1;
  }
  return s;
}

}  // namespace shpb
