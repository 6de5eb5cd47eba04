#include "core/closest_match.hpp"

#include <algorithm>
#include <cctype>

namespace shpb {
namespace {

std::string fold(std::string_view s) {
  std::string out(s);
  for (auto& c : out) {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (c == '-') c = '_';
  }
  return out;
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

}  // namespace

std::optional<std::string> closest_match(std::string_view word,
                                         const std::vector<std::string>& candidates) {
  const std::string w = fold(word);
  if (w.empty()) return std::nullopt;
  // A typo changes at most about a third of a word (one letter in a short one), and never the
  // whole word ("c" is no typo of "a").
  const std::size_t limit = std::min(std::max<std::size_t>(1, w.size() / 3), w.size() - 1);
  std::optional<std::string> best;
  std::size_t best_distance = limit + 1;
  for (const auto& c : candidates) {
    const std::size_t d = edit_distance(w, fold(c));
    if (d < best_distance) {
      best_distance = d;
      best = c;
    }
  }
  return best;
}

std::string key_suggestion_text(std::string_view word, const std::vector<std::string>& allowed,
                                const std::vector<KeyPlace>& schema) {
  if (closest_match(word, allowed)) return suggestion_text(word, allowed);
  const auto places_of = [&](const std::string& key) {
    std::vector<std::string> places;
    for (const KeyPlace& p : schema)
      if (std::find(p.keys->begin(), p.keys->end(), key) != p.keys->end() &&
          std::find(places.begin(), places.end(), p.where) == places.end())
        places.push_back(p.where);
    std::string text;
    for (std::size_t i = 0; i < places.size(); ++i)
      text += (i == 0 ? "" : i + 1 == places.size() ? " or " : ", ") + places[i];
    return text;
  };
  if (const std::string places = places_of(std::string(word)); !places.empty())
    return "not here; \"" + std::string(word) + "\" is a key of " + places;
  std::vector<std::string> elsewhere;
  for (const KeyPlace& p : schema)
    elsewhere.insert(elsewhere.end(), p.keys->begin(), p.keys->end());
  if (const auto near = closest_match(word, elsewhere))
    return "did you mean \"" + *near + "\", a key of " + places_of(*near) + "?";
  return suggestion_text(word, allowed);
}

std::string suggestion_text(std::string_view word, const std::vector<std::string>& candidates) {
  if (auto m = closest_match(word, candidates)) return "did you mean \"" + *m + "\"?";
  std::string s = "expected one of: ";
  for (std::size_t i = 0; i < candidates.size(); ++i) s += (i ? ", " : "") + candidates[i];
  return s;
}

}  // namespace shpb
