#pragma once
// The files of `shpb study --sweep monte-carlo` (docs/outputs.md): each draw's values and fate,
// the bands of the gauges and of the processed curve, and each quantity's spread.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "model/scene.hpp"
#include "study/monte_carlo_sweep.hpp"

namespace shpb {

// draws.csv, gauge_bands.csv, curve_bands.csv and summary.json (docs/outputs.md) from every run's
// result (results[0] the nominal run). NumericalError (exit 3) when the nominal run or all but
// one of the draws failed; otherwise the warnings to print: how many draws failed or were not
// reduced, with the first cause.
std::vector<std::string> write_monte_carlo(
    const Scene& scene, const std::vector<Distribution>& distributions, std::uint64_t seed,
    const std::vector<MonteCarloJob>& jobs, const std::vector<MonteCarloJobResult>& results,
    int threads, double wall_s, const std::filesystem::path& dir);

}  // namespace shpb
