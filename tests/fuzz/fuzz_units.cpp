// libFuzzer target: the unit parser (core/units.cpp). The first byte picks the expected dimension,
// the rest is the text. Contract: parse_quantity returns a finite SI value or throws
// std::invalid_argument; anything else (another exception, a crash, UB) is a finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string_view>

#include "core/units.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  constexpr int kDimensions = static_cast<int>(shpb::Dimension::kStiffness) + 1;
  const auto dimension = static_cast<shpb::Dimension>(data[0] % kDimensions);
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    const double value = shpb::parse_quantity(text, dimension);
    if (!std::isfinite(value)) std::abort();  // a non-finite value must be refused
    (void)shpb::to_string(dimension);
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
