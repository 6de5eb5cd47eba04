#pragma once
// Columns sampled on one time grid: recorded gauges, interface forces, simulated or measured
// pulses. A plain value type, so that analysis reads a simulation's record without the solver.
#include <cstddef>
#include <string>
#include <vector>

namespace shpb {

// Fewer samples cannot resolve a pulse (a rise alone takes several): a simulated record that short
// is warned of, a measured window that short refused.
inline constexpr std::size_t kMinRecordSamples = 16;

// values[c][k] is column c at time_s[k].
struct TimeSeries {
  std::vector<std::string> columns;  // CSV names (units in the names), without time_s
  std::vector<double> time_s;
  std::vector<std::vector<double>> values;

  std::size_t samples() const { return time_s.size(); }
  // The column named `name`, or throws std::out_of_range.
  const std::vector<double>& column(const std::string& name) const;
};

}  // namespace shpb
