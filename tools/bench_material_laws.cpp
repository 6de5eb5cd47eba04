// Benchmark (not a test): element updates per second of each material law, over a bar-sized
// array of specimen elements loaded at 2000 /s to 0.4 strain and unloaded (plastic most of the
// time), with the specimen's time step of the classic experiment (≈ 2e-8 s).
// Build: cmake --build build --target bench_material_laws; run: build/bench_material_laws.
// Prints the median of 5 repetitions per law in ns per element update.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "model/material_law.hpp"
#include "model/material_reader.hpp"

namespace {
using namespace shpb;

// Al 6061-T6 as the classic experiment's specimen file gives it (Johnson–Cook, adiabatic); the
// other laws take its density and modulus with parameters of the same order.
MaterialSpec law_spec(MaterialModel model) {
  MaterialSpec spec = read_material_file(
      std::filesystem::path(SHPB_SOURCE_DIR) / "specimens" / "al6061-t6.json", "al6061-t6.json");
  spec.model = model;
  spec.bilinear = {.yield_stress_Pa = 300e6, .tangent_modulus_Pa = 1e9};
  spec.viscoelastic = {.long_term_modulus_Pa = 39e9, .arms = {{20e9, 1e-3}, {10e9, 2e-5}}};
  return spec;
}

double ns_per_update(const MaterialLaw& law) {
  constexpr int kElements = 50, kSteps = 40000;
  constexpr double kDt = 2e-8, kRate = 2000;
  std::vector<MaterialPointState> states(kElements);
  std::vector<double> strain(kElements), stress(kElements);
  law.initialize(states);
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < kSteps; ++k) {
    const double e = -kRate * kDt * (k < kSteps / 2 ? k : kSteps - k);
    for (int i = 0; i < kElements; ++i) strain[i] = e * (1 + 0.01 * i / kElements);
    law.update(strain, kDt, states, stress);
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return s / (static_cast<double>(kElements) * kSteps) * 1e9;
}
}  // namespace

int main() {
  const std::pair<const char*, MaterialModel> laws[] = {
      {"elastic", MaterialModel::kElastic},
      {"bilinear", MaterialModel::kBilinear},
      {"johnson-cook", MaterialModel::kJohnsonCook},
      {"viscoelastic (2 arms)", MaterialModel::kViscoelastic}};
  std::printf("%-22s %14s %18s\n", "law", "ns/update", "updates/s");
  for (const auto& [name, model] : laws) {
    const auto law = make_material_law(law_spec(model));
    std::vector<double> runs;
    for (int r = 0; r < 5; ++r) runs.push_back(ns_per_update(*law));
    std::sort(runs.begin(), runs.end());
    std::printf("%-22s %14.1f %18.3g\n", name, runs[2], 1e9 / runs[2]);
  }
}
