#include <cstdio>

#include "app/commands.hpp"

namespace shpb {

int run_process(const ProcessArgs&) {
  std::fprintf(stderr, "error: shpb process: not implemented yet\n");
  return 2;
}

}  // namespace shpb
