#pragma once
// 1-, 2- and 3-wave reduction of the pulses at the specimen faces (Kolsky 1949; Gray 2000;
// docs/methods.md §6). Inputs are strains at the faces on one time grid, tension positive (the
// solver's and the gauges' sign); outputs are compression positive, as a compression test is
// reported. Bars may differ (E, A, c0 per side).
#include <span>
#include <vector>

namespace shpb {

struct BarSide {
  double youngs_modulus_Pa = 0;
  double area_m2 = 0;
  double c0_m_s = 0;
};

struct SpecimenGeometry {
  double length_m = 0;
  double area_m2 = 0;
};

struct Curve {
  std::vector<double> strain_rate_1_s;        // 3-wave: (v1 − v2)/L_s
  std::vector<double> strain_rate_1wave_1_s;  // 2 c0 ε_R / L_s (identical bars; reduction.cpp)
  std::vector<double> strain_1wave;   // ∫ 1-wave strain rate dt: the reflected-pulse strain
  std::vector<double> strain;         // ∫ 3-wave strain rate dt (trapezoid), engineering
  std::vector<double> force_front_N;  // P1 = −E A (ε_I + ε_R), compression positive
  std::vector<double> force_back_N;   // P2 = −E A ε_T
  std::vector<double>
      velocity_front_m_s;  // v1 = −c0 (ε_I − ε_R), the incident face's, the same way
  std::vector<double> velocity_back_m_s;  // v2 = −c0 ε_T, the transmitted face's, toward the bar
  std::vector<double> stress_1wave_Pa;    // P2 / A_s
  std::vector<double> stress_2wave_Pa;    // P1 / A_s
  std::vector<double> stress_3wave_Pa;    // (P1 + P2) / (2 A_s)
  std::vector<double> true_strain;        // −ln(1 − ε_e)
  std::vector<double> true_stress_Pa;     // σ_e (1 − ε_e), from the 3-wave stress
  std::vector<double> equilibrium_ratio;  // R = 2|P1 − P2| / |P1 + P2|
};

// Below this fraction of the peak |P1 + P2| the ratio R is meaningless (0/0 before the pulse
// arrives); its denominator is floored there so R stays finite.
inline constexpr double kEquilibriumFloor = 0.02;

// The force-equilibrium ratio R = 2|P1 − P2| / |P1 + P2| of the forces on the specimen's faces
// (the bars' forces, compression positive), the denominator floored at kEquilibriumFloor of its
// peak over the record (docs/methods.md §6). Used by the reduction and by `plan` (§12).
std::vector<double> equilibrium_ratio(std::span<const double> front_N,
                                      std::span<const double> back_N);

// True strain and stress of an engineering pair at constant volume (docs/methods.md §6):
// compression −ln(1 − e) and σ(1 − e), tension ln(1 + e) and σ(1 + e); defined while the specimen
// has length (a compressive e ≥ 1 gives a large finite true strain, refused by `process`).
void true_values(std::span<const double> strain, std::span<const double> stress, bool tension,
                 std::vector<double>& true_strain, std::vector<double>& true_stress);

// `force_incident`/`force_reflected`/`force_transmitted` are the strains to use for forces (the
// same as the kinematic ones unless Tyas–Pope m1·m2 factors were applied).
Curve reduce_pulses(std::span<const double> incident, std::span<const double> reflected,
                    std::span<const double> transmitted, std::span<const double> force_incident,
                    std::span<const double> force_reflected,
                    std::span<const double> force_transmitted, double dt, const BarSide& front,
                    const BarSide& back, const SpecimenGeometry& specimen);

}  // namespace shpb
