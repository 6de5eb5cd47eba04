#pragma once
// Reading a JSON file for the scene reader: a missing or unreadable file, an empty file, text that
// is not JSON (with line and column), duplicate keys (JSON allows them, we do not: the second one
// would silently win), nesting deeper than kMaxJsonDepth, files larger than kMaxJsonBytes, FIFOs
// and devices, and a top level that is not an object are all InputErrors naming the file.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "core/error.hpp"

namespace shpb {

// Limits checked before the document is built: a scene is a few kB and a few levels deep.
inline constexpr int kMaxJsonDepth = 64;
inline constexpr std::size_t kMaxJsonBytes = std::size_t{64} << 20;

// The refusal of a value nested deeper than kMaxJsonDepth at `path` (also of a dict the Python
// module is given, python/values.cpp: a dict that holds itself is nested without end).
InputError too_deep(const std::string& display, const std::string& path);

// `display` is how the file is named in messages (the path as the user wrote it).
nlohmann::json read_json_object_file(const std::filesystem::path& file, const std::string& display);
// Its text, with the same checks of the file (size, UTF-16, binary) before it is parsed.
std::string read_json_file_text(const std::filesystem::path& file, const std::string& display);

// The same from text already in memory.
nlohmann::json parse_json_object(const std::string& text, const std::string& display);

}  // namespace shpb
