#include "core/time_series.hpp"

#include <stdexcept>

namespace shpb {

const std::vector<double>& TimeSeries::column(const std::string& name) const {
  for (std::size_t c = 0; c < columns.size(); ++c)
    if (columns[c] == name) return values[c];
  throw std::out_of_range("no column " + name);
}

}  // namespace shpb
