#pragma once
#include <string>

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

}  // namespace shpb
