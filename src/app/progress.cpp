#include "app/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace shpb {

ProgressPrinter::ProgressPrinter(std::string label)
    : label_(std::move(label)), tty_(::isatty(STDERR_FILENO) != 0) {}

void ProgressPrinter::operator()(double fraction, std::string_view detail) {
  // 100 % only when done: rounded, 16829 runs of 16913 read 100 % and the lines ended there.
  const int pct = fraction < 1 ? std::clamp(static_cast<int>(fraction * 100 + 0.5), 0, 99) : 100;
  std::string suffix;  // built piecewise: GCC 12 warns falsely on " " + std::string(...)
  if (!detail.empty()) (suffix = " ") += detail;
  if (tty_) {
    if (pct == last_ && suffix == last_detail_) return;
    constexpr int kWidth = 40;
    const int filled = pct * kWidth / 100;
    std::fprintf(stderr, "\r%s [%.*s%*s] %3d%%%s", label_.c_str(), filled,
                 "########################################", kWidth - filled, "", pct,
                 suffix.c_str());
    if (pct >= 100) std::fprintf(stderr, "\n");
  } else {
    const bool step = last_ < 0 || pct / 10 != last_ / 10 || (pct == 100 && last_ != 100);
    if (!step) return;
    std::fprintf(stderr, "%s: %d%%%s\n", label_.c_str(), pct, suffix.c_str());
  }
  last_ = pct;
  last_detail_ = suffix;
}

}  // namespace shpb
