#pragma once
#include <string>

#include "core/error.hpp"

namespace shpb {

// Options whose IsValid(&message) is false are refused before anything runs (InputError, exit 2,
// the one-line message), as Ceres' Solver::Options::IsValid.
template <typename Options>
void require_valid(const Options& options) {
  std::string message;
  if (!options.IsValid(&message)) throw InputError(message);
}

}  // namespace shpb
