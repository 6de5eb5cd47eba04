#pragma once
// Closed forms of a Kolsky specimen's response beyond uniform uniaxial stress (docs/methods.md §8),
// one place for the simulator (which adds them to the specimen) and `process` (which divides or
// subtracts them out of the 3-wave curve). Compression positive throughout.
#include <cmath>

namespace shpb {

// Interface friction, Dharan & Hauser (1970), Exp. Mech. 10:370 (slab analysis of a cylinder with
// Coulomb friction μ on both faces and a von Mises material, shear yield σ/√3): the mean axial
// pressure needed for flow is
//   p̄ = σ (1 + μ d / (3√3 L)),
// d and L the current diameter and length. Siebel's form (METHODS §8) has 3 in place of 3√3
// (Tresca); Avitzur's upper bound agrees to first order in μ d/L.
inline double friction_factor_per_aspect(double mu) { return mu / (3 * std::sqrt(3.0)); }
inline double friction_factor(double mu, double diameter_m, double length_m) {
  return 1 + friction_factor_per_aspect(mu) * diameter_m / length_m;
}

// Radial inertia of a plastically flowing (volume-conserving) cylinder of radius a, Gorham (1989),
// J. Phys. D 22:1888, and Forrestal, Wright & Chen (2007), Int. J. Impact Eng. 34:405: with the
// radial velocity ε̇ r/2 of incompressible flow, the mean axial stress exceeds the flow stress by
//   Δσ = ρ a² (ε̈/8 + ε̇²/16),
// ε̇ and ε̈ the true (logarithmic) strain rate and its derivative. This is Davies & Hunter's
// (1963, J. Mech. Phys. Solids 11:155) ρ ν² D² ε̈ / 8 at ν = 1/2 plus the convective ε̇² term of
// the growing radius. The specimen's axial inertia (their L² terms) is carried by the 1D mesh
// itself (and, in `process`, by the faces' own axial terms, analysis/specimen_corrections.hpp).
inline double radial_inertia_stress(double density_kg_m3, double radius_m, double rate_1_s,
                                    double acceleration_1_s2) {
  return density_kg_m3 * radius_m * radius_m * (acceleration_1_s2 / 8 + rate_1_s * rate_1_s / 16);
}

}  // namespace shpb
