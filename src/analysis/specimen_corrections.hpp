#pragma once
// Corrections of the 3-wave curve for what a uniform-stress specimen model leaves out
// (docs/methods.md §8), the closed forms of model/specimen_response.hpp read backwards:
//   measured = φ σ_flow + Δσ_inertia,   σ_flow = (measured − Δσ_inertia) / φ,
// in true terms (force over the current, volume-conserving area A0/(1 − e)), then written back to
// the engineering 3-wave stress. Friction divides each face's stress by φ (the 1- and 2-wave
// stresses too); inertia corrects the 3-wave stress, the mean of the faces', only. Applied by
// process_signals when the scene asks for them (measurement.corrections), after the reduction
// (analysis/reduction.hpp) and before the curve's peaks are read.
#include <optional>
#include <string>
#include <vector>

#include "analysis/reduction.hpp"

namespace shpb {

struct SpecimenCorrections {
  std::optional<double> friction;  // Coulomb μ of the faces (Dharan–Hauser factor removed)
  bool inertia = false;            // radial and axial inertia removed
};

struct SpecimenProperties {
  double length_m = 0;
  double area_m2 = 0;
  double density_kg_m3 = 0;
};

// What was removed, per term, over the loaded part of the curve (3-wave stress ≥ 20 % of its
// peak): the median and the largest magnitude, in Pa of true stress.
struct RemovedTerm {
  std::string name;
  double median_Pa = 0;
  double max_abs_Pa = 0;
};

struct CorrectionReport {
  std::vector<RemovedTerm> terms;
  double friction_factor_min = 1, friction_factor_max = 1;  // φ over the loaded part
};

// The inertia terms of the 3-wave stress at one instant (true stress, compression positive):
// the face average exceeds the volume mean by ρ L² (ε̈ − ε̇²)/12 (axial; Davies & Hunter 1963 with
// the convective term of a linear axial velocity field), and the volume mean exceeds the flow
// stress by ρ a² (ε̈/8 + ε̇²/16) (radial; model/specimen_response.hpp). L and a current.
struct InertiaTerms {
  double axial_acceleration_Pa = 0, axial_convective_Pa = 0;
  double radial_acceleration_Pa = 0, radial_convective_Pa = 0;
  double total() const {
    return axial_acceleration_Pa + axial_convective_Pa + radial_acceleration_Pa +
           radial_convective_Pa;
  }
};
InertiaTerms inertia_terms(const SpecimenProperties& specimen, double engineering_strain,
                           double true_rate_1_s, double true_acceleration_1_s2);

// Corrects curve.stress_3wave_Pa, curve.true_stress_Pa and (friction) curve.stress_1wave_Pa and
// curve.stress_2wave_Pa in place (sampled at dt).
CorrectionReport apply_specimen_corrections(Curve& curve, double dt,
                                            const SpecimenProperties& specimen,
                                            const SpecimenCorrections& corrections);

}  // namespace shpb
