#pragma once
// Reads one material (docs/scene-format.md `materials`, a specimens/*.json file, or an inline
// object) into a MaterialSpec and validates what a law needs to be well posed: positive density and
// moduli, ν in (−1, 0.5), Johnson–Cook A, B ≥ 0, n in [0, 1], m > 0, T_melt > T_room, c_p > 0, β in
// [0, 1]; bilinear σ_y > 0, 0 ≤ E_t < E; viscoelastic τ_k > 0, at most kMaxArms arms.
#include <filesystem>
#include <string>
#include <vector>

#include "core/json_value.hpp"
#include "model/material.hpp"

namespace shpb {

// `name` is stored in MaterialSpec::name (the key in `materials`, the file, or "inline").
MaterialSpec read_material(const JsonValue& value, const std::string& name);

// The keys of `model`'s own law, besides the keys of every material (input_keys::kMaterial).
const std::vector<std::string>& material_model_keys(MaterialModel model);

// A material file's document; `display` names it in messages, and a key refused in one of its
// objects is refused naming the others it belongs to (input_keys::kMaterialPlaces).
MaterialSpec read_material_document(const nlohmann::json& document, const std::string& display);
// A material file, read as read_material_document.
MaterialSpec read_material_file(const std::filesystem::path& file, const std::string& display);

}  // namespace shpb
