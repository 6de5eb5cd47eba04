#pragma once
// `shpb process` over several tests (docs/commands.md): scenes or a campaign file; each test's
// folder as the one-test command writes it (analysis/process_outputs.hpp process_into), plus
// campaign.csv; --shard K/N and --merge as for `study` (core/shards.hpp).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "analysis/uncertainty.hpp"

namespace shpb {

struct CampaignOptions {
  std::vector<std::filesystem::path> scenes;
  std::optional<std::filesystem::path> campaign;
  std::filesystem::path output;
  std::vector<double> flow_strains;  // engineering strains of the flow_stress_Pa_at_<e> columns
  std::string shard;                 // "K/N"
  bool merge = false;
  // Each test's measurement.uncertainty drawn as the one-test command draws it (--draws, --seed,
  // --threads; none given: its defaults); a test without the block is processed as before. The
  // shards draw: the merge copies their tests, so draws or a seed given to it are refused.
  std::optional<std::size_t> draws;
  std::optional<std::uint64_t> seed;
  int threads = 0;
  MonteCarloOptions monte_carlo() const;
  std::function<void(const std::string&)> progress;  // one line at a time; empty: silent
  // Each test's warnings on stderr as the one-test command prints them (`warning: ...`); they
  // are in its folder's summary.json either way (the Python module returns them from there).
  bool print_warnings = true;
  // Ceres' Solver::Options::IsValid: false with the reason in `error`.
  bool IsValid(std::string* error) const;
};

// Every scene read and checked before anything is processed or written. InputError (exit 2),
// NumericalError (exit 3) as the one-test command. Returns the folder holding the result: the
// output folder, a shard's part (DIR/parts/K-of-N) or the merge's DIR/result.
std::filesystem::path process_campaign(const CampaignOptions& options);
// The files such a run reads (the campaign file, a fit's material file, each scene's files): no
// output folder may hold one.
std::vector<std::filesystem::path> process_campaign_inputs(const CampaignOptions& options);

}  // namespace shpb
