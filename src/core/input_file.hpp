#pragma once
// Reading a whole input file (scene, material, signal file) safely: its type is checked before it
// is read — a FIFO would block forever and a device never end — and its size is bounded, so a
// wrong path is an InputError naming the file, never a hang or an out-of-memory.
#include <cstdint>
#include <filesystem>
#include <string>

namespace shpb {

// `display`: the file as the user wrote it; `expected`: what it should be ("a JSON file").
std::string read_input_file(const std::filesystem::path& file, const std::string& display,
                            const std::string& expected, std::uintmax_t max_bytes);

}  // namespace shpb
