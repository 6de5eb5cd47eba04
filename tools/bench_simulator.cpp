// Benchmark (not a test) of the simulator, issue 8: for each scene given, the median wall time of
// several runs, node updates per second, node updates against the full model (causal economy),
// and asynchronous against global stepping (time ratio and incident-plateau error of each), plus
// the raw element-update rate of elastic bars. Build: cmake --build build --target
// bench_simulator; run: build/bench_simulator [--repeat N] experiments/*/scene.json
// (tools/bench.sh does both).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "solver/simulation.hpp"

using namespace shpb;

namespace {

double median(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  return x[x.size() / 2];
}

// Relative error of the incident plateau (15–85 % of the pulse) against V/(2c0), for a striker
// and incident bar of equal impedance; NaN when not applicable.
double incident_error(const Scene& scene, const SimulationResult& r) {
  if (scene.bars.size() < 2 || scene.bars[1].gauges.empty()) return std::nan("");
  const BarSpec& s = scene.bars[0];
  const BarSpec& b = scene.bars[1];
  if (std::abs(s.impedance_kg_s() / b.impedance_kg_s() - 1) > 1e-9) return std::nan("");
  const double expected = -s.velocity_m_s / (2 * s.material.wave_speed_m_s());
  const auto& x = r.gauges.column(b.gauges.front().name);
  long first = -1, last = -1;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const bool in = x[k] / expected > 0.5;
    if (in && first < 0) first = static_cast<long>(k);
    if (first >= 0 && !in) break;
    if (in) last = static_cast<long>(k);
  }
  if (first < 0) return std::nan("");
  const long a = first + (last - first) * 15 / 100, e = first + (last - first) * 85 / 100;
  double sum = 0;
  for (long k = a; k <= e; ++k) sum += x[k];
  return std::abs(sum / (e - a + 1) / expected - 1);
}

// Wall time of the solve (summary's wall_time_s) and the process CPU time of the whole call;
// on a loaded machine the CPU time is the steadier figure.
struct Timing {
  double wall_s;
  double cpu_s;
  SimulationResult last;
};

Timing run(const Scene& scene, const SimulationOptions& options, int repeat) {
  std::vector<double> walls, cpus;
  SimulationResult r;
  for (int i = 0; i < repeat; ++i) {
    const std::clock_t c0 = std::clock();
    r = simulate(scene, options);
    cpus.push_back(double(std::clock() - c0) / CLOCKS_PER_SEC);
    walls.push_back(r.wall_time_s);
  }
  return {median(walls), median(cpus), std::move(r)};
}

}  // namespace

int main(int argc, char** argv) {
  int repeat = 5;
  std::vector<std::string> scenes;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--repeat" && i + 1 < argc) repeat = std::max(1, std::atoi(argv[++i]));
    else scenes.push_back(a);
  }
  SimulationOptions economy;
  economy.record_field = false;
  SimulationOptions full = economy;
  full.full_model = true;

  for (const std::string& file : scenes) {
    Scene scene;
    try {
      scene = read_scene(file);
    } catch (const std::exception& e) {
      std::printf("%s: skipped (%s)\n", file.c_str(), e.what());
      continue;
    }
    scene.simulation.stepping = Stepping::kAsynchronous;
    const Timing a = run(scene, economy, repeat);
    const Timing af = run(scene, full, 1);
    scene.simulation.stepping = Stepping::kGlobal;
    const Timing g = run(scene, economy, std::max(1, repeat / 2));
    scene.simulation.stepping = Stepping::kAsynchronous;
    std::printf("%s (%s)\n", file.c_str(), scene.name.c_str());
    std::printf("  asynchronous: %.2f ms wall, %.2f ms CPU (medians of %d), %lld node updates "
                "(%.3g/s of CPU), energy error %.2g%s\n",
                a.wall_s * 1e3, a.cpu_s * 1e3, repeat, a.last.node_updates,
                a.last.node_updates / a.cpu_s, a.last.energy_error, a.last.stable ? "" : " UNSTABLE");
    std::printf("  causal economy: %lld of %lld node updates of the full model (saves %.1f %%); "
                "full model %.2f ms\n",
                a.last.node_updates, af.last.node_updates,
                100.0 * (1.0 - double(a.last.node_updates) / double(af.last.node_updates)),
                af.wall_s * 1e3);
    std::printf("  global: %.2f ms wall, %.2f ms CPU, %lld node updates; global/asynchronous: "
                "CPU time x%.1f, updates x%.1f\n",
                g.wall_s * 1e3, g.cpu_s * 1e3, g.last.node_updates, g.cpu_s / a.cpu_s,
                double(g.last.node_updates) / double(a.last.node_updates));
    std::printf("  incident plateau error against V/(2c0): asynchronous %.2e, global %.2e\n",
                incident_error(scene, a.last), incident_error(scene, g.last));
  }

  // Raw rate of the elastic kernel: a steel striker on a 2 m bar, every node updated.
  Scene bars;
  bars.name = "elastic bars";
  MaterialSpec steel;
  steel.density_kg_m3 = 8000;
  steel.youngs_modulus_Pa = 200e9;
  BarSpec s;
  s.name = "striker";
  s.material = steel;
  s.length_m = 0.3;
  s.area_m2 = 2.85e-4;
  s.velocity_m_s = 10;
  BarSpec b = s;
  b.name = "bar";
  b.length_m = 2.0;
  b.velocity_m_s = 0;
  b.gauges.push_back({"g", 1.0});
  bars.bars = {s, b};
  bars.simulation.duration_s = 800e-6;
  const Timing e = run(bars, full, repeat);
  std::printf("elastic bars (0.3 m striker on 2 m bar, 1 mm elements, 800 us, full model): "
              "%.2f ms wall, %.2f ms CPU, %.3g element updates/s of CPU\n",
              e.wall_s * 1e3, e.cpu_s * 1e3, e.last.node_updates / e.cpu_s);
  return 0;
}
