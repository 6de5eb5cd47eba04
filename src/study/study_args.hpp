#pragma once
// What `shpb study` is asked (docs/commands.md, "study"): the sweep, its options and which of the
// plan / run / merge steps, with the check of their combinations.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "model/run_overrides.hpp"
#include "study/sweep.hpp"

namespace shpb {

// The stability map's refinement: 64 puts about 64² ≈ 4000 times refine 1's points on the grid,
// and bounds a mistyped value before its grid is allocated.
inline constexpr int kMaxRefine = 64;
// Monte Carlo draws of a study, each a whole simulation: a million is far past the 200 that give
// band edges to two digits (study/monte_carlo_sweep.hpp), and bounds the draws' storage.
inline constexpr std::size_t kMaxStudyDraws = 1000000;

struct StudyArgs {
  std::filesystem::path scene;
  std::filesystem::path output;
  std::optional<Sweep> sweep;  // as given; none: pareto (chosen_sweep)
  RunOverrides overrides;
  int refine = 1;  // stability grid refinement (study/sweep.hpp)
  // --sweep monte-carlo: the distributions file, draws and seed (study/monte_carlo_sweep.hpp).
  std::filesystem::path distributions;
  std::optional<std::size_t> draws;  // none: the default (kDefaultMonteCarloDraws)
  std::optional<std::uint64_t> seed;
  // Plan, run, merge (docs/commands.md): at most one of the three.
  std::optional<std::filesystem::path> plan;   // write DIR/plan.json (needs the scene)
  std::optional<std::filesystem::path> run;    // run shard `shard` of DIR's plan
  std::optional<std::filesystem::path> merge;  // merge DIR's parts into -o (default DIR/result)
  std::string shard;                           // "K/N"
  bool IsValid(std::string* error) const;      // the modes and their options
  Sweep chosen_sweep() const { return sweep.value_or(Sweep::kPareto); }
};

}  // namespace shpb
