#include "core/units.hpp"

#include <stdexcept>

namespace shpb {
// STUB: replaced by the foundation work (issue 2).
std::string_view to_string(Dimension) { return "quantity"; }
std::string_view si_unit(Dimension) { return ""; }
double parse_quantity(std::string_view text, Dimension) {
  throw std::invalid_argument("unit parsing not implemented yet: " + std::string(text));
}
}  // namespace shpb
