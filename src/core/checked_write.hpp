#pragma once
// Writes whose every step is checked (docs/outputs.md (conventions)): a full disk or an I/O error
// becomes a WriteError naming the file and the system's reason ("No space left on device"),
// never a silently truncated output.
#include <filesystem>
#include <string>
#include <string_view>

namespace shpb {

// "<file>: cannot be written: <strerror(errno)>".
[[noreturn]] void throw_write_error(const std::filesystem::path& file, int error_number);

// Creates (or truncates) `file` and writes `text` to it, checking every call.
void write_text_file(const std::filesystem::path& file, std::string_view text);

// fsync of a file or a folder (a folder's entries are durable only after its own fsync).
void sync_path(const std::filesystem::path& path);

// fsync of every file and folder under `dir`, and of `dir` itself.
void sync_tree(const std::filesystem::path& dir);

}  // namespace shpb
