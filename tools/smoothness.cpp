// Smoothness of the simulated gauge signals in a material parameter (docs/methods.md §9, "Smooth
// residuals"): the synthetic fit campaign's 2000 /s OFHC copper test (tests/fit/
// test_fit_synthetic.cpp builds the same scene) is run at A(1 − h), A, A(1 + h) for relative steps
// h, and the Euclidean norms over the record of the central first difference ½(g₊ − g₋) and of the
// second difference g₊ − 2g₀ + g₋ are printed per gauge. For a smooth response the first
// difference grows as h and the second as h² (ratio D2/D1 ∝ h, small); for a rough one both are
// of the same size whatever h.
// Build: cmake --build build --target smoothness; run:
//   build/smoothness [--stepping global|asynchronous] [--filter SECONDS] [--parameter A|B|n|C]
//                    [--no-adaptive] [--no-subcycle] [--no-skip] [--velocity M_S]
//                    [--until SECONDS] (the record up to that time only)
//                    [--events] (closings/releases per interface and steps per bar over A ± 1 %)
// --filter 0 turns the law's strain-rate filter off; without --filter the specimen's default.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../tests/fit/synthetic_scene.hpp"
#include "model/scene.hpp"
#include "solver/simulation.hpp"

using namespace shpb;
namespace fs = std::filesystem;

namespace {

double& parameter(Scene& scene, const std::string& name) {
  JohnsonCookParams& jc = scene.bars[*scene.specimen].material.johnson_cook;
  if (name == "B") return jc.B_Pa;
  if (name == "n") return jc.n;
  if (name == "C") return jc.C;
  return jc.A_Pa;
}

double norm(const std::vector<double>& x) {
  double s = 0;
  for (double v : x) s += v * v;
  return std::sqrt(s);
}

}  // namespace

int main(int argc, char** argv) {
  std::string stepping = "asynchronous", name = "A";
  double filter_s = -1, velocity = 18.5, until = 1.0;  // filter −1: the specimen's default
  bool events = false;
  SimulationOptions options;
  options.record_field = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--stepping" && i + 1 < argc)
      stepping = argv[++i];
    else if (a == "--filter" && i + 1 < argc)
      filter_s = std::atof(argv[++i]);
    else if (a == "--parameter" && i + 1 < argc)
      name = argv[++i];
    else if (a == "--velocity" && i + 1 < argc)
      velocity = std::atof(argv[++i]);
    else if (a == "--until" && i + 1 < argc)
      until = std::atof(argv[++i]);
    else if (a == "--events")
      events = true;
    else if (a == "--no-adaptive")
      options.adaptive_step = false;
    else if (a == "--no-subcycle")
      options.subcycle = false;
    else if (a == "--no-skip")
      options.skip_at_rest = false;
    else {
      std::fprintf(stderr, "unknown argument %s\n", a.c_str());
      return 2;
    }
  }
  const fs::path dir = fs::temp_directory_path() / "shpb_smoothness";
  fs::create_directories(dir);
  nlohmann::json law = nlohmann::json::parse(
      std::ifstream(fs::path(SHPB_SOURCE_DIR) / "specimens/ofhc-copper.json"));
  if (filter_s >= 0) law["strain_rate_filter"] = std::to_string(filter_s * 1e6) + " us";
  std::ofstream(dir / "law.json") << law.dump(1);
  std::ofstream(dir / "scene.json")
      << shpb_test::synthetic_scene(velocity, dir / "law.json", stepping);
  const Scene base = read_scene(dir / "scene.json");

  auto run = [&](double factor) {
    Scene s = base;
    parameter(s, name) *= factor;
    return simulate(s, options);
  };
  const SimulationResult mid = run(1.0);
  if (events)
    for (double f : {0.99, 0.997, 0.999, 0.9997, 0.9999, 1.0, 1.0001, 1.0003, 1.001, 1.003, 1.01}) {
      const SimulationResult r = run(f);
      std::printf("%8.4f", f);
      for (const auto& i : r.interface_statistics)
        std::printf("  %s %ld/%ld", i.name.c_str(), i.activations, i.releases);
      for (const auto& b : r.bars) std::printf("  %ld", b.steps);
      std::printf("\n");
    }
  std::printf("stepping %s, filter %g s, parameter %s, adaptive %d subcycle %d skip %d\n",
              stepping.c_str(), filter_s, name.c_str(), options.adaptive_step, options.subcycle,
              options.skip_at_rest);
  for (const std::string& g : mid.gauges.columns)
    std::printf("  |%s| = %.4e\n", g.c_str(), norm(mid.gauges.column(g)));
  std::printf("%10s %12s %12s %12s %12s %12s %12s\n", "h", "D1 inc", "D2 inc", "D2/D1 inc",
              "D1 trans", "D2 trans", "D2/D1 trans");
  for (double h : {1e-4, 3e-4, 1e-3, 3e-3, 1e-2}) {
    const SimulationResult lo = run(1 - h), hi = run(1 + h);
    std::printf("%10.0e", h);
    for (const std::string& g : mid.gauges.columns) {
      const std::vector<double>&a = lo.gauges.column(g), &b = mid.gauges.column(g),
            &c = hi.gauges.column(g);
      std::vector<double> d1(b.size()), d2(b.size());
      for (std::size_t k = 0; k < b.size(); ++k) {
        if (mid.gauges.time_s[k] > until) break;
        d1[k] = 0.5 * (c[k] - a[k]);
        d2[k] = c[k] - 2 * b[k] + a[k];
      }
      std::printf(" %12.3e %12.3e %12.3e", norm(d1), norm(d2), norm(d2) / norm(d1));
    }
    std::printf("\n");
  }
  fs::remove_all(dir);
  return 0;
}
