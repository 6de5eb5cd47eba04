#pragma once
// Progress of a long command on stderr (simulate: simulated time; study: runs done): on a terminal
// one line redrawn in place with a bar, otherwise a plain line at every 10 % step and at the end.
// Commands with --quiet do not make one.
#include <string>
#include <string_view>

namespace shpb {

class ProgressPrinter {
 public:
  explicit ProgressPrinter(std::string label);
  // `fraction` done in [0, 1]; `detail` (e.g. "3/10 runs") follows the percentage.
  void operator()(double fraction, std::string_view detail = {});

 private:
  std::string label_;
  bool tty_;
  int last_ = -1;  // last percentage printed
  std::string last_detail_;
};

}  // namespace shpb
