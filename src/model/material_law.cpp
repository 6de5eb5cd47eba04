#include "model/material_law.hpp"

#include "model/laws/bilinear_law.hpp"
#include "model/laws/elastic_law.hpp"
#include "model/laws/johnson_cook_law.hpp"
#include "model/laws/viscoelastic_law.hpp"

namespace shpb {

// The spec was validated by the scene reader; the laws take its numbers as they are.
std::unique_ptr<MaterialLaw> make_material_law(const MaterialSpec& spec) {
  switch (spec.model) {
    case MaterialModel::kElastic:
      return std::make_unique<ElasticLaw>(spec);
    case MaterialModel::kBilinear:
      return std::make_unique<BilinearLaw>(spec);
    case MaterialModel::kJohnsonCook:
      return std::make_unique<JohnsonCookLaw>(spec);
    case MaterialModel::kViscoelastic:
      return std::make_unique<ViscoelasticLaw>(spec);
  }
  return nullptr;  // unreachable: every MaterialModel is handled above
}

}  // namespace shpb
