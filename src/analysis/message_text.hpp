#pragma once
// Numbers put into the reduction's messages (warnings and errors) through printf formats.
#include <cstdio>
#include <string>

namespace shpb {

// The whole text, however long: a fixed buffer cut the longer warnings mid-word.
inline std::string fmt(const char* format, double a, double b = 0, double c = 0, double d = 0) {
  const int n = std::snprintf(nullptr, 0, format, a, b, c, d);
  if (n <= 0) return {};
  std::string text(static_cast<std::size_t>(n), '\0');
  std::snprintf(text.data(), text.size() + 1, format, a, b, c, d);
  return text;
}

}  // namespace shpb
