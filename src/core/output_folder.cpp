#include "core/output_folder.hpp"

#include <fcntl.h>  // AT_FDCWD
#include <signal.h>
#include <stdio.h>  // renameat2
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <charconv>
#include <csignal>
#include <fstream>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <system_error>

#include "core/checked_write.hpp"
#include "core/error.hpp"

namespace shpb {
namespace fs = std::filesystem;

namespace {
std::atomic<bool> g_interrupted{false};  // the one global: a signal handler cannot reach others
// The first signal asks the run to stop cleanly; a second one ends it at once (default action).
extern "C" void on_signal(int sig) {
  g_interrupted.store(true);
  std::signal(sig, SIG_DFL);
}

// ".<name>.tmp-<pid>-<random>" (and its ".old" twin): the temporary folders and files of this
// scheme.
std::string temp_prefix(const fs::path& final_path) {
  std::string prefix = ".";
  prefix += final_path.filename().string();
  prefix += ".tmp-";
  return prefix;
}

// The pid in "<prefix><pid>-...", if the name is of our scheme and the pid a valid one; names
// that merely look alike (too many digits, no dash) are not ours and are left alone.
std::optional<pid_t> temp_owner(const std::string& name, const std::string& prefix) {
  if (name.rfind(prefix, 0) != 0) return std::nullopt;
  const std::string_view rest = std::string_view(name).substr(prefix.size());
  const auto dash = rest.find('-');
  if (dash == 0 || dash == std::string_view::npos || dash > 9) return std::nullopt;
  long pid = 0;
  const auto [end, ec] = std::from_chars(rest.data(), rest.data() + dash, pid);
  if (ec != std::errc() || end != rest.data() + dash || pid <= 0) return std::nullopt;
  return static_cast<pid_t>(pid);
}

// Temporaries left by a run that was killed outright (SIGKILL, power loss) are removed when the
// next run starts: their owner process is gone. Only names of our own scheme are touched.
void remove_stale_temporaries(const fs::path& final_path) {
  const std::string prefix = temp_prefix(final_path);
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(final_path.parent_path(), ec)) {
    const auto pid = temp_owner(e.path().filename().string(), prefix);
    if (pid && ::kill(*pid, 0) != 0 && errno == ESRCH) {
      std::error_code rm;
      fs::remove_all(e.path(), rm);
    }
  }
}

// Why shpb may not replace `dir`, or "" if it may: it is empty, or its marker starts with the
// signature and lists every entry the folder holds.
std::string refusal(const fs::path& dir) {
  std::error_code ec;
  if (fs::is_empty(dir, ec)) return "";
  const fs::path marker = dir / kOutputMarker;
  if (!fs::is_regular_file(fs::symlink_status(marker, ec)))
    return "is not empty and holds no " + std::string(kOutputMarker) +
           " marker: shpb replaces only folders it wrote (a result of an older shpb has no "
           "marker: delete it yourself) — choose another output folder";
  std::ifstream in(marker);
  std::string line;
  if (!std::getline(in, line) || line != kOutputMarkerSignature)
    return std::string(kOutputMarker) + " is not shpb's marker; refusing to replace the folder";
  std::set<std::string> listed;
  while (std::getline(in, line))
    if (line.rfind("file: ", 0) == 0) listed.insert(line.substr(6));
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name != kOutputMarker && !listed.count(name))
      return "holds " + name +
             ", which shpb did not write; refusing to replace the folder (move it away or "
             "choose another output folder)";
  }
  if (ec) return "cannot be listed: " + ec.message();
  return "";
}

// `inner` is `outer` or lies inside it (both canonical).
bool contains(const fs::path& outer, const fs::path& inner) {
  auto o = outer.begin(), i = inner.begin();
  for (; o != outer.end(); ++o, ++i)
    if (i == inner.end() || *o != *i) return false;
  return true;
}

fs::path make_temporary(const fs::path& final_path, bool folder) {
  std::random_device rd;
  std::error_code ec;
  for (int attempt = 0; attempt < 100; ++attempt) {
    const fs::path candidate =  // hidden sibling: ".<name>.tmp-<pid>-<random>"
        final_path.parent_path() / (temp_prefix(final_path) + std::to_string(::getpid()) + "-" +
                                    std::to_string(rd() % 100000));
    if (folder) {
      if (fs::create_directory(candidate, ec)) return candidate;
    } else {
      const int fd = ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
      if (fd >= 0) {
        ::close(fd);
        return candidate;
      }
      if (errno != EEXIST) throw_write_error(candidate, errno);
    }
  }
  throw input_error(final_path.parent_path().string(), "", "", "cannot create a temporary output");
}

// The absolute path of an output (DIR or FILE).
fs::path absolute_output(const fs::path& given, const std::string& what) {
  std::error_code ec;
  if (given.empty()) throw input_error("-o", "", "\"\"", "an output " + what + " is required");
  fs::path absolute = fs::absolute(given, ec);
  if (ec) throw input_error(given.string(), "", "", "cannot resolve the output " + what);
  if (!absolute.has_filename()) absolute = absolute.parent_path();
  return absolute;
}

