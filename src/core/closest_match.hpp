#pragma once
// "Did you mean": the candidate closest to a misspelt word (Levenshtein distance, case-insensitive,
// '_' and '-' treated alike), or nothing when no candidate is close enough to be a likely typo.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace shpb {

std::optional<std::string> closest_match(std::string_view word,
                                         const std::vector<std::string>& candidates);

// Appends "; did you mean \"x\"?" when a candidate is close, else "; expected one of: a, b, c".
std::string suggestion_text(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace shpb
