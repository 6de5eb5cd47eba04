#pragma once
// A number of a JSON file (a study plan's parts, summary.json), for every file that writes
// or reads one.
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

namespace shpb {

// JSON has no NaN or infinity: written as null, read back as NaN (a CSV writes both as empty).
inline nlohmann::ordered_json number(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}
inline double number(const nlohmann::json& j) {
  return j.is_null() ? std::numeric_limits<double>::quiet_NaN() : j.get<double>();
}

}  // namespace shpb
