// Clipping judgements on synthetic digitized records (docs/validation.md, "Clipping"): per
// digitizer resolution and noise, the share of unclipped records (a Kolsky trapezoid, a shaped
// rise, a rounded top, each peaking at 30, 60 or 90 % of the range) that main's pile-up rule
// called clipped and the share the rule of analysis/signal_checks.hpp calls clipped or "may be
// clipped"; then the same for records clipped at the range, the range at 50–99 % of the would-be
// peak. Each record: 4000 samples, a compressive pulse of 1000 and a tensile reflection at 40 %,
// white Gaussian noise, rounded to the grid of a ±range digitizer and held at its end codes.
// Build: cmake --build build --target clip_rates; run: build/clip_rates [--draws N]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "analysis/signal_checks.hpp"

namespace {

constexpr std::size_t kSamples = 4000, kOnset = 800, kLength = 1000;

// The pulse's shape at u ∈ [0, 1] of its length, peak 1.
double shape(int kind, double u) {
  if (u <= 0 || u >= 1) return 0;
  if (kind == 0) return std::min({1.0, u / 0.1, (1 - u) / 0.1});  // trapezoid
  if (kind == 1) {  // a shaped (smoothstep) rise over 70 %, a cosine fall
    if (u < 0.7) return (u / 0.7) * (u / 0.7) * (3 - 2 * u / 0.7);
    return 0.5 * (1 + std::cos(std::numbers::pi * (u - 0.7) / 0.3));
  }
  return std::sin(std::numbers::pi * u);  // rounded top
}

// main's rule (before the smooth-top and noise tests), kept here to measure against.
bool piles_up(const std::vector<double>& x) {
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  for (const double e : {*hi, *lo}) {
    std::size_t run = 0, longest = 0, at = 0, at_next = 0;
    double next = e == *hi ? *lo : *hi;
    for (double v : x) {
      longest = std::max(longest, run = v == e ? run + 1 : 0);
      at += v == e;
      if (v != e && std::abs(e - v) < std::abs(e - next)) next = v;
    }
    for (double v : x) at_next += v == next;
    if (e != 0 && longest >= shpb::kClippedRun &&
        static_cast<double>(at) >= shpb::kClippedPileUp * static_cast<double>(at_next))
      return true;
  }
  return false;
}

// The digitizer's range of a record drawn with these arguments.
double range_of(double peak_of_range, double clip) { return clip > 0 ? clip : 1 / peak_of_range; }

std::vector<double> record(int kind, int bits, double noise, double peak_of_range, double clip,
                           std::mt19937_64& rng) {
  std::normal_distribution<double> gauss(0, noise);
  // Would-be peak 1; the range at `peak / peak_of_range`, or at `clip` of the peak.
  const double range = range_of(peak_of_range, clip);
  const double q = 2 * range / std::ldexp(1.0, bits);
  const double top = std::ldexp(1.0, bits - 1);
  std::vector<double> x(kSamples);
  for (std::size_t i = 0; i < kSamples; ++i) {
    const double u = (static_cast<double>(i) - kOnset) / kLength;
    const double v = -shape(kind, u) +
                     0.4 * std::sin(std::numbers::pi * (u - 1.5)) * (u > 1.5 && u < 2.5) +
                     gauss(rng);
    x[i] = std::clamp(std::round(v / q), -top, top - 1) * q;
  }
  return x;
}

}  // namespace

int main(int argc, char** argv) {
  int draws = 60;
  if (argc == 3 && std::string(argv[1]) == "--draws") draws = std::stoi(argv[2]);
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  const double noises[] = {0.001, 0.002, 0.005, 0.01, 0.02};
  const double clips[] = {0.5, 0.7, 0.9, 0.95, 0.99};
  std::printf(
      "| bits | noise | unclipped: main clipped | now clipped | now may be | range stated: clipped "
      "| "
      "clipped: main found | now clipped | now may be | now missed | range stated: found "
      "|\n|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const int bits : {8, 10, 12, 16})
    for (const double noise : noises) {
      int n_un = 0, old_fp = 0, new_fp = 0, new_may = 0, range_fp = 0;
      int n_cl = 0, old_tp = 0, new_tp = 0, new_may_cl = 0, new_miss = 0, range_tp = 0;
      auto stated = [](double range) { return shpb::FullScale{{-range, range}}; };
      for (int d = 0; d < draws; ++d)
        for (int kind = 0; kind < 3; ++kind) {
          for (const double at : {0.3, 0.6, 0.9}) {
            const double of_range = at + jitter(rng);
            const auto x = record(kind, bits, noise, of_range, 0, rng);
            range_fp += !shpb::clipped_levels(x, stated(range_of(of_range, 0))).empty();
            const auto levels = shpb::clipped_levels(x);
            ++n_un, old_fp += piles_up(x);
            const bool est = std::any_of(levels.begin(), levels.end(),
                                         [](const auto& c) { return c.established; });
            new_fp += est, new_may += !est && !levels.empty();
          }
          for (const double c : clips) {
            const double cut = c * (1 + jitter(rng) / 5);
            const auto x = record(kind, bits, noise, 0, cut, rng);
            range_tp += !shpb::clipped_levels(x, stated(range_of(0, cut))).empty();
            const auto levels = shpb::clipped_levels(x);
            ++n_cl, old_tp += piles_up(x);
            const bool est = std::any_of(levels.begin(), levels.end(),
                                         [](const auto& l) { return l.established; });
            new_tp += est, new_may_cl += !est && !levels.empty(), new_miss += levels.empty();
          }
        }
      auto pc = [](int k, int n) { return 100.0 * k / n; };
      std::printf(
          "| %d | %.1f %% | %.1f %% | %.1f %% | %.1f %% | %.1f %% | %.1f %% | %.1f %% | %.1f %% | "
          "%.1f %% | %.1f %% |\n",
          bits, 100 * noise, pc(old_fp, n_un), pc(new_fp, n_un), pc(new_may, n_un),
          pc(range_fp, n_un), pc(old_tp, n_cl), pc(new_tp, n_cl), pc(new_may_cl, n_cl),
          pc(new_miss, n_cl), pc(range_tp, n_cl));
    }
}
