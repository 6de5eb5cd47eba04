#pragma once
// From a time to a sample of an increasing time base (a record's clock, or the faces').
#include <algorithm>
#include <cstddef>
#include <vector>

namespace shpb {

// The first sample at or after `time` (t.size() when there is none).
inline std::size_t index_at(const std::vector<double>& t, double time) {
  const auto it = std::lower_bound(t.begin(), t.end(), time);
  return static_cast<std::size_t>(it - t.begin());
}

// The one rule for times set by hand (the scene's windows): the nearest sample.
inline std::size_t nearest_sample(const std::vector<double>& t, double time) {
  const std::size_t i = index_at(t, time);
  if (i == 0) return 0;
  if (i == t.size()) return t.size() - 1;
  return time - t[i - 1] <= t[i] - time ? i - 1 : i;
}

}  // namespace shpb
