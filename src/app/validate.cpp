#include <cstdio>

#include "app/commands.hpp"

namespace shpb {

int run_validate(const ValidateArgs&) {
  std::fprintf(stderr, "error: shpb validate: not implemented yet\n");
  return 2;
}

}  // namespace shpb
