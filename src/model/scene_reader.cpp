#include "core/error.hpp"
#include "model/scene.hpp"

namespace shpb {
// STUB: replaced by the foundation work (issue 2).
Scene read_scene(const std::filesystem::path& file) {
  throw input_error(file.string(), "", "", "scene reading not implemented yet");
}
std::optional<std::size_t> Scene::incident_bar() const { return std::nullopt; }
std::optional<std::size_t> Scene::transmitter_bar() const { return std::nullopt; }
std::string_view to_string(ContactMethod m) {
  switch (m) {
    case ContactMethod::kPenalty: return "penalty";
    case ContactMethod::kBipenalty: return "bipenalty";
    case ContactMethod::kLocalizedBipenalty: return "localized-bipenalty";
  }
  return "?";
}
std::string_view to_string(Stepping s) {
  return s == Stepping::kAsynchronous ? "asynchronous" : "global";
}
std::string_view to_string(MaterialModel m) {
  switch (m) {
    case MaterialModel::kElastic: return "elastic";
    case MaterialModel::kBilinear: return "bilinear";
    case MaterialModel::kJohnsonCook: return "johnson-cook";
    case MaterialModel::kViscoelastic: return "viscoelastic";
  }
  return "?";
}
std::optional<ContactMethod> contact_method_from_string(std::string_view s) {
  if (s == "penalty") return ContactMethod::kPenalty;
  if (s == "bipenalty") return ContactMethod::kBipenalty;
  if (s == "localized-bipenalty") return ContactMethod::kLocalizedBipenalty;
  return std::nullopt;
}
std::optional<Stepping> stepping_from_string(std::string_view s) {
  if (s == "asynchronous") return Stepping::kAsynchronous;
  if (s == "global") return Stepping::kGlobal;
  return std::nullopt;
}
}  // namespace shpb
