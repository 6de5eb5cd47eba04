// `shpb report DIR`: figures and a one-page HTML report of an output folder. The plotting lives in
// the Python package tools/shpb_report/ (matplotlib) behind the entry script tools/report.py; this
// file finds the script and a Python that can import matplotlib and numpy, and runs it.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "core/error.hpp"

extern char** environ;

namespace shpb {
namespace {

namespace fs = std::filesystem;

// Runs `argv` (argv[0] looked up on PATH) and returns its exit status, or -1 if it could not be
// started or died from a signal. With `quiet`, its stdout and stderr go to /dev/null.
int run_program(const std::vector<std::string>& argv, bool quiet) {
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (quiet) {
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
  }
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) return -1;
  int status = 0;
  if (waitpid(pid, &status, 0) < 0 || !WIFEXITED(status)) return -1;
  return WEXITSTATUS(status);
}

// The report script is found from the executable alone, so an installed shpb works without the
// source tree: PREFIX/bin/shpb → PREFIX/share/shpb/report.py (its package in
// share/shpb/shpb_report/); build/shpb → build/share/shpb/ (CMake copies both there).
std::optional<fs::path> find_script() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return std::nullopt;
  for (const fs::path& c : {exe.parent_path().parent_path() / "share" / "shpb" / "report.py",
                            exe.parent_path() / "share" / "shpb" / "report.py"})
    if (fs::is_regular_file(c, ec)) return c;
  return std::nullopt;
}

// Debian's python3-matplotlib belongs to /usr/bin/python3, which may not be the first python3
// on PATH (README.md (Layout)): try it first.
std::optional<std::string> find_python() {
  for (const std::string python : {"/usr/bin/python3", "python3"})
    if (run_program({python, "-c", "import matplotlib, numpy"}, true) == 0) return python;
  return std::nullopt;
}

}  // namespace

int run_report(const ReportArgs& args) {
  const auto script = find_script();
  if (!script)
    throw input_error("report", "share/shpb/report.py", "not found",
                      "the report script is installed beside the executable (cmake --install)");
  const auto python = find_python();
  if (!python)
    throw input_error("report", "python3", "matplotlib/numpy not importable",
                      "install python3-matplotlib and python3-numpy (bash tools/install-deps.sh)");
  const int rc = run_program({*python, script->string(), args.folder.string()}, false);
  // 2 bad input, 3 not written, 4 a bug of the script: it printed its own `error:` line.
  if (rc == 0 || rc == 2 || rc == 3 || rc == 4) return rc;
  std::fprintf(stderr, "error: internal: %s %s exited with status %d\n", python->c_str(),
               script->c_str(), rc);
  return 4;
}

Command add_report_command(CLI::App& app) {
  auto args = std::make_shared<ReportArgs>();
  auto* cmd = app.add_subcommand(
      "report",
      "Turn an output folder of simulate/process/compare/study into PNG figures and one "
      "self-contained report.html (needs python3 with matplotlib)");
  cmd->add_option("folder", args->folder, "Output folder")
      ->required()
      ->check(CLI::ExistingDirectory);
  return {cmd, [args] { return run_report(*args); }};
}

}  // namespace shpb
