#pragma once
// Johnson–Cook parameter sets of Johnson & Cook (1985) Table 1, shared by the material tests.
#include "model/material.hpp"

namespace shpb::test {

// Al 6061-T6, Johnson & Cook (1985) Table 1 / Lesuer (2000): the numbers of
// specimens/al6061-t6.json.
inline MaterialSpec al6061(bool adiabatic) {
  MaterialSpec spec;
  spec.model = MaterialModel::kJohnsonCook;
  spec.density_kg_m3 = 2703;
  spec.youngs_modulus_Pa = 69e9;
  spec.johnson_cook = {.A_Pa = 324e6,
                       .B_Pa = 114e6,
                       .n = 0.42,
                       .C = 0.002,
                       .reference_strain_rate_1_s = 1,
                       .m = 1.34,
                       .room_temperature_K = 294,
                       .melting_temperature_K = 925,
                       .initial_temperature_K = 294,
                       .specific_heat_J_kgK = 885,
                       .taylor_quinney = 0.9,
                       .adiabatic = adiabatic};
  return spec;
}

// OFHC copper, Johnson & Cook (1985) Table 1: strong hardening and rate sensitivity (C = 0.025).
inline MaterialSpec ofhc_copper(bool adiabatic) {
  MaterialSpec spec;
  spec.model = MaterialModel::kJohnsonCook;
  spec.density_kg_m3 = 8960;
  spec.youngs_modulus_Pa = 124e9;
  spec.johnson_cook = {.A_Pa = 90e6,
                       .B_Pa = 292e6,
                       .n = 0.31,
                       .C = 0.025,
                       .reference_strain_rate_1_s = 1,
                       .m = 1.09,
                       .room_temperature_K = 294,
                       .melting_temperature_K = 1356,
                       .initial_temperature_K = 294,
                       .specific_heat_J_kgK = 383,
                       .taylor_quinney = 0.9,
                       .adiabatic = adiabatic};
  return spec;
}

}  // namespace shpb::test
