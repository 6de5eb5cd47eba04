// Interrupting a long `shpb simulate` (docs/outputs.md (conventions)): SIGINT or SIGTERM ends it
// promptly, the previous results in the output folder stay as they were, no temporary folder is
// left beside it, and the next run completes normally.
#include <signal.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <string>
#include <thread>

#include "child_process.hpp"
#include "striker_on_bar_scene.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_robustness_test_interrupt {

namespace {

using namespace shpb_robust;

// Least time the long run gets before it is interrupted.
constexpr double kRunBeforeSignal_s = 0.5;
constexpr double kHangLimit_s = 60.0;

std::vector<std::string> simulate(const fs::path& dir, const std::string& scene_file) {
  return {"simulate", (dir / scene_file).string(), "-o", (dir / "out").string(), "--quiet"};
}

}  // namespace

TEST_CASE("An interrupted simulation exits promptly and leaves the previous results intact",
          "[robustness][interrupt]") {
  const int sig = GENERATE(SIGINT, SIGTERM);
  INFO("signal " << sig);
  ScratchFolder scratch("interrupt");
  const fs::path& dir = scratch.path();
  write_bytes(dir / "short.json", striker_on_bar_scene("300 us"));
  write_bytes(dir / "long.json", striker_on_bar_scene("5 s", "100 kHz"));

  const Outcome first = run(simulate(dir, "short.json"), dir, kHangLimit_s);
  INFO(first.err);
  REQUIRE(first.code == 0);
  const std::string previous = read_all(dir / "out" / "gauges.csv");
  REQUIRE_FALSE(previous.empty());

  Child child(simulate(dir, "long.json"), dir);
  REQUIRE(child.started());
  // Signal once the run is under way: at least kRunBeforeSignal_s, and its temporary output
  // folder exists (a loaded machine or the sanitizers can make start-up slower than that).
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  while ((elapsed() < kRunBeforeSignal_s || litter(dir).empty()) && elapsed() < kHangLimit_s)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  REQUIRE_FALSE(litter(dir).empty());
  child.signal(sig);
  const Outcome stopped = child.wait(kHangLimit_s);
  INFO(stopped.err);
  CHECK(stopped.signal == 0);  // it handled the signal, was not killed by it
  CHECK(stopped.code == 130);  // "interrupted" (main.cpp)
  CHECK(stopped.seconds < prompt_exit_s());
  CHECK(read_all(dir / "out" / "gauges.csv") == previous);
  CHECK(litter(dir).empty());
  std::size_t entries = 0;  // short.json, long.json, out: nothing else appeared
  for (const auto& e : fs::directory_iterator(dir))
    entries += e.path().filename().string()[0] != '.' ? 1 : 0;
  CHECK(entries == 3);

  const Outcome again = run(simulate(dir, "short.json"), dir, kHangLimit_s);
  INFO(again.err);
  CHECK(again.code == 0);
  CHECK(fs::exists(dir / "out" / "summary.json"));
  CHECK(litter(dir).empty());
}

TEST_CASE("An interrupted campaign shard leaves nothing, not even the parts folder",
          "[robustness][interrupt]") {
  // --shard K/N writes DIR/parts/K-of-N/; the run made DIR/parts/ before its output folder, and
  // an interrupted (or failed) shard left it, with DIR, behind, empty.
  ScratchFolder scratch("interrupt");
  const fs::path out = scratch.path() / "campaign";
  const fs::path scene =
      fs::path(SHPB_SOURCE_DIR) / "experiments" / "lanl-cu-ofe-273k" / "scene.json";
  // 20 000 draws of the scene's measurement.uncertainty: seconds of work to land a signal in.
  double delay_s = kRunBeforeSignal_s;
  const Outcome o = interrupted_run({"process", scene.string(), "--shard", "0/1", "--draws",
                                     "20000", "-o", out.string(), "--quiet"},
                                    scratch.path(), SIGINT, delay_s, kHangLimit_s);
  INFO(o.err);
  CHECK(o.code == 130);
  CHECK(o.seconds < prompt_exit_s());
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("A signal before shpb's own code runs ends every command with exit 130, nothing written",
          "[robustness][interrupt]") {
  // A signal in the first milliseconds (while the options were parsed) killed shpb outright, or,
  // pending while its parent kept it blocked across the exec, was never taken: the run went on
  // and wrote its result. The handlers are installed before anything of shpb runs and unblock
  // the two signals (main.cpp): the signal, pending from before the first instruction, must end
  // each command with 130 (docs/commands.md, Exit codes), nothing written, no temporary left.
  const int sig = GENERATE(SIGINT, SIGTERM);
  const fs::path experiments = fs::path(SHPB_SOURCE_DIR) / "experiments";
  const std::string classic = (experiments / "classic-al6061" / "scene.json").string();
  const std::string copper = (experiments / "lanl-cu-ofe-273k" / "scene.json").string();
  const std::string campaign = (experiments / "lanl-cu-ofe-273k" / "campaign.json").string();
  const std::string planned = (experiments / "plan-al6061" / "scene.json").string();
  ScratchFolder scratch("early_signal");
  const std::string out = (scratch.path() / "out").string();
  const std::vector<std::vector<std::string>> commands = {
      {"simulate", classic, "-o", out},
      {"process", copper, "-o", out},
      {"compare", copper, "-o", out},
      {"dispersion", "--poisson", "0.33", "-o", out},
      {"study", classic, "-o", out, "--sweep", "stability", "--contact", "penalty"},
      {"validate", classic},
      {"report", out},
      {"fit", campaign, "-o", out, "--max-iterations", "1"},
      {"calibrate", classic, "-o", out},
      {"plan", planned, "--rate", "1000", "-o", out}};
  for (const auto& command : commands) {
    INFO("signal " << sig << ", shpb " << command.front());
    Child child(command, scratch.path(), sig);
    REQUIRE(child.started());
    const Outcome o = child.wait(kHangLimit_s);
    INFO(o.err);
    CHECK(o.signal == 0);
    CHECK(o.code == 130);
    CHECK(o.out.empty());  // validate printed no set-up
    CHECK_FALSE(fs::exists(out));
    CHECK(litter(scratch.path()).empty());
  }
}

}  // namespace tests_robustness_test_interrupt
