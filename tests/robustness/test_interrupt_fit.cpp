// Interrupting `shpb fit` (docs/outputs.md (conventions)) in each of its phases: reading and
// processing the tests, the first simulations, the curve stage, the signals stage's iterations,
// the covariance and step check at the solution, the final simulations and the writing. A SIGINT
// or SIGTERM ends it within a second with exit 130 and no output folder, nothing half-written
// beside it. The phases are found by the fit's progress lines on stderr, so the signal lands in
// the phase on any machine; the covariance is reached by the last iteration line of an
// uninterrupted run (the fit is deterministic: the same lines in the same order).
#include <signal.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <functional>
#include <string>
#include <thread>

#include "../fit/synthetic_scene.hpp"
#include "child_process.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_robustness_test_interrupt_fit {

namespace {

using namespace shpb_robust;

constexpr double kLimit_s = 300.0;  // a hang, not a slow machine (a sanitizer build fits slowly)

// A 1 µs strain-rate filter and asynchronous stepping: the synthetic campaign of the fit's
// recovery test (tests/fit/test_fit_synthetic.cpp).
const fs::path kCopper = fs::path(SHPB_SOURCE_DIR) / "specimens/ofhc-copper.json";

// The stderr lines so far.
std::vector<std::string> lines_of(const fs::path& file) {
  std::vector<std::string> lines;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// Waits until `count` lines of the child's stderr satisfy `match` (or the child ends).
bool wait_for_lines(const Child& child, const std::function<bool(const std::string&)>& match,
                    std::size_t count) {
  const auto limit = std::chrono::steady_clock::now() + std::chrono::duration<double>(kLimit_s);
  while (std::chrono::steady_clock::now() < limit) {
    std::size_t n = 0;
    for (const auto& line : lines_of(child.err_file())) n += match(line) ? 1 : 0;
    if (n >= count) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return false;
}

bool starts(const std::string& line, const std::string& prefix) {
  return line.rfind(prefix, 0) == 0;
}

}  // namespace

TEST_CASE("SIGINT and SIGTERM stop fit within a second in every phase, nothing written",
          "[robustness][interrupt][fit]") {
  ScratchFolder scratch("interrupt_fit");
  const fs::path campaign =
      shpb_test::write_synthetic_campaign(scratch.path(), kCopper, "1 us", "asynchronous", 2024);
  const fs::path out = scratch.path() / "out";
  const std::vector<std::string> args = {"fit", campaign.string(), "-o", out.string(), "--threads",
                                         "2",   "--bootstrap",     "0"};
  // An uninterrupted run: its iteration lines, of the curve stage and then of the signals stage
  // (whose last one ends the solve: the covariance follows).
  std::size_t curve_iterations = 0, signals_iterations = 0;
  {
    const Outcome o = run(args, scratch.path(), kLimit_s);
    INFO(o.err);
    REQUIRE(o.code == 0);
    std::istringstream err(o.err);
    bool signals = false;
    for (std::string line; std::getline(err, line);) {
      signals = signals || starts(line, "fit: stage signals:");
      if (starts(line, "fit: iteration")) ++(signals ? signals_iterations : curve_iterations);
    }
    REQUIRE(signals_iterations > 2);
    fs::remove_all(out);
  }
  const auto iteration = [](const std::string& l) { return starts(l, "fit: iteration"); };
  struct Phase {
    const char* name;
    std::function<bool(const std::string&)> match;
    std::size_t count;
  };
  const std::vector<Phase> phases = {
      {"reading and processing the tests", [](const std::string&) { return true; }, 0},
      {"the first simulations", [](const std::string& l) { return starts(l, "fit: campaign"); }, 1},
      {"the curve stage", [](const std::string& l) { return starts(l, "fit: stage curve:"); }, 1},
      {"the signals stage's start",
       [](const std::string& l) { return starts(l, "fit: stage signals:"); }, 1},
      {"an iteration midway", iteration, curve_iterations + signals_iterations / 2},
      {"the covariance and step check after the last iteration", iteration,
       curve_iterations + signals_iterations},
      {"the final simulations and the writing",
       [](const std::string& l) { return starts(l, "fit: stage signals done"); }, 1}};
  int k = 0;
  for (const auto& phase : phases) {
    const int sig = k++ % 2 ? SIGTERM : SIGINT;
    INFO("signal " << sig << " in " << phase.name);
    Child child(args, scratch.path());
    REQUIRE(child.started());
    REQUIRE(child.wait_until_interruptible(kLimit_s));
    REQUIRE(wait_for_lines(child, phase.match, phase.count));
    child.signal(sig);
    const Outcome o = child.wait(kLimit_s);
    INFO(o.err);
    CHECK(o.signal == 0);  // no crash (SIGSEGV was seen in the covariance)
    CHECK(o.code == 130);
    CHECK(o.seconds < prompt_exit_s());
    CHECK_FALSE(fs::exists(out));
    CHECK(litter(scratch.path()).empty());
  }
}

}  // namespace tests_robustness_test_interrupt_fit
