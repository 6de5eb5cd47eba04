#include <cstdio>

#include "app/commands.hpp"

namespace shpb {

int run_simulate(const SimulateArgs&) {
  std::fprintf(stderr, "error: shpb simulate: not implemented yet\n");
  return 2;
}

}  // namespace shpb
