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

// The median with an even count's two middle values averaged: the negation of a sample's is its
// negation's (the upper middle value of a record is the lower one of the record turned over: a
// channel wired the other way). Where a record's level decides what is read from it.
inline double symmetric_median(std::vector<double> v) {
  if (v.empty()) return 0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  if (v.size() % 2 == 1) return *mid;
  return 0.5 * (*mid + *std::max_element(v.begin(), mid));
}

}  // namespace shpb
