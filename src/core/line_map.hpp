#pragma once
// The line of each of a sequence of rows or samples (messages name a sample by its file's line),
// kept as runs of consecutive lines: a record without blank or skipped lines is one run, so the
// lines of a deep-memory record cost nothing per sample (a vector of them cost 8 bytes each).
#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace shpb {

class LineMap {
 public:
  // Appends the next item's line.
  void push_back(std::size_t line) {
    if (runs_.empty() || runs_.back().second + (size_ - runs_.back().first) != line)
      runs_.emplace_back(size_, line);
    ++size_;
  }
  std::size_t operator[](std::size_t i) const {
    const auto run = std::upper_bound(runs_.begin(), runs_.end(), i,
                                      [](std::size_t k, const auto& r) { return k < r.first; });
    return std::prev(run)->second + (i - std::prev(run)->first);
  }
  std::size_t back() const { return (*this)[size_ - 1]; }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  void clear() { runs_.clear(), size_ = 0; }
  // The lines of items [first, size()).
  LineMap from(std::size_t first) const {
    LineMap m;
    for (std::size_t r = 0; r < runs_.size(); ++r) {
      const std::size_t end = r + 1 < runs_.size() ? runs_[r + 1].first : size_;
      if (end <= first) continue;
      const std::size_t b = std::max(first, runs_[r].first);
      m.runs_.emplace_back(b - first, runs_[r].second + (b - runs_[r].first));
    }
    m.size_ = size_ > first ? size_ - first : 0;
    return m;
  }
  // The runs held: what the map costs (one per break in the lines' sequence).
  std::size_t runs() const { return runs_.size(); }

 private:
  std::vector<std::pair<std::size_t, std::size_t>> runs_;  // (first item, its line)
  std::size_t size_ = 0;
};

}  // namespace shpb
