#include "core/output_folder.hpp"

#include <fcntl.h>  // AT_FDCWD
#include <signal.h>
#include <stdio.h>  // renameat2
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <random>
#include <string>
#include <system_error>

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

// ".<name>.tmp-<pid>-<random>" (and its ".old" twin): the temporary folders of this scheme.
std::string temp_prefix(const fs::path& final_dir) {
  std::string prefix = ".";
  prefix += final_dir.filename().string();
  prefix += ".tmp-";
  return prefix;
}

// Temporary folders left by a run that was killed outright (SIGKILL, power loss) are removed
// when the next run starts: their owner process is gone. Only names of our own scheme are touched.
void remove_stale_temporaries(const fs::path& final_dir) {
  const std::string prefix = temp_prefix(final_dir);
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(final_dir.parent_path(), ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const std::string rest = name.substr(prefix.size());
    const auto dash = rest.find('-');
    if (dash == 0 || dash == std::string::npos ||
        rest.substr(0, dash).find_first_not_of("0123456789") != std::string::npos)
      continue;
    const long pid = std::stol(rest.substr(0, dash));
    if (pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) {
      std::error_code rm;
      fs::remove_all(e.path(), rm);
    }
  }
}

bool written_by_shpb(const fs::path& dir) {
  std::error_code ec;
  if (fs::is_empty(dir, ec)) return true;
  return fs::exists(dir / "summary.json", ec);
}
}  // namespace

void install_interrupt_handlers() {
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
}
bool interrupted() { return g_interrupted.load(std::memory_order_relaxed); }

OutputFolder::OutputFolder(fs::path final_dir) : final_(std::move(final_dir)) {
  std::error_code ec;
  if (final_.empty()) throw input_error("-o", "", "\"\"", "an output folder is required");
  fs::path absolute = fs::absolute(final_, ec);
  if (ec) throw input_error(final_.string(), "", "", "cannot resolve the output folder");
  if (!absolute.has_filename()) absolute = absolute.parent_path();
  final_ = absolute;
  if (fs::exists(final_, ec) && !fs::is_directory(final_, ec))
    throw input_error(final_.string(), "", "", "exists and is not a folder");
  if (fs::exists(final_, ec) && !written_by_shpb(final_))
    throw input_error(
        final_.string(), "", "",
        "exists, is not empty and holds no shpb summary.json; refusing to replace it");
  const fs::path parent = final_.parent_path();
  if (!fs::is_directory(parent, ec)) {
    fs::create_directories(parent, ec);
    if (ec) throw input_error(parent.string(), "", "", "output parent folder cannot be created");
  }
  if (::access(parent.c_str(), W_OK) != 0)
    throw input_error(parent.string(), "", "", "output parent folder is not writable");
  remove_stale_temporaries(final_);
  std::random_device rd;
  for (int attempt = 0; attempt < 100; ++attempt) {
    const std::string name =  // hidden sibling: ".<name>.tmp-<pid>-<random>"
        temp_prefix(final_) + std::to_string(::getpid()) + "-" + std::to_string(rd() % 100000);
    const fs::path candidate = parent / name;
    if (fs::create_directory(candidate, ec)) {
      temp_ = candidate;
      return;
    }
  }
  throw input_error(parent.string(), "", "", "cannot create a temporary output folder");
}

OutputFolder::~OutputFolder() {
  if (!committed_ && !temp_.empty()) {
    std::error_code ec;
    fs::remove_all(temp_, ec);
  }
}

void OutputFolder::commit() {
  if (interrupted()) throw Interrupted();  // asked to stop: keep the previous result
  std::error_code ec;
  if (fs::exists(final_, ec)) {
    // One atomic exchange where the file system offers it: DIR is never missing, not even for
    // an instant; the previous result ends up in the temporary folder and is removed with it.
    if (::renameat2(AT_FDCWD, temp_.c_str(), AT_FDCWD, final_.c_str(), RENAME_EXCHANGE) == 0) {
      committed_ = true;
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
  if (!old.empty()) fs::remove_all(old, ec);
}

}  // namespace shpb
