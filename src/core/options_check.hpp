#pragma once
#include <initializer_list>
#include <string>
#include <utility>

#include "core/error.hpp"

namespace shpb {

// --threads of every command (and `threads` of the Python module): a whole number >= 0, 0 for all
// cores. The one wording of the command line's check (app/cli_options.cpp) and the library's.
inline constexpr const char* kThreadsExpected = "expected a whole number >= 0 (0: all cores)";
// The library's check of a threads count (the command line refuses it as it parses; Python passes
// any int): empty when it is >= 0, else the one line.
inline std::string threads_problem(int threads) {
  if (threads >= 0) return {};
  return input_error("--threads", "", std::to_string(threads), kThreadsExpected).what();
}

// Options whose IsValid(&message) is false are refused before anything runs (InputError, exit 2,
// the one-line message), as Ceres' Solver::Options::IsValid.
template <typename Options>
void require_valid(const Options& options) {
  std::string message;
  if (!options.IsValid(&message)) throw InputError(message);
}

// The first of `options` ({given, name}) that was given, or nullptr: the option an error names.
inline const char* first_given(std::initializer_list<std::pair<bool, const char*>> options) {
  for (const auto& [given, name] : options)
    if (given) return name;
  return nullptr;
}

// An option given to a step of a sharded run that cannot use it, because an earlier step fixed
// what it sets (a study's plan, a campaign's shards) or a later one does what it asks: the one
// refusal of `study --run/--merge` and `process --shard/--merge` (exit 2, "<option>: not with
// <step>: <why>"), said before anything is read.
inline InputError not_with_step(const char* option, const std::string& step,
                                const std::string& why) {
  return input_error(option, "", "", "not with " + step + ": " + why);
}

}  // namespace shpb
