// Benchmark (not a test): Pochhammer–Chree correction of a 1 000 000-sample record.
// Build: cmake --build build --target bench_dispersion; run: build/bench_dispersion [samples].
// Times the table (once per bar), the first call (plans the FFT) and repeated calls (plan reused).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <vector>

#include "dispersion/propagation.hpp"

int main(int argc, char** argv) {
  using clock = std::chrono::steady_clock;
  const std::size_t n = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 1000000;
  const double dt = 1e-7;  // 10 MHz: 0.1 s of record
  const shpb::BarWaveguide bar{9.525e-3, 5000.0, 0.29};
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * dt;
    x[i] = -1e-3 * (std::fmod(t, 400e-6) < 100e-6) *
           std::sin(std::numbers::pi * std::fmod(t, 400e-6) / 100e-6);
  }
  auto seconds = [](clock::time_point a, clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
  };
  const auto t0 = clock::now();
  const shpb::DispersionTable table(bar.poisson);
  const auto t1 = clock::now();
  shpb::Propagator p(table, bar, {});
  std::vector<double> y(n);
  p.propagate(x, dt, 1.0, y);
  const auto t2 = clock::now();
  constexpr int kRepeats = 5;
  for (int r = 0; r < kRepeats; ++r) p.propagate(x, dt, 1.0, y);
  const auto t3 = clock::now();
  std::printf("samples %zu, bar radius %.4g m, c0 %.0f m/s, nu %.2f, distance 1 m\n", n,
              bar.radius_m, bar.c0_m_s, bar.poisson);
  std::printf("dispersion table (4001 points)   %8.3f s\n", seconds(t0, t1));
  std::printf("first correction (plans the FFT) %8.3f s\n", seconds(t1, t2));
  std::printf("correction, plan reused (mean/%d) %8.3f s\n", kRepeats, seconds(t2, t3) / kRepeats);
  std::printf("checksum %.6g\n", y[n / 2]);
  return 0;
}