// Creates the output's parent folder if needed and checks that it is writable.
void prepare_parent(const fs::path& output) {
  std::error_code ec;
  const fs::path parent = output.parent_path();
  if (!fs::is_directory(parent, ec)) {
    fs::create_directories(parent, ec);
    if (ec) throw input_error(parent.string(), "", "", "output parent folder cannot be created");
  }
  if (::access(parent.c_str(), W_OK) != 0)
    throw input_error(parent.string(), "", "", "output parent folder is not writable");
}
}  // namespace

void install_interrupt_handlers() {
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
}
bool interrupted() { return g_interrupted.load(std::memory_order_relaxed); }
void throw_if_interrupted() {
  if (interrupted()) throw Interrupted();
}
void request_interrupt() { g_interrupted.store(true); }
void clear_interrupt() { g_interrupted.store(false); }

OutputFolder::OutputFolder(fs::path final_dir, std::string command,
                           const std::vector<fs::path>& inputs)
    : command_(std::move(command)) {
  std::error_code ec;
  final_ = absolute_output(final_dir, "folder");
  if (fs::exists(final_, ec) && !fs::is_directory(final_, ec))
    throw input_error(final_.string(), "", "", "exists and is not a folder");
  // An input of the run inside DIR would be deleted by the exchange (or DIR is one).
  const fs::path real_dir = fs::weakly_canonical(final_, ec);
  for (const fs::path& input : inputs) {
    if (input.empty()) continue;
    const fs::path real_input = fs::weakly_canonical(fs::absolute(input, ec), ec);
    if (!ec && contains(real_dir, real_input))
      throw input_error(final_.string(), "", "",
                        "is or holds an input of this run (" + input.string() +
                            "); choose another output folder");
  }
  if (fs::exists(final_, ec))
    if (const std::string why = refusal(final_); !why.empty())
      throw input_error(final_.string(), "", "", why);
  prepare_parent(final_);
  remove_stale_temporaries(final_);
  temp_ = make_temporary(final_, true);
}

OutputFolder::~OutputFolder() {
  if (!committed_ && !temp_.empty()) {
    std::error_code ec;
    fs::remove_all(temp_, ec);
  }
}

void OutputFolder::commit() {
  throw_if_interrupted();  // asked to stop: keep the previous result
  std::string marker = std::string(kOutputMarkerSignature) + "\ncommand: " + command_ + "\n";
  std::error_code ec;
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(temp_, ec))
    names.insert(e.path().filename().string());
  for (const auto& name : names) marker += "file: " + name + "\n";
  write_text_file(temp_ / kOutputMarker, marker);
  sync_tree(temp_);  // durable before it becomes the result
  if (fs::exists(final_, ec)) {
    // One atomic exchange where the file system offers it: DIR is never missing, not even for
    // an instant; the previous result ends up in the temporary folder and is removed with it.
    if (::renameat2(AT_FDCWD, temp_.c_str(), AT_FDCWD, final_.c_str(), RENAME_EXCHANGE) == 0) {
      committed_ = true;
      sync_path(final_.parent_path());
      fs::remove_all(temp_, ec);
      return;
    }
  }
  fs::path old;
  if (fs::exists(final_, ec)) {
    old = temp_.string() + ".old";
    fs::rename(final_, old, ec);
    if (ec)
      throw input_error(final_.string(), "", "",
                        "cannot replace the previous result: " + ec.message());
  }
  fs::rename(temp_, final_, ec);
  if (ec) {
    if (!old.empty()) fs::rename(old, final_, ec);
    throw input_error(final_.string(), "", "", "cannot move the result into place");
  }
  committed_ = true;
  sync_path(final_.parent_path());
  if (!old.empty()) fs::remove_all(old, ec);
}

OutputFile::OutputFile(fs::path final_file) {
  final_ = absolute_output(final_file, "file");
  std::error_code ec;
  if (fs::is_directory(final_, ec))
    throw input_error(final_.string(), "", "", "is a folder: a file name was expected");
  if (fs::exists(final_, ec) && !fs::is_regular_file(final_, ec))
    throw input_error(final_.string(), "", "", "exists and is not a regular file");
  prepare_parent(final_);
  remove_stale_temporaries(final_);
  temp_ = make_temporary(final_, false);
}

OutputFile::~OutputFile() {
  if (!committed_ && !temp_.empty()) {
    std::error_code ec;
    fs::remove(temp_, ec);
  }
}

void OutputFile::commit() {
  throw_if_interrupted();
  sync_path(temp_);
  if (::rename(temp_.c_str(), final_.c_str()) != 0) throw_write_error(final_, errno);
  committed_ = true;
  sync_path(final_.parent_path());
}

}  // namespace shpb
