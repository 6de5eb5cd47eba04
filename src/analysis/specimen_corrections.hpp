#pragma once
// Corrections of the reduced curve for what a uniform-stress specimen model leaves out
// (docs/methods.md §8), the closed forms of model/specimen_response.hpp read backwards:
//   measured = φ σ_flow + Δσ_inertia,   σ_flow = (measured − Δσ_inertia) / φ,
// in true terms (force over the current, volume-conserving area A0/(1 − e)), then written back to
// the engineering stresses. Friction divides each face's stress by φ (the 1-, 2- and 3-wave
// stresses); inertia corrects the 3-wave stress (the mean of the faces'), the 1-wave stress
// (the transmitted face's) and the 2-wave stress (the incident face's), each by its own axial
// term. Applied by process_signals when the scene
// asks for them (measurement.corrections), after the reduction (analysis/reduction.hpp) and before
// the curve's peaks are read.
#include <optional>
#include <string>
#include <vector>

#include "analysis/reduction.hpp"

namespace shpb {

struct SpecimenCorrections {
  std::optional<double> friction;  // Coulomb μ of the faces (Dharan–Hauser factor removed)
  bool inertia = false;            // radial and axial inertia removed (3-, 1- and 2-wave stresses)
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

// The inertia terms at one instant (true stress, compression positive) of a specimen straining
// uniformly, its axial velocity linear from the front face's v1 to the back face's v2 (one
// dimension: ρ Dv/Dt = −∂σ/∂x). The face average exceeds the volume mean by ρ L² (ε̈ − ε̇²)/12; the
// back face lies below the volume mean by ρ L (v̇2/2 + L (ε̈ − ε̇²)/6) (Davies & Hunter 1963's
// ρ L² ε̈/6 for a back face at rest, with the convective term of the linear field) and the front
// face above it by ρ L (v̇1/2 − L (ε̈ − ε̇²)/6) (the mirror image: a front face at rest lies
// ρ L² ε̈/6 below it); and the volume mean exceeds the flow stress by ρ a² (ε̈/8 + ε̇²/16) (radial;
// model/specimen_response.hpp). L and a current, v̇1 and v̇2 the faces' accelerations (toward the
// transmitter).
struct InertiaTerms {
  double axial_acceleration_Pa = 0, axial_convective_Pa = 0;              // face average − mean
  double front_axial_acceleration_Pa = 0, front_axial_convective_Pa = 0;  // front face − mean
  double back_axial_acceleration_Pa = 0, back_axial_convective_Pa = 0;    // back face − mean
  double radial_acceleration_Pa = 0, radial_convective_Pa = 0;            // mean − flow stress
  double radial() const { return radial_acceleration_Pa + radial_convective_Pa; }
  // The 3-wave (face average), 2-wave (front face) and 1-wave (back face) stresses less the flow
  // stress.
  double face_average() const { return axial_acceleration_Pa + axial_convective_Pa + radial(); }
  double front_face() const {
    return front_axial_acceleration_Pa + front_axial_convective_Pa + radial();
  }
  double back_face() const {
    return back_axial_acceleration_Pa + back_axial_convective_Pa + radial();
  }
};
InertiaTerms inertia_terms(const SpecimenProperties& specimen, double engineering_strain,
                           double true_rate_1_s, double true_acceleration_1_s2,
                           double front_face_acceleration_m_s2, double back_face_acceleration_m_s2);

// Corrects curve.stress_3wave_Pa, curve.true_stress_Pa, curve.stress_1wave_Pa and
// curve.stress_2wave_Pa in place (sampled at dt). A term of zero (zero density) leaves a stress
// exactly as it was.
CorrectionReport apply_specimen_corrections(Curve& curve, double dt,
                                            const SpecimenProperties& specimen,
                                            const SpecimenCorrections& corrections);

}  // namespace shpb
