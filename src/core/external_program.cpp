#include "core/external_program.hpp"

#include <dlfcn.h>  // dladdr
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <thread>

#include "core/interrupt.hpp"  // interrupted()

extern char** environ;

namespace shpb {

namespace fs = std::filesystem;

namespace {

// An unnamed temporary file (removed when closed) that the program's stderr is written to (its
// descriptor closed in the program, which writes to its copy, fd 2).
struct ErrorsFile {
  int fd = -1;
  ErrorsFile() {
    std::string name = (fs::temp_directory_path() / "shpb-errors-XXXXXX").string();
    fd = ::mkostemp(name.data(), O_CLOEXEC);
    if (fd >= 0) ::unlink(name.c_str());
  }
  ~ErrorsFile() {
    if (fd >= 0) ::close(fd);
  }
  std::string text() const {
    std::string s;
    char buffer[4096];
    ::lseek(fd, 0, SEEK_SET);
    for (ssize_t n; (n = ::read(fd, buffer, sizeof buffer)) > 0;) s.append(buffer, n);
    return s;
  }
};

}  // namespace

int run_program(const std::vector<std::string>& argv, bool quiet, std::string* errors) {
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (quiet || errors) posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  if (quiet) posix_spawn_file_actions_adddup2(&actions, 1, 2);
  std::optional<ErrorsFile> captured;
  if (errors) {
    captured.emplace();
    if (captured->fd < 0) {
      posix_spawn_file_actions_destroy(&actions);
      return -1;
    }
    posix_spawn_file_actions_adddup2(&actions, captured->fd, 2);
  }
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) return -1;
  // SIGINT/SIGTERM to shpb alone (kill PID) would not reach the program: it is passed on once
  // (a Ctrl-C on a terminal reaches both). The program stops on it within milliseconds, or puts
  // its result in place if it was doing so: ended outright only if it hangs (kGrace), not in the
  // middle of its few renames (the report's figures/ would be left missing).
  constexpr auto kGrace = std::chrono::seconds(10);
  constexpr auto kPoll = std::chrono::milliseconds(5);
  int status = 0;
  std::optional<std::chrono::steady_clock::time_point> told;
  for (;;) {
    const pid_t done = waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) return -1;
    if (interrupted() && !told) {
      ::kill(pid, SIGTERM);
      told = std::chrono::steady_clock::now();
    } else if (told && std::chrono::steady_clock::now() - *told > kGrace) {
      ::kill(pid, SIGKILL);
    }
    std::this_thread::sleep_for(kPoll);
  }
  if (errors) *errors = captured->text();
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::optional<fs::path> find_installed(const std::string& name) {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return std::nullopt;
  for (const fs::path& c : {exe.parent_path().parent_path() / "share" / "shpb" / name,
                            exe.parent_path() / "share" / "shpb" / name})
    if (fs::is_regular_file(c, ec)) return c;
  // Not the executable's code: a module loaded into another program (Python's).
  Dl_info own{};
  if (::dladdr(reinterpret_cast<void*>(&find_installed), &own) == 0 || !own.dli_fname)
    return std::nullopt;
  const fs::path module = fs::absolute(own.dli_fname, ec);
  if (ec || fs::equivalent(module, exe, ec)) return std::nullopt;
  for (fs::path dir = module.parent_path(); !dir.empty(); dir = dir.parent_path()) {
    if (const fs::path c = dir / "share" / "shpb" / name; fs::is_regular_file(c, ec)) return c;
    if (dir == dir.root_path()) break;
  }
  return std::nullopt;
}

std::optional<std::string> find_python(const std::string& check) {
  for (const std::string python : {"/usr/bin/python3", "python3"}) {
    if (run_program({python, "-c", check}, true) == 0) return python;
    throw_if_interrupted();  // the check was stopped, not failed
  }
  return std::nullopt;
}

}  // namespace shpb
