#include <cstdio>

#include "app/commands.hpp"

namespace shpb {

int run_report(const ReportArgs&) {
  std::fprintf(stderr, "error: shpb report: not implemented yet\n");
  return 2;
}

}  // namespace shpb
