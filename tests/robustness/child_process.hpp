#pragma once
// Runs the real `shpb` executable (shpb_exe()) with a time limit, or starts it and lets the test
// signal it: a robustness test must see a crash (killed by a signal) or a hang (time limit) as a
// result, not hang or die itself.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "../app/run_shpb.hpp"

namespace shpb_robust {

// "Promptly", "within a second": the program's loops poll for a signal and its readers check
// their limits before reading on. The sanitized suite runs the executable built with ASan + UBSan
// at -O1, about three times slower than the optimised one, and allows that factor.
constexpr double kPromptExit_s = 1.0;
constexpr double kSanitizerSlowdown = 3.0;
// On a machine with more runnable processes than cores (the 1-minute load average over the
// cores) a process gets that share of one, and a second of its work takes that much longer.
inline double load_slowdown() {
  double load = 0;
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  if (::getloadavg(&load, 1) != 1) return 1.0;
  return std::max(1.0, load / cores);
}
inline double prompt_exit_s() {
  return kPromptExit_s * (shpb_test::running_sanitized() ? kSanitizerSlowdown : 1.0) *
         load_slowdown();
}
// The size of an input that keeps a run as long in either build: the sanitized executable reads a
// third of it in the time the optimised one reads all (an interruption test needs a run long
// enough to land a signal in, not a longer one).
inline long same_run_length(long optimised_size) {
  return shpb_test::running_sanitized() ? static_cast<long>(optimised_size / kSanitizerSlowdown)
                                        : optimised_size;
}

namespace fs = std::filesystem;

struct Outcome {
  int code = -1;           // exit code if the process exited
  int signal = 0;          // the signal that killed it, if one did
  bool timed_out = false;  // killed by us after the time limit
  double seconds = 0;      // from start (or from signal()) to exit
  std::string out, err;
};

inline std::string read_all(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class Child {
 public:
  // Starts `shpb args...`; stdout and stderr go to files in `scratch`; the signals of `blocked`
  // blocked from its first instruction, if given.
  Child(const std::vector<std::string>& args, const fs::path& scratch,
        const sigset_t* blocked = nullptr)
      : out_(scratch / ".child.out"), err_(scratch / ".child.err") {
    pid_ = shpb_test::spawn_shpb(args, out_, err_, blocked);
    start_ = std::chrono::steady_clock::now();
  }
  // The same with `pending` raised (and blocked) in the process before it executes shpb: pending
  // at shpb's first instruction, whatever the machine's load (a signal sent after the start can
  // come after shpb's own code has begun).
  Child(const std::vector<std::string>& args, const fs::path& scratch, int pending)
      : out_(scratch / ".child.out"), err_(scratch / ".child.err") {
    shpb_test::ShpbArgv command(args);
    sigset_t blocked;
    sigemptyset(&blocked);
    sigaddset(&blocked, pending);
    const std::string out = out_.string(), err = err_.string();
    pid_ = ::fork();  // after it, only async-signal-safe calls until the exec
    if (pid_ == 0) {
      const int o = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (o < 0 || e < 0 || ::dup2(o, 1) < 0 || ::dup2(e, 2) < 0) ::_exit(127);
      ::sigprocmask(SIG_SETMASK, &blocked, nullptr);
      ::kill(::getpid(), pending);
      ::execv(command.argv[0], command.argv.data());
      ::_exit(127);
    }
    start_ = std::chrono::steady_clock::now();
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;
  ~Child() {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }

  bool started() const { return pid_ > 0; }
  pid_t pid() const { return pid_; }
  // The file the process's stderr goes to (read while it runs: its progress lines).
  const fs::path& err_file() const { return err_; }

  // Waits at most `limit_s` until the process catches SIGINT and SIGTERM (Linux: the SigCgt mask
  // of /proc/<pid>/status): shpb's main has installed its handlers, so a signal from now on tests
  // the interruption, however slow the machine (a sanitizer build on a loaded machine can take
  // longer than 0.1 s to get there). False if it never did.
  bool wait_until_interruptible(double limit_s) const {
    const fs::path status = fs::path("/proc") / std::to_string(pid_) / "status";
    const unsigned long long wanted = (1ull << (SIGINT - 1)) | (1ull << (SIGTERM - 1));
    const auto limit = std::chrono::steady_clock::now() + std::chrono::duration<double>(limit_s);
    while (pid_ > 0 && std::chrono::steady_clock::now() < limit) {
      std::ifstream in(status);
      for (std::string line; std::getline(in, line);)
        if (line.rfind("SigCgt:", 0) == 0 &&
            (std::stoull(line.substr(7), nullptr, 16) & wanted) == wanted)
          return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return false;
  }

  // Sends `sig` and restarts the clock, so wait() measures the time to react.
  void signal(int sig) {
    if (pid_ > 0) ::kill(pid_, sig);
    start_ = std::chrono::steady_clock::now();
  }

  // Waits at most `limit_s`; a process still running then is killed and reported as timed out.
  Outcome wait(double limit_s) {
    Outcome o;
    if (pid_ <= 0) return o;
    int status = 0;
    const auto limit = start_ + std::chrono::duration<double>(limit_s);
    while (::waitpid(pid_, &status, WNOHANG) == 0) {
      if (std::chrono::steady_clock::now() > limit) {
        o.timed_out = true;
        ::kill(pid_, SIGKILL);
        ::waitpid(pid_, &status, 0);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    pid_ = -1;
    if (WIFEXITED(status)) o.code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) o.signal = WTERMSIG(status);
    o.out = read_all(out_);
    o.err = read_all(err_);
    fs::remove(out_);
    fs::remove(err_);
    return o;
  }

 private:
  fs::path out_, err_;
  pid_t pid_ = -1;
  std::chrono::steady_clock::time_point start_;
};

inline Outcome run(const std::vector<std::string>& args, const fs::path& scratch, double limit_s) {
  Child child(args, scratch);
  return child.wait(limit_s);
}

// How long `shpb args...` runs uninterrupted from the moment it can be interrupted to its exit
// (its start-up excluded): signal times as fractions of it land inside the work on any machine.
inline double seconds_after_startup(const std::vector<std::string>& args, const fs::path& scratch,
                                    double limit_s) {
  Child child(args, scratch);
  if (!child.started() || !child.wait_until_interruptible(limit_s)) return 0;
  child.signal(0);  // no signal: restarts the clock
  return child.wait(limit_s).seconds;
}

// Runs `shpb args...` and sends it `sig` `delay_s` after it can be interrupted. A run faster than
// the one timed that ends first with exit 2 (the work it was given holds no answer) gets the
// signal twice as early, up to five times. `delay_s` is left at the delay of the last attempt.
inline Outcome interrupted_run(const std::vector<std::string>& args, const fs::path& scratch,
                               int sig, double& delay_s, double limit_s) {
  Outcome o;
  for (int attempt = 0; attempt < 5; ++attempt, delay_s /= 2) {
    Child child(args, scratch);
    if (!child.started() || !child.wait_until_interruptible(limit_s)) return o;
    std::this_thread::sleep_for(std::chrono::duration<double>(delay_s));
    child.signal(sig);
    o = child.wait(limit_s);
    if (o.code != 2) break;
  }
  return o;
}

// A fresh empty scratch folder per object (a counter tells apart those of one process), removed
// with the object.
class ScratchFolder : public shpb_test::ScratchDir {
 public:
  explicit ScratchFolder(const std::string& tag)
      : ScratchDir("robust_" + tag + "_" + std::to_string(counter_++)) {}

 private:
  static inline int counter_ = 0;
};

inline void write_bytes(const fs::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
}

// The pid of a process that has just exited (and been reaped): no process has it now.
inline pid_t dead_pid() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  ::waitpid(pid, nullptr, 0);
  return pid;
}

// Entries of `dir` whose names hold ".tmp" (temporary output folders left behind).
inline std::vector<std::string> litter(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().find(".tmp") != std::string::npos)
      found.push_back(e.path().filename().string());
  return found;
}

}  // namespace shpb_robust
