#pragma once
// The parameters of a material law by the names its material file uses (docs/scene-format.md):
// what `shpb fit` may free, read and set on a MaterialSpec, write back into a material document,
// and the law's flow stress for the curve stage (docs/methods.md §9).
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/units.hpp"
#include "model/material.hpp"

namespace shpb {

// Johnson–Cook: A, B, n, C, m, youngs_modulus; bilinear: yield_stress, tangent_modulus,
// youngs_modulus; viscoelastic: long_term_modulus, arms[k].modulus, arms[k].relaxation_time;
// elastic: youngs_modulus.
std::vector<std::string> law_parameter_names(const MaterialSpec& m);
Dimension law_parameter_dimension(const std::string& name);
double law_parameter(const MaterialSpec& m, const std::string& name);
// Sets a parameter (and what derives from it: a viscoelastic E = E_inf + ΣE_k).
void set_law_parameter(MaterialSpec& m, const std::string& name, double value);
// The member of a material document that holds the parameter `name` (created when absent).
nlohmann::json& law_parameter_member(nlohmann::json& document, const std::string& name);
// Writes the value into a material document as its file would say it ("95.2 MPa", 0.31).
void set_law_parameter(nlohmann::json& document, const std::string& name, double value);

// The flow stress of a plastic law at true plastic strain, strain rate and temperature
// (bilinear: σ_y + H ε_p with H = E E_t/(E − E_t)); nullopt for laws without one.
std::optional<double> law_flow_stress(const MaterialSpec& m, double plastic_strain,
                                      double strain_rate_1_s, double temperature_K);

// The true stress (positive) a specimen of law `m` carries along a uniaxial true-strain history
// (`strain[i]` ≥ 0 at `time_s[i]`, compression unless `tension`), driven from rest at the first
// sample: the law's own response, what a law without a flow stress (viscoelastic: a hereditary
// integral of the whole history, docs/methods.md §8) is compared by.
std::vector<double> law_stress_along(const MaterialSpec& m, const std::vector<double>& time_s,
                                     const std::vector<double>& strain, bool tension);

// A value as a material file writes it: "95.2 MPa", "12 us", or a plain number.
nlohmann::json law_parameter_json(const std::string& name, double value);

}  // namespace shpb
