#include "core/record_filter.hpp"

#include <algorithm>
#include <cmath>

namespace shpb {

namespace {
// Half-width of the smoothing kernel in standard deviations (weights below 3e-4 of the peak).
constexpr int kKernelHalfWidth = 4;
// Outputs summed side by side inside the record.
constexpr int kInterleaved = 8;
}  // namespace

std::vector<double> record_smoothed(std::span<const double> x, int sigma, int stride) {
  const int half = kKernelHalfWidth * sigma;
  std::vector<double> w(2 * half + 1);
  for (int j = -half; j <= half; ++j)
    w[j + half] =
        std::exp(-0.5 * (static_cast<double>(j) / sigma) * (static_cast<double>(j) / sigma));
  const long n = static_cast<long>(x.size());
  // The whole kernel's weight, summed in the order the ends sum theirs.
  double inside = 0;
  for (const double v : w) inside += v;
  // A record's leading zeros (a gauge the pulse has not reached yet: a quarter to three quarters
  // of a classic test's record) smooth to zero exactly, so the samples whose kernel sees only
  // them are not summed.
  const long zeros = std::find_if(x.begin(), x.end(), [](double v) { return v != 0; }) - x.begin();
  std::vector<double> y;
  y.reserve(x.size() / stride + 1);
  for (long k = 0; k < n; k += stride) {
    if (k + half < zeros) {
      y.push_back(0.0);
      continue;
    }
    double s = 0, weight = 0;
    if (k >= half && k + (kInterleaved - 1) * stride + half < n) {
      // kInterleaved outputs at once, each summed in the same order as alone: the independent
      // sums keep the floating-point unit busy where one waits on its own last addition.
      const double* xk = x.data() + (k - half);
      double a[kInterleaved] = {};
      for (int j = 0; j <= 2 * half; ++j, ++xk)
        for (int m = 0; m < kInterleaved; ++m) a[m] += w[j] * xk[m * stride];
      for (const double v : a) y.push_back(v / inside);
      k += (kInterleaved - 1) * stride;
      continue;
    }
    if (k >= half && k + half < n) {  // the kernel inside the record: no bounds to check
      const double* xk = x.data() + (k - half);
      for (int j = 0; j <= 2 * half; ++j) s += w[j] * xk[j];
      weight = inside;
    } else {
      for (int j = -half; j <= half; ++j) {
        const long i = k + j;
        if (i < 0 || i >= n) continue;
        s += w[j + half] * x[i];
        weight += w[j + half];
      }
    }
    y.push_back(s / weight);
  }
  return y;
}

}  // namespace shpb
