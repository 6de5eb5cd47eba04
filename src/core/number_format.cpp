#include "core/number_format.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace shpb {
namespace {

// Significant digits of a shortest round-trip text ("1.25e-05" → 3, "1200" → 2).
int significant_digits(std::string_view s) {
  const auto e = s.find_first_of("eE");
  const std::string_view mantissa = s.substr(0, e);
  int digits = 0, trailing_zeros = 0;
  bool started = false;
  for (char c : mantissa) {
    if (c < '0' || c > '9') continue;
    if (c == '0' && !started) continue;
    started = true;
    ++digits;
    trailing_zeros = c == '0' ? trailing_zeros + 1 : 0;
  }
  return digits - (mantissa.find('.') == std::string_view::npos ? trailing_zeros : 0);
}

}  // namespace

std::string format_number(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  if (value == 0) return "0";  // also -0
  // Beyond this many significant digits the value was computed, not typed.
  constexpr int kTypedDigits = 9;
  char buffer[64];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  std::string shortest(buffer, end);
  if (significant_digits(shortest) <= kTypedDigits) return shortest;
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

std::string format_resolved(double value, double resolution, int digits) {
  constexpr int kDoubleDigits = 17;
  if (std::isfinite(value) && value != 0 && std::isfinite(resolution) && resolution > 0) {
    const double needed =
        std::floor(std::log10(std::abs(value))) - std::floor(std::log10(resolution)) + 1;
    digits = static_cast<int>(std::clamp<double>(needed, digits, kDoubleDigits));
  }
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

std::string format_range(double lo, double hi, bool lo_open, bool hi_open) {
  std::string s(lo_open ? "(" : "[");
  s += format_number(lo);
  s += ", ";
  s += format_number(hi);
  s += hi_open ? ")" : "]";
  return s;
}

}  // namespace shpb
