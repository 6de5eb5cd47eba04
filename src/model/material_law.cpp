#include "model/material_law.hpp"

#include <stdexcept>

namespace shpb {
// STUB: replaced by the materials work (issue 4).
std::unique_ptr<MaterialLaw> make_material_law(const MaterialSpec&) {
  throw std::logic_error("material laws not implemented yet");
}
}  // namespace shpb
