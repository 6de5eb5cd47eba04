#pragma once
// The median of a sample: the upper of the two middle values for an even count (always a value of
// the sample, found by selection in linear time); 0 for an empty sample.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace shpb {

inline double median(std::vector<double> v) {
  if (v.empty()) return 0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace shpb
