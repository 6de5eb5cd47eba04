#pragma once
// Where a series stops being finite: the one check the records, the reduction and the Monte Carlo
// draws make before a value can reach an output (no NaN or infinity is ever written).
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>

namespace shpb {

// The index of the first non-finite value of `v`, v.size() if none. A run's records are hundreds
// of thousands of values, almost always all finite: each block is first checked without a branch
// (a value is non-finite where its exponent bits are all ones, and adding one to the exponent then
// carries into the top bit), and searched value by value only if that finds one.
inline std::size_t first_non_finite(std::span<const double> v) {
  constexpr std::uint64_t kExponent = 0x7ff0000000000000, kExponentOne = 0x0010000000000000;
  constexpr std::size_t kBlock = 512;
  for (std::size_t b = 0; b < v.size(); b += kBlock) {
    const std::size_t e = std::min(v.size(), b + kBlock);
    std::uint64_t carried = 0;
    for (std::size_t k = b; k < e; ++k)
      carried |= (std::bit_cast<std::uint64_t>(v[k]) & kExponent) + kExponentOne;
    if (carried >> 63)
      for (std::size_t k = b; k < e; ++k)
        if (!std::isfinite(v[k])) return k;
  }
  return v.size();
}

inline bool all_finite(std::span<const double> v) { return first_non_finite(v) == v.size(); }

}  // namespace shpb
