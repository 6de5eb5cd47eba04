#pragma once
// A material as read from a scene or a specimens/*.json file: plain data, SI units, validated by
// the scene reader. The behaviour (stress update) lives in model/material_law.hpp.
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "core/enum_names.hpp"

namespace shpb {

enum class MaterialModel { kElastic, kBilinear, kJohnsonCook, kViscoelastic };
inline constexpr EnumName<MaterialModel> kMaterialModelNames[] = {
    {"elastic", MaterialModel::kElastic},
    {"bilinear", MaterialModel::kBilinear},
    {"johnson-cook", MaterialModel::kJohnsonCook},
    {"viscoelastic", MaterialModel::kViscoelastic}};

struct BilinearParams {
  double yield_stress_Pa = 0;     // initial yield stress σ_y > 0
  double tangent_modulus_Pa = 0;  // hardening slope of σ–ε after yield, 0 ≤ E_t < E
  bool operator==(const BilinearParams&) const = default;
};

// σ = (A + B ε_p^n)(1 + C ln(ε̇*/ε̇0))(1 − T*^m), T* = (T − T_room)/(T_melt − T_room);
// adiabatic heating ΔT = β ∫σ dε_p / (ρ c_p) (Johnson & Cook 1983).
struct JohnsonCookParams {
  double A_Pa = 0;
  double B_Pa = 0;
  double n = 1;
  double C = 0;
  double reference_strain_rate_1_s = 1;
  double m = 1;
  double room_temperature_K = 293.15;
  double melting_temperature_K = 1000;
  double initial_temperature_K = 293.15;  // test temperature
  // `temperature` given: the test's own; else the test is at room temperature, and stays there when
  // the room temperature is set (set_room_temperature).
  bool temperature_given = false;
  double specific_heat_J_kgK = 900;
  // `specific_heat` given (adiabatic heating needs it: a scene edit that turns the heating on
  // without it is refused, as the file would be).
  bool specific_heat_given = false;
  double taylor_quinney = 0.9;  // β, fraction of plastic work turned into heat
  bool adiabatic = true;
  // τ of a first-order low-pass filter on the rate of the rate term (0: off, the step's rate);
  // not given: the scene's specimen's default, off elsewhere (model/laws/johnson_cook_law.hpp).
  std::optional<double> strain_rate_filter_s;
  bool operator==(const JohnsonCookParams&) const = default;
};

// The room temperature of `p` set to `kelvin`; a test without a `temperature` of its own is at it.
inline void set_room_temperature(JohnsonCookParams& p, double kelvin) {
  p.room_temperature_K = kelvin;
  if (!p.temperature_given) p.initial_temperature_K = kelvin;
}

// Generalized Maxwell (Prony series): E(t) = E_inf + Σ E_k exp(−t/τ_k).
struct MaxwellArm {
  double modulus_Pa = 0;
  double relaxation_time_s = 0;
  bool operator==(const MaxwellArm&) const = default;
};
struct ViscoelasticParams {
  double long_term_modulus_Pa = 0;  // E_inf
  std::vector<MaxwellArm> arms;
  bool operator==(const ViscoelasticParams&) const = default;
};

struct MaterialSpec {
  std::string name;    // name in `materials`, the file it came from, or "inline"
  std::string source;  // citation: paper and table the parameters come from (specimen files)
  MaterialModel model = MaterialModel::kElastic;
  double density_kg_m3 = 0;
  double youngs_modulus_Pa = 0;  // elastic (instantaneous) modulus; for viscoelastic E_inf + ΣE_k
  double poisson_ratio = 0.3;
  BilinearParams bilinear;
  JohnsonCookParams johnson_cook;
  ViscoelasticParams viscoelastic;

  double wave_speed_m_s() const { return std::sqrt(youngs_modulus_Pa / density_kg_m3); }
  bool is_elastic() const { return model == MaterialModel::kElastic; }
  bool operator==(const MaterialSpec&) const = default;
};

// Sets a material's (instantaneous) modulus E0, as a measured, calibrated or drawn wave speed
// √(E0/ρ) does: a viscoelastic law's moduli scale with it, the shape of its relaxation spectrum
// kept, so that E0 stays E∞ + ΣE_k (docs/methods.md §5.1) and the law's every speed moves with c0.
inline void set_instantaneous_modulus(MaterialSpec& m, double modulus_Pa) {
  if (m.model == MaterialModel::kViscoelastic && m.youngs_modulus_Pa > 0) {
    const double scale = modulus_Pa / m.youngs_modulus_Pa;
    m.viscoelastic.long_term_modulus_Pa *= scale;
    for (MaxwellArm& a : m.viscoelastic.arms) a.modulus_Pa *= scale;
  }
  m.youngs_modulus_Pa = modulus_Pa;
}

}  // namespace shpb
