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

// An object of an input file's schema: where it is ("contact", "bars[].gauges[]") and its keys.
struct KeyPlace {
  std::string where;
  const std::vector<std::string>* keys;
};

// What to say of a key `word` that an object allowing `allowed` does not know, looking through the
// file's other objects `schema` too: a close key of this object first ("did you mean \"x\"?"),
// else the places of `schema` that have the key ("not here; \"friction\" is a key of contact,
// contact.interfaces[] or measurement.corrections") or a close spelling of one of theirs ("did you
// mean \"friction\", a key of contact ...?"), else the keys allowed ("expected one of: ...").
std::string key_suggestion_text(std::string_view word, const std::vector<std::string>& allowed,
                                const std::vector<KeyPlace>& schema);

}  // namespace shpb
