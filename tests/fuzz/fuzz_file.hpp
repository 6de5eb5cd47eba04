#pragma once
// The readers under test take a path, so each input is written to a file in a private temporary
// folder (one per fuzzing process, removed at exit). The folder also holds `specimen.json` and
// `signals.csv` so that scenes referring to them reach the code behind the reference.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "../scratch.hpp"

namespace shpb_fuzz {

namespace fs = std::filesystem;

inline const fs::path& scratch_folder() {
  static const shpb_test::ScratchDir dir("fuzz");
  static const bool seeded = [] {
    std::ofstream(dir.path() / "specimen.json")
        << R"({"model": "elastic", "density": 2700, "youngs_modulus": "70 GPa", "poisson_ratio": 0.33})";
    std::ofstream(dir.path() / "signals.csv")
        << "time_s,ch1,ch2\n0,0,0\n1e-7,1e-4,2e-4\n2e-7,2e-4,3e-4\n";
    return true;
  }();
  (void)seeded;
  return dir.path();
}

// Writes the fuzz input to `name` in the scratch folder and returns its path.
inline fs::path write_input(const std::uint8_t* data, std::size_t size, const std::string& name) {
  const fs::path file = scratch_folder() / name;
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return file;
}

}  // namespace shpb_fuzz
