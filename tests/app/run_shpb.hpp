#pragma once
// Runs the real `shpb` executable (shpb_exe()) as a user would, without a shell in between, and
// returns its exit code with stdout and stderr. spawn_shpb is the one way every test starts it.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../scratch.hpp"

extern char** environ;

namespace shpb_test {

struct RunResult {
  int code = -1;  // exit code, or -1 if the process did not exit normally
  std::string out;
  std::string err;
};

inline std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// True if a Python that `shpb report` would run (/usr/bin/python3 first, then python3 on PATH;
// src/app/report.cpp) imports matplotlib and numpy. Report tests skip without it.
inline bool have_matplotlib() {
  return std::system("/usr/bin/python3 -c 'import matplotlib, numpy' >/dev/null 2>&1") == 0 ||
         std::system("python3 -c 'import matplotlib, numpy' >/dev/null 2>&1") == 0;
}

// The executable under test: $SHPB_EXE, which CTest sets to the sanitized build's for the sanitized
// suite (CMakeLists.txt), else the optimised build's.
inline const char* shpb_exe() {
  const char* given = std::getenv("SHPB_EXE");
  return given && *given ? given : SHPB_EXE;
}

// True in the sanitized test binary: the AddressSanitizer runtime is linked in (a weak reference
// that the optimised binary leaves null).
extern "C" void __asan_init() __attribute__((weak));
inline bool running_sanitized() { return &__asan_init != nullptr; }

// `shpb args...` as an exec's argument vector: `text` holds the strings, `argv` points into them.
struct ShpbArgv {
  std::vector<std::string> text;
  std::vector<char*> argv;
  explicit ShpbArgv(const std::vector<std::string>& args) : text{shpb_exe()} {
    text.insert(text.end(), args.begin(), args.end());
    for (auto& a : text) argv.push_back(a.data());
    argv.push_back(nullptr);
  }
  ShpbArgv(const ShpbArgv&) = delete;  // argv points into text
  ShpbArgv& operator=(const ShpbArgv&) = delete;
};

// Starts `shpb args...` with stdout and stderr written to the files `out` and `err` (truncated;
// "/dev/null" discards), and the signals of `blocked` blocked, if given, from before its first
// instruction. Returns the child's pid, or -1 if it could not be started.
inline pid_t spawn_shpb(const std::vector<std::string>& args, const std::filesystem::path& out,
                        const std::filesystem::path& err, const sigset_t* blocked = nullptr) {
  ShpbArgv command(args);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  if (blocked) {
    posix_spawnattr_setsigmask(&attributes, blocked);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK);
  }
  pid_t pid = 0;
  if (posix_spawn(&pid, shpb_exe(), &actions, &attributes, command.argv.data(), environ) != 0)
    pid = -1;
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

inline RunResult run_shpb(const std::vector<std::string>& args) {
  static const ScratchDir streams("streams");  // the child's stdout and stderr
  const auto out = streams.path() / "out", err = streams.path() / "err";
  RunResult r;
  if (const pid_t pid = spawn_shpb(args, out, err); pid > 0) {
    int status = 0;
    if (waitpid(pid, &status, 0) == pid && WIFEXITED(status)) r.code = WEXITSTATUS(status);
  }
  r.out = read_text(out);
  r.err = read_text(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

}  // namespace shpb_test
