#include "core/output_folder.hpp"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <random>
#include <system_error>

#include "core/error.hpp"

namespace shpb {
namespace fs = std::filesystem;

namespace {
std::atomic<bool> g_interrupted{false};  // the one global: a signal handler cannot reach others
extern "C" void on_signal(int) { g_interrupted.store(true); }

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
    throw input_error(final_.string(), "", "",
                      "exists, is not empty and holds no shpb summary.json; refusing to replace it");
  const fs::path parent = final_.parent_path();
  if (!fs::is_directory(parent, ec)) {
    fs::create_directories(parent, ec);
    if (ec) throw input_error(parent.string(), "", "", "output parent folder cannot be created");
  }
  if (::access(parent.c_str(), W_OK) != 0)
    throw input_error(parent.string(), "", "", "output parent folder is not writable");
  std::random_device rd;
  for (int attempt = 0; attempt < 100; ++attempt) {
    std::string name = ".";  // hidden sibling: ".<name>.tmp-<pid>-<random>"
    name += final_.filename().string();
    name += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(rd() % 100000);
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
  std::error_code ec;
  fs::path old;
  if (fs::exists(final_, ec)) {
    old = temp_.string() + ".old";
    fs::rename(final_, old, ec);
    if (ec) throw input_error(final_.string(), "", "", "cannot replace the previous result: " + ec.message());
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
