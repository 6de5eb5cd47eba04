#include "core/file_digest.hpp"

#include <cstdio>
#include <fstream>
#include <set>

#include "core/error.hpp"

namespace shpb {
namespace fs = std::filesystem;

namespace {
constexpr std::uint64_t kFnvOffsetBasis = 14695981039346656037ull;
constexpr std::uint64_t kFnvPrime = 1099511628211ull;

fs::path absolute_path(const fs::path& file) {
  std::error_code ec;
  const fs::path a = fs::absolute(file, ec);
  return (ec ? file : a).lexically_normal();
}
}  // namespace

namespace {
std::uint64_t fnv1a64(std::uint64_t h, std::string_view bytes) {
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= kFnvPrime;
  }
  return h;
}
}  // namespace

std::uint64_t fnv1a64(std::string_view bytes) { return fnv1a64(kFnvOffsetBasis, bytes); }

std::string digest_text(std::uint64_t digest) {
  char s[17];
  std::snprintf(s, sizeof s, "%016llx", static_cast<unsigned long long>(digest));
  return s;
}

std::optional<std::uint64_t> file_digest(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  std::uint64_t h = kFnvOffsetBasis;
  std::string buffer(1 << 16, '\0');
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    h = fnv1a64(h, std::string_view(buffer.data(), static_cast<std::size_t>(in.gcount())));
  }
  if (in.bad()) return std::nullopt;
  return h;
}

nlohmann::json input_digests(const std::vector<fs::path>& files, const fs::path& base) {
  nlohmann::json list = nlohmann::json::array();
  std::set<std::string> seen;
  for (const fs::path& f : files) {
    if (f.empty()) continue;
    const std::string name =
        base.empty() ? absolute_path(f).string()
                     : absolute_path(f).lexically_relative(absolute_path(base)).string();
    if (!seen.insert(name).second) continue;
    const auto digest = file_digest(f);
    if (!digest) throw input_error(f.string(), "", "", "cannot be read");
    list.push_back({{"file", name}, {"fnv1a64", digest_text(*digest)}});
  }
  return list;
}

void check_input_digests(const nlohmann::json& recorded, const fs::path& record_file,
                         const std::string& json_path, const std::string& since,
                         const std::string& remedy, const fs::path& base) {
  if (!recorded.is_array())
    throw input_error(record_file.string(), json_path, "",
                      "missing or not a list of input files with their digests: " + remedy);
  for (std::size_t i = 0; i < recorded.size(); ++i) {
    const std::string where = json_path + "[" + std::to_string(i) + "]";
    const auto& e = recorded[i];
    if (!e.is_object() || !e.contains("file") || !e["file"].is_string() || !e.contains("fnv1a64") ||
        !e["fnv1a64"].is_string())
      throw input_error(record_file.string(), where, "",
                        "expected {\"file\": ..., \"fnv1a64\": ...}: " + remedy);
    const std::string file = e["file"].get<std::string>();
    const fs::path path = base.empty() ? fs::path(file) : base / file;
    if (!base.empty() && (fs::path(file).is_absolute() || file.find("..") != std::string::npos))
      throw input_error(record_file.string(), where, "\"" + file + "\"",
                        "expected a path inside " + base.string() + ": " + remedy);
    const auto now = file_digest(path);
    if (!now)
      throw input_error(record_file.string(), where, "\"" + file + "\"",
                        "missing or unreadable since " + since + ": " + remedy);
    if (digest_text(*now) != e["fnv1a64"].get<std::string>())
      throw input_error(record_file.string(), where, "\"" + file + "\"",
                        "changed since " + since + ": " + remedy);
  }
}

}  // namespace shpb
