#include <cstdio>

#include "app/commands.hpp"

namespace shpb {

int run_compare(const CompareArgs&) {
  std::fprintf(stderr, "error: shpb compare: not implemented yet\n");
  return 2;
}

}  // namespace shpb
