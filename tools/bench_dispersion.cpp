// Benchmark (not a test): Pochhammer–Chree correction of a 1 000 000-sample record — the peers'
// workload: a 10 MS/s pulse moved 1 m on a 20 mm steel bar. Build: cmake --build build --target
// bench_dispersion; run: build/bench_dispersion [samples] [--write-record DIR].
// Prints, side by side in one run (wall and CPU time; the machine may be loaded): the full
// dispersion table against the table up to the default cut-off a correction needs; the first
// correction (plans the FFT) against repeated ones (plan reused); and the six corrections of one
// test with amplitude factors, each planning its own FFT against all sharing one set of plans.
// --write-record DIR writes DIR/record.csv (time and two gauge columns, 1 M rows of a
// classic-bar test) and DIR/scene.json that processes it with the correction on, for the
// whole-process benchmark of tools/bench.sh.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "dispersion/propagation.hpp"

namespace {

struct Time {
  double wall_s, cpu_s;
};

Time measure(const std::function<void()>& f, int repeats = 1) {
  const auto w0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  for (int r = 0; r < repeats; ++r) f();
  const double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC / repeats;
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count() / repeats;
  return {wall, cpu};
}

void print(const char* what, Time t) {
  std::printf("  %-52s %8.1f ms wall %8.1f ms CPU\n", what, 1e3 * t.wall_s, 1e3 * t.cpu_s);
}

// A compressive half-sine pulse of 100 µs every 400 µs (the record is mostly pulses).
double pulse(double t) {
  const double phase = std::fmod(t, 400e-6);
  return phase < 100e-6 ? -1e-3 * std::sin(std::numbers::pi * phase / 100e-6) : 0.0;
}

// Trapezoid of amplitude `a` from t0, 10 µs rise and fall, `length` long in all.
double trapezoid(double t, double t0, double length, double a) {
  constexpr double kRise = 10e-6;
  const double s = t - t0;
  if (s <= 0 || s >= length) return 0;
  return a * std::min({1.0, s / kRise, (length - s) / kRise});
}

// A classic-bar test (steel C350, 19.05 mm, gauges 1 m from the specimen) sampled at 10 MS/s:
// incident, reflected and transmitted pulses after a 10 ms pre-trigger (the baseline), plus a
// little deterministic noise.
int write_record(const std::filesystem::path& dir, std::size_t n) {
  std::filesystem::create_directories(dir);
  const double c0 = std::sqrt(200e9 / 8080), dt = 1e-7, t0 = 10e-3, length = 120e-6;
  {
    std::FILE* f = std::fopen((dir / "record.csv").c_str(), "w");
    if (!f) return 1;
    std::fprintf(f, "time_s,incident_V,transmitted_V\n");
    unsigned noise = 12345;
    auto jitter = [&] {
      noise = noise * 1103515245u + 12345u;
      return 2e-6 * (static_cast<double>((noise >> 8) & 0xffff) / 65535.0 - 0.5);
    };
    for (std::size_t i = 0; i < n; ++i) {
      const double t = static_cast<double>(i) * dt;
      const double inc = trapezoid(t, t0, length, -1e-3) + trapezoid(t, t0 + 2 / c0, length, 6e-4);
      const double tra = trapezoid(t, t0 + 2 / c0 + 2e-6, length, -4e-4);
      std::fprintf(f, "%.7e,%.6e,%.6e\n", t, inc + jitter(), tra + jitter());
    }
    if (std::fclose(f) != 0) return 1;
  }
  std::ofstream s(dir / "scene.json");
  s << R"json({
  "name": "1 M-sample record of a classic test (benchmark)",
  "bars": [
    { "name": "striker", "material": "steel-c350", "length": "300 mm", "diameter": "19.05 mm",
      "velocity": "15 m/s" },
    { "name": "incident", "material": "steel-c350", "length": "2 m", "diameter": "19.05 mm",
      "gauges": [ { "name": "incident", "position": "1 m" } ] },
    { "name": "specimen", "material": "aluminium", "length": "5 mm", "diameter": "10 mm" },
    { "name": "transmitter", "material": "steel-c350", "length": "2 m", "diameter": "19.05 mm",
      "gauges": [ { "name": "transmitted", "position": "1 m" } ] }
  ],
  "specimen": "specimen",
  "materials": {
    "steel-c350": { "model": "elastic", "density": "8080 kg/m3", "youngs_modulus": "200 GPa",
                    "poisson_ratio": 0.29, "source": "nominal bar values" },
    "aluminium": { "model": "elastic", "density": "2700 kg/m3", "youngs_modulus": "69 GPa",
                   "poisson_ratio": 0.33, "source": "nominal" }
  },
  "simulation": { "duration": "800 us", "sample_rate": "10 MHz" },
  "measurement": {
    "file": "record.csv",
    "format": "csv",
    "time": { "column": "time_s", "unit": "s" },
    "channels": [
      { "gauge": "incident", "column": "incident_V", "unit": "strain" },
      { "gauge": "transmitted", "column": "transmitted_V", "unit": "strain" }
    ],
    "dispersion": { "correction": "pochhammer-chree", "amplitude_factors": false }
  }
}
)json";
  return s ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t n = 1000000;
  const char* record_dir = nullptr;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--write-record") == 0 && i + 1 < argc)
      record_dir = argv[++i];
    else
      n = std::strtoul(argv[i], nullptr, 10);
  }
  if (record_dir) return write_record(record_dir, n);

  const double dt = 1e-7;  // 10 MS/s: 0.1 s of record
  // 20 mm steel bar: E 200 GPa, ρ 7850 kg/m³, ν 0.29.
  const shpb::BarWaveguide bar{10e-3, std::sqrt(200e9 / 7850), 0.29};
  std::vector<double> x(n), y(n);
  for (std::size_t i = 0; i < n; ++i) x[i] = pulse(static_cast<double>(i) * dt);
  std::printf(
      "dispersion: %zu samples at 10 MS/s moved 1 m, bar radius %.4g m, c0 %.0f m/s, "
      "nu %.2f\n",
      n, bar.radius_m, bar.c0_m_s, bar.poisson);

  const Time full = measure([&] { const shpb::DispersionTable t(bar.poisson); });
  const Time needed = measure(
      [&] { (void)shpb::DispersionTable::up_to(bar.poisson, shpb::kDefaultCutoffFaOverC0); });
  print("dispersion table, whole grid (a/L <= 2)", full);
  print("dispersion table, up to the cut-off (what process builds)", needed);
  std::printf("  %-52s %8.1f x\n", "  ratio (CPU)", full.cpu_s / needed.cpu_s);

  const auto table = shpb::DispersionTable::up_to(bar.poisson, shpb::kDefaultCutoffFaOverC0);
  shpb::Propagator p(table, bar, {});
  const Time first = measure([&] { p.propagate(x, dt, 1.0, y); });
  constexpr int kRepeats = 5;
  const Time reused = measure([&] { p.propagate(x, dt, 1.0, y); }, kRepeats);
  print("first correction (plans the FFT)", first);
  print("correction, plan reused (mean of 5)", reused);

  // One test with amplitude factors: incident forward, reflected and transmitted back, strain
  // and stress factors each.
  auto six = [&](shpb::FftPlans* plans) {
    for (const auto a : {shpb::AmplitudeFactor::kStrain, shpb::AmplitudeFactor::kStress})
      for (const double d : {1.0, -1.0, -1.0}) {
        shpb::PropagationOptions o;
        o.amplitude = a;
        shpb::Propagator q(table, bar, o, plans);
        q.propagate(x, dt, d, y);
      }
  };
  const Time own = measure([&] { six(nullptr); });
  shpb::FftPlans shared;
  const Time one = measure([&] { six(&shared); });
  print("6 corrections, each planning its own FFT", own);
  print("6 corrections, one plan per length (what process does)", one);
  std::printf("  %-52s %8.1f x\n", "  ratio (CPU)", own.cpu_s / one.cpu_s);
  std::printf("checksum %.6g\n", y[n / 2]);
  return 0;
}
