#include "core/shards.hpp"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <map>
#include <regex>

#include "core/checked_write.hpp"
#include "core/error.hpp"
#include "core/output_folder.hpp"

namespace shpb {
namespace fs = std::filesystem;

namespace {
bool parse_count(std::string_view text, std::size_t& value) {
  if (text.empty()) return false;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && end == text.data() + text.size();
}

// "runs 2, 10, 18, …" (the first few).
std::string list_runs(const std::vector<std::size_t>& runs) {
  constexpr std::size_t kShown = 4;
  std::string s = runs.size() == 1 ? "run " : "runs ";
  for (std::size_t i = 0; i < std::min(runs.size(), kShown); ++i)
    s += (i ? ", " : "") + std::to_string(runs[i]);
  if (runs.size() > kShown) s += ", … (" + std::to_string(runs.size()) + " runs)";
  return s;
}
}  // namespace

Shard parse_shard(const std::string& option, const std::string& text) {
  Shard s;
  const auto slash = text.find('/');
  if (slash == std::string::npos ||
      !parse_count(std::string_view(text).substr(0, slash), s.index) ||
      !parse_count(std::string_view(text).substr(slash + 1), s.count) || s.count == 0 ||
      s.index >= s.count || s.count > kMaxShards)
    throw input_error(option, "", "\"" + text + "\"",
                      "expected K/N with 0 <= K < N <= " + std::to_string(kMaxShards) +
                          ", e.g. 0/8 (shard K of N, K from 0)");
  return s;
}

std::string part_name(const Shard& shard) {
  return std::to_string(shard.index) + "-of-" + std::to_string(shard.count);
}

std::vector<std::size_t> shard_runs(std::size_t total, const Shard& shard) {
  std::vector<std::size_t> runs;
  if (shard.count == 0) return runs;
  // r + N is never formed past `total`: no wrap-around, whatever N.
  for (std::size_t r = shard.index; r < total; r += shard.count) {
    runs.push_back(r);
    if (total - r <= shard.count) break;
  }
  return runs;
}

void write_file_atomically(const fs::path& file, const std::string& text) {
  OutputFile out(file);
  write_text_file(out.path(), text);
  out.commit();
}

std::vector<Part> find_parts(const fs::path& folder, const std::string& suffix) {
  static const std::regex name("([0-9]+)-of-([0-9]+)");
  std::vector<Part> parts;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(folder, ec)) {
    std::string n = e.path().filename().string();
    if (n.size() <= suffix.size() || n.compare(n.size() - suffix.size(), suffix.size(), suffix))
      continue;
    n.resize(n.size() - suffix.size());
    std::smatch m;
    if (!std::regex_match(n, m, name)) continue;
    Part p;
    p.path = e.path();
    if (!parse_count(m.str(1), p.shard.index) || !parse_count(m.str(2), p.shard.count) ||
        p.shard.count == 0 || p.shard.index >= p.shard.count)
      continue;
    parts.push_back(p);
  }
  std::sort(parts.begin(), parts.end(), [](const Part& a, const Part& b) {
    return std::pair(a.shard.count, a.shard.index) < std::pair(b.shard.count, b.shard.index);
  });
  return parts;
}

void check_parts_cover(const fs::path& folder, std::size_t total, const std::vector<Part>& parts) {
  if (parts.empty())
    throw input_error(folder.string(), "", "",
                      "no parts (K-of-N) found: run the shards first (--shard K/N)");
  std::vector<const Part*> owner(total, nullptr);
  for (const Part& p : parts)
    for (std::size_t r : shard_runs(total, p.shard)) {
      if (owner[r])
        throw input_error(folder.string(), "", "",
                          "duplicated part: " + part_name(p.shard) + " and " +
                              part_name(owner[r]->shard) + " both hold run " + std::to_string(r) +
                              " (parts of one split K/N only; remove the other split's parts)");
      owner[r] = &p;
    }
  // Missing runs, named by the part of the split in use that would hold them.
  const std::size_t n = parts.front().shard.count;
  std::map<std::size_t, std::vector<std::size_t>> missing;  // part index → runs
  for (std::size_t r = 0; r < total; ++r)
    if (!owner[r]) missing[r % n].push_back(r);
  if (missing.empty()) return;
  std::string what = missing.size() == 1 ? "missing part " : "missing parts ";
  bool first = true;
  for (const auto& [k, runs] : missing) {
    what += (first ? "" : "; ") + part_name({k, n}) + " (" + list_runs(runs) + ")";
    first = false;
  }
  throw input_error(folder.string(), "", "", what + ": run those shards again (--shard K/N)");
}

}  // namespace shpb
