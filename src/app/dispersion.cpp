#include <cstdio>

#include "app/commands.hpp"

namespace shpb {

int run_dispersion(const DispersionArgs&) {
  std::fprintf(stderr, "error: shpb dispersion: not implemented yet\n");
  return 2;
}

}  // namespace shpb
