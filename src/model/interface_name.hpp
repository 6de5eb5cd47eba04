#pragma once
// The name of the interface between bar `left` and the next one, "<left>-<right>": the prefix of
// its columns in interfaces.csv ("<name>_force_N", "<name>_gap_m"; docs/outputs.md).
#include <cstddef>
#include <string>

#include "model/scene.hpp"

namespace shpb {

inline std::string interface_name(const Scene& scene, std::size_t left) {
  return scene.bars[left].name + "-" + scene.bars[left + 1].name;
}

}  // namespace shpb
