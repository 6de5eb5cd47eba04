#pragma once
// What a plan or a part was computed from (docs/outputs.md, plans and parts): every input file
// with a digest of its bytes, recorded when the plan or the part is written and compared when it is
// used, so a scene, material, measured or campaign file edited in between is named, not merged.
// The digest is 64-bit FNV-1a over the file's bytes (offset basis 14695981039346656037, prime
// 1099511628211): not a cryptographic hash — it tells an edit from no edit, which is all a plan
// needs; a deliberate collision is not a threat it guards against.
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace shpb {

// FNV-1a of `bytes`, and of a file's bytes (nullopt if the file cannot be read).
std::uint64_t fnv1a64(std::string_view bytes);
std::optional<std::uint64_t> file_digest(const std::filesystem::path& file);
// A digest as records write it: 16 hex digits.
std::string digest_text(std::uint64_t digest);

// [{"file": path, "fnv1a64": 16 hex digits}, ...] of `files` (duplicates once, in order); the
// path absolute, or relative to `base` if one is given (files of a folder that is moved into place
// after they are recorded). Throws InputError naming a file that cannot be read.
nlohmann::json input_digests(const std::vector<std::filesystem::path>& files,
                             const std::filesystem::path& base = {});

// Checks the digests recorded in `recorded` (written by input_digests with the same `base`) against
// the files as they are now. Throws InputError naming `record_file`, `json_path`[i] and the changed
// or missing file: "changed since <since>: <remedy>", at the first difference; also when the
// record is not an array of such entries.
void check_input_digests(const nlohmann::json& recorded, const std::filesystem::path& record_file,
                         const std::string& json_path, const std::string& since,
                         const std::string& remedy, const std::filesystem::path& base = {});

}  // namespace shpb
