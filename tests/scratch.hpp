// Scratch folders for tests: the one place that names them. Unique per process, because ctest -j
// runs test cases in parallel processes and other checkouts on the same machine run the same tests
// at the same time.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace shpb_test {

// Removes a scratch folder, also when a test made it read-only.
inline void remove_scratch(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::permissions(dir, std::filesystem::perms::owner_all,
                               std::filesystem::perm_options::add, ec);
  std::filesystem::remove_all(dir, ec);
}

// Every folder scratch_dir made in this process, removed when the process ends (a test process
// leaves nothing in the temporary folder).
struct ScratchRegistry {
  std::vector<std::filesystem::path> folders;
  ~ScratchRegistry() {
    for (const auto& dir : folders) remove_scratch(dir);
  }
};
inline ScratchRegistry& scratch_registry() {
  static ScratchRegistry registry;
  return registry;
}

// <temp>/shpb_test_<name>_<pid>, emptied and created.
inline std::filesystem::path scratch_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("shpb_test_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  auto& folders = scratch_registry().folders;
  if (std::find(folders.begin(), folders.end(), dir) == folders.end()) folders.push_back(dir);
  return dir;
}

// A scratch_dir(name) removed with the object (also when a test made the folder read-only).
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name) : path_(scratch_dir(name)) {}
  ~ScratchDir() { remove_scratch(path_); }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace shpb_test
