#pragma once
// Independent runs handed to an outside scheduler (a Slurm job array, GNU parallel): shard K/N
// takes every N-th run of a plan starting at K and writes one part, named "K-of-N", atomically;
// the merge checks that the parts found cover every run exactly once (docs/commands.md).
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace shpb {

struct Shard {
  std::size_t index = 0;  // K, from 0
  std::size_t count = 1;  // N
};

// The most shards of one plan: more than any scheduler launches as one array (Slurm's
// MaxArraySize tops out at 4 000 001), and far from where K + N could overflow.
inline constexpr std::size_t kMaxShards = 1'000'000'000;

// "K/N" with 0 ≤ K < N ≤ kMaxShards; throws InputError naming `option`.
Shard parse_shard(const std::string& option, const std::string& text);

// "K-of-N": the part's name (file "K-of-N.json" or folder "K-of-N").
std::string part_name(const Shard& shard);

// The runs of a plan of `total` runs that shard K/N takes: K, K+N, K+2N, …
std::vector<std::size_t> shard_runs(std::size_t total, const Shard& shard);

// Writes `text` to `file` through a temporary file in the same folder and one rename
// (core/output_folder.hpp OutputFile), so a killed writer leaves either no file or the whole one.
void write_file_atomically(const std::filesystem::path& file, const std::string& text);

struct Part {
  std::filesystem::path path;
  Shard shard;
};

// The parts in `folder`: entries named "K-of-N" + `suffix` (".json" for files, "" for folders),
// in name order. Anything else (temporary files of running shards) is ignored.
std::vector<Part> find_parts(const std::filesystem::path& folder, const std::string& suffix);

// Checks that `parts` cover runs 0 … total−1 exactly once. Throws InputError naming the folder
// and the missing parts ("missing part 2-of-8 (runs 2, 10, …)"), or the two parts that hold the
// same run.
void check_parts_cover(const std::filesystem::path& folder, std::size_t total,
                       const std::vector<Part>& parts);

}  // namespace shpb
