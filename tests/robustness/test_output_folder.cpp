// OutputFolder (core/output_folder.hpp): results appear all at once or not at all, the previous
// result survives a failed run, files the program did not write are never deleted, and
// temporary folders of killed runs do not pile up.
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <fstream>

#include "child_process.hpp"
#include "core/error.hpp"
#include "core/output_folder.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_robustness_test_output_folder {

namespace {
using namespace shpb_robust;

// The pid of a process that has just exited (and been reaped): no process has it now.
pid_t dead_pid() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  ::waitpid(pid, nullptr, 0);
  return pid;
}
}  // namespace

TEST_CASE("A committed output folder replaces the previous result and leaves nothing beside it",
          "[robustness][output]") {
  ScratchFolder scratch("folder");
  const fs::path out = scratch.path() / "out";
  std::string previous;
  for (const std::string run : {"first", "second"}) {
    shpb::OutputFolder folder(out);
    write_bytes(folder.file("summary.json"), run);
    CHECK(read_all(out / "summary.json") == previous);  // nothing new visible before commit
    previous = run;
    folder.commit();
    CHECK(read_all(out / "summary.json") == run);
  }
  std::size_t entries = 0;
  for (const auto& e : fs::directory_iterator(scratch.path())) entries += e.exists();
  CHECK(entries == 1);
}

TEST_CASE("An output folder that is not committed leaves the previous result untouched",
          "[robustness][output]") {
  ScratchFolder scratch("folder");
  const fs::path out = scratch.path() / "out";
  {
    shpb::OutputFolder first(out);
    write_bytes(first.file("summary.json"), "previous");
    first.commit();
  }
  {
    shpb::OutputFolder folder(out);
    write_bytes(folder.file("summary.json"), "half");
  }  // a failure: no commit
  CHECK(read_all(out / "summary.json") == "previous");
  CHECK(litter(scratch.path()).empty());
}

TEST_CASE("A folder holding files shpb did not write is never replaced", "[robustness][output]") {
  ScratchFolder scratch("folder");
  const fs::path out = scratch.path() / "out";
  fs::create_directory(out);
  write_bytes(out / "notes.txt", "mine");
  CHECK_THROWS_AS(shpb::OutputFolder(out), shpb::InputError);
  CHECK(read_all(out / "notes.txt") == "mine");
  CHECK(litter(scratch.path()).empty());
}

TEST_CASE("Folders that only look like temporaries of a dead run are kept",
          "[robustness][output]") {
  // Removing needs proof (the exact name with this host's tag and the marker inside naming host
  // and pid): a name alone, even with a dead pid, is not proof. The removal of a real killed run's
  // folder is tested through the executable (test_lost_data.cpp).
  ScratchFolder scratch("folder");
  const fs::path dead = scratch.path() / (".out.tmp-" + std::to_string(dead_pid()) + "-123");
  const fs::path dead_old = fs::path(dead.string() + ".old");
  const fs::path alive = scratch.path() / (".out.tmp-" + std::to_string(::getpid()) + "-7");
  const fs::path other = scratch.path() / ".other.tmp-1-1";  // another DIR's: not ours to judge
  const fs::path look_alike = scratch.path() / ".out.tmp-notes";
  for (const auto& d : {dead, dead_old, alive, other, look_alike}) fs::create_directory(d);
  shpb::OutputFolder folder(scratch.path() / "out");
  for (const auto& d : {dead, dead_old, alive, other, look_alike}) CHECK(fs::exists(d));
}

}  // namespace tests_robustness_test_output_folder
