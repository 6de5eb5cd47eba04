#include "analysis/reduction.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace shpb {

void true_values(std::span<const double> strain, std::span<const double> stress, bool tension,
                 std::vector<double>& true_strain, std::vector<double>& true_stress) {
  true_strain.resize(strain.size());
  true_stress.resize(strain.size());
  for (std::size_t i = 0; i < strain.size(); ++i) {
    const double e = tension ? -strain[i] : strain[i];  // shortening positive
    true_strain[i] = e < 1 ? -std::log1p(-e) : -std::log(1e-12);
    true_stress[i] = stress[i] * (1 - e);
    if (tension) true_strain[i] = -true_strain[i];
  }
}

std::vector<double> equilibrium_ratio(std::span<const double> front, std::span<const double> back) {
  const std::size_t n = std::min(front.size(), back.size());
  double peak = 0;
  for (std::size_t i = 0; i < n; ++i) peak = std::max(peak, std::abs(front[i] + back[i]));
  const double floor = std::max(kEquilibriumFloor * peak, 1e-300);
  std::vector<double> r(n);
  for (std::size_t i = 0; i < n; ++i)
    r[i] = 2 * std::abs(front[i] - back[i]) / std::max(std::abs(front[i] + back[i]), floor);
  return r;
}

Curve reduce_pulses(std::span<const double> ei, std::span<const double> er,
                    std::span<const double> et, std::span<const double> fi,
                    std::span<const double> fr, std::span<const double> ft, double dt,
                    const BarSide& front, const BarSide& back, const SpecimenGeometry& s) {
  const std::size_t n = ei.size();
  if (er.size() != n || et.size() != n || fi.size() != n || fr.size() != n || ft.size() != n)
    throw std::invalid_argument("reduce_pulses: pulses of different lengths");
  Curve c;
  auto resize = [n](std::vector<double>& v) { v.assign(n, 0.0); };
  for (auto* v : {&c.strain_rate_1_s, &c.strain_rate_1wave_1_s, &c.strain_1wave, &c.strain,
                  &c.force_front_N, &c.force_back_N, &c.velocity_front_m_s, &c.velocity_back_m_s,
                  &c.stress_1wave_Pa, &c.stress_2wave_Pa, &c.stress_3wave_Pa, &c.true_strain,
                  &c.true_stress_Pa, &c.equilibrium_ratio})
    resize(*v);
  // The reflected-pulse strain rate with the incident pulse eliminated by the faces' equilibrium,
  // E_I A_I (ε_I + ε_R) = E_T A_T ε_T: (v1 − v2)/L_s = (2 c_I ε_R + (c_T − k c_I) ε_T)/L_s with
  // k = E_T A_T/(E_I A_I). Identical bars: 2 c0 ε_R / L_s, the textbook form (the second term
  // exactly 0); a magnesium transmitter on steel bars (k 0.23) made that form 10²–10³ × off.
  const double k =
      back.youngs_modulus_Pa * back.area_m2 / (front.youngs_modulus_Pa * front.area_m2);
  const double transmitted_weight = back.c0_m_s - k * front.c0_m_s;
  for (std::size_t i = 0; i < n; ++i) {
    // Tension-positive strains: a right-going wave has particle velocity −c0 ε, a left-going
    // one +c0 ε. Face velocities (to the right) v1 = −c0 (ε_I − ε_R), v2 = −c0 ε_T.
    const double v1 = -front.c0_m_s * (ei[i] - er[i]);
    const double v2 = -back.c0_m_s * et[i];
    c.strain_rate_1_s[i] = (v1 - v2) / s.length_m;  // shortening rate, compression positive
    c.velocity_front_m_s[i] = v1;
    c.velocity_back_m_s[i] = v2;
    c.strain_rate_1wave_1_s[i] =
        (2 * front.c0_m_s * er[i] + transmitted_weight * et[i]) / s.length_m;
    c.force_front_N[i] = -front.youngs_modulus_Pa * front.area_m2 * (fi[i] + fr[i]);
    c.force_back_N[i] = -back.youngs_modulus_Pa * back.area_m2 * ft[i];
    c.stress_1wave_Pa[i] = c.force_back_N[i] / s.area_m2;
    c.stress_2wave_Pa[i] = c.force_front_N[i] / s.area_m2;
    c.stress_3wave_Pa[i] = 0.5 * (c.force_front_N[i] + c.force_back_N[i]) / s.area_m2;
    if (i > 0) {
      c.strain[i] = c.strain[i - 1] + 0.5 * dt * (c.strain_rate_1_s[i] + c.strain_rate_1_s[i - 1]);
      c.strain_1wave[i] = c.strain_1wave[i - 1] +
                          0.5 * dt * (c.strain_rate_1wave_1_s[i] + c.strain_rate_1wave_1_s[i - 1]);
    }
  }
  true_values(c.strain, c.stress_3wave_Pa, false, c.true_strain, c.true_stress_Pa);
  c.equilibrium_ratio = equilibrium_ratio(c.force_front_N, c.force_back_N);
  return c;
}

}  // namespace shpb
