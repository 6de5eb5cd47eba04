#include <cstdio>

#include "app/commands.hpp"

namespace shpb {

int run_study(const StudyArgs&) {
  std::fprintf(stderr, "error: shpb study: not implemented yet\n");
  return 2;
}

}  // namespace shpb
