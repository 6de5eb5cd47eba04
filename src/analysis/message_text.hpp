#pragma once
// Numbers put into the reduction's messages (warnings and errors) through printf formats.
#include <cstdio>
#include <string>

namespace shpb {

inline std::string fmt(const char* format, double a, double b = 0, double c = 0, double d = 0) {
  char buf[400];
  std::snprintf(buf, sizeof buf, format, a, b, c, d);
  return buf;
}

}  // namespace shpb
