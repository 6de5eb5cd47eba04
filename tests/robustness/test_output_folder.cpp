// OutputFolder (core/output_folder.hpp): results appear all at once or not at all, the previous
// result survives a failed run, files the program did not write are never deleted, and
// temporary folders of killed runs do not pile up.
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <fstream>

#include "child_process.hpp"
#include "core/error.hpp"
#include "core/file_digest.hpp"
#include "core/output_folder.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_robustness_test_output_folder {

namespace {
using namespace shpb_robust;

// The marker of a temporary folder of process `pid` on this host (core/output_folder.cpp).
std::string marker(pid_t pid) {
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  return "shpb temporary output: removed once its process is gone\nhost: " + std::string(host) +
         "\npid: " + std::to_string(pid) + "\n";
}

// The name a temporary of process `pid` on this host has for the output "out": the scheme
// of core/output_folder.cpp, ".<name>.tmp-<pid>-<16 hex digits of the host name's
// FNV-1a>-<random>".
std::string temporary_name(pid_t pid, int random) {
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  char tag[17];
  std::snprintf(tag, sizeof tag, "%016llx",
                static_cast<unsigned long long>(shpb::fnv1a64(std::string(host))));
  return ".out.tmp-" + std::to_string(pid) + "-" + tag + "-" + std::to_string(random);
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

TEST_CASE("A file shpb wrote and the user edited since is never replaced", "[robustness][output]") {
  // The marker listed names only: a gauges.csv the user annotated was replaced by the next run
  // (docs/outputs.md, Ownership marker). Its digest no longer holds: refused, before the run and
  // when the run commits, and the edit is kept; an unedited result is still replaced.
  ScratchFolder scratch("folder");
  const fs::path out = scratch.path() / "out";
  for (const bool edit_during_run : {false, true}) {
    CAPTURE(edit_during_run);
    fs::remove_all(out);
    {
      shpb::OutputFolder first(out);
      write_bytes(first.file("summary.json"), "first");
      fs::create_directory(first.file("simulation"));
      write_bytes(first.file("simulation") / "gauges.csv", "time_s\n0\n");
      first.commit();
    }
    const fs::path edited = edit_during_run ? out / "summary.json" : out / "simulation/gauges.csv";
    if (!edit_during_run) {
      write_bytes(edited, "time_s\n0\n# my note\n");
      CHECK_THROWS_AS(shpb::OutputFolder(out), shpb::InputError);
    } else {
      shpb::OutputFolder second(out);
      write_bytes(second.file("summary.json"), "second");
      write_bytes(edited, "first, annotated");  // while the second run works
      CHECK_THROWS_AS(second.commit(), shpb::InputError);
    }
    CHECK(read_all(edited) == (edit_during_run ? "first, annotated" : "time_s\n0\n# my note\n"));
    CHECK(litter(scratch.path()).empty());
  }
  shpb::OutputFolder unedited(scratch.path() / "other");
  write_bytes(unedited.file("summary.json"), "one");
  unedited.commit();
  shpb::OutputFolder again(scratch.path() / "other");
  write_bytes(again.file("summary.json"), "two");
  again.commit();
  CHECK(read_all(scratch.path() / "other/summary.json") == "two");
}

TEST_CASE("A file the user adds inside a sub-folder shpb wrote is never deleted",
          "[robustness][output]") {
  // The marker's "file: figures" line covers the sub-folder by name: a PDF the user put into it
  // was deleted with the folder by the next run. Every file under a sub-folder must be one the
  // digest lines record; a sub-folder with its own marker (a campaign's test) is judged by it.
  ScratchFolder scratch("folder");
  const fs::path out = scratch.path() / "out";
  {
    shpb::OutputFolder first(out);
    fs::create_directories(first.file("figures"));
    write_bytes(first.file("figures") / "signals.png", "png");
    fs::create_directories(first.file("test-1"));
    write_bytes(first.file("test-1") / "curve.csv", "strain\n0\n");
    first.commit();
  }
  write_bytes(out / "figures" / "paper_fig1.pdf", "%PDF the user's figure");
  CHECK_THROWS_AS(shpb::OutputFolder(out), shpb::InputError);
  CHECK(read_all(out / "figures" / "paper_fig1.pdf") == "%PDF the user's figure");
  fs::remove(out / "figures" / "paper_fig1.pdf");
  {
    shpb::OutputFolder again(out);  // as written: replaced
    write_bytes(again.file("summary.json"), "two");
    again.commit();
  }
  CHECK(read_all(out / "summary.json") == "two");
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

TEST_CASE("A run killed while making its temporary folder leaves nothing the next run keeps",
          "[robustness][output]") {
  // make_temporary creates the folder, then writes its marker in one write: a SIGKILL in between
  // leaves the exact name with a dead pid and nothing inside, or a marker cut short. Nothing of
  // anyone's is in such a folder, so the next run into the same -o removes it; a folder that also
  // holds another file is not provably shpb's and stays.
  ScratchFolder scratch("folder");
  const pid_t pid = dead_pid();
  const fs::path empty = scratch.path() / temporary_name(pid, 1);
  const fs::path empty_marker = scratch.path() / temporary_name(pid, 2);
  const fs::path cut_marker = scratch.path() / temporary_name(pid, 3);
  const fs::path with_file = scratch.path() / temporary_name(pid, 4);
  const fs::path foreign_marker = scratch.path() / temporary_name(pid, 5);
  for (const auto& d : {empty, empty_marker, cut_marker, with_file, foreign_marker})
    fs::create_directory(d);
  write_bytes(empty_marker / ".shpb-temporary", "");
  write_bytes(cut_marker / ".shpb-temporary", "shpb temporary output: remo");
  write_bytes(with_file / ".shpb-temporary", "shpb temporary output: remo");
  write_bytes(with_file / "notes.txt", "the user's");
  write_bytes(foreign_marker / ".shpb-temporary", "something else");
  shpb::OutputFolder folder(scratch.path() / "out");
  CHECK_FALSE(fs::exists(empty));
  CHECK_FALSE(fs::exists(empty_marker));
  CHECK_FALSE(fs::exists(cut_marker));
  CHECK(fs::exists(with_file / "notes.txt"));
  CHECK(fs::exists(foreign_marker));
}

TEST_CASE("A run killed while committing leaves nothing the next run keeps",
          "[robustness][output]") {
  // commit() writes the result's marker, removes the temporary's, syncs (seconds for a large
  // field.csv), exchanges, then removes the previous result: a SIGKILL in any of these steps
  // leaves under the temporary's name a whole shpb result, new or previous, with or without the
  // temporary's marker, or a previous result partly removed. They were kept for ever (a kill
  // loop on simulate left one 5.7 MB folder per three kills); a folder holding a file its marker
  // does not list is not provably shpb's and stays.
  ScratchFolder scratch("folder");
  const pid_t pid = dead_pid();
  const auto result = [&](int random, const std::string& extra) {
    const fs::path d = scratch.path() / temporary_name(pid, random);
    fs::create_directories(d / "simulation");
    write_bytes(d / "gauges.csv", "time_s,incident\n0,0\n");
    write_bytes(d / "simulation" / "energy.csv", "time_s\n0\n");
    write_bytes(d / shpb::kOutputMarker, std::string(shpb::kOutputMarkerSignature) +
                                             "\ncommand: simulate\nfile: gauges.csv\n"
                                             "file: simulation\n");
    if (!extra.empty()) write_bytes(d / extra, extra == ".shpb-temporary" ? marker(pid) : "x");
    return d;
  };
  const fs::path whole = result(1, "");
  const fs::path with_notes = result(2, "notes.txt");
  const fs::path both_markers = result(3, ".shpb-temporary");
  shpb::OutputFolder folder(scratch.path() / "out");
  CHECK_FALSE(fs::exists(whole));
  CHECK(fs::exists(with_notes / "notes.txt"));
  CHECK_FALSE(fs::exists(both_markers));
}

TEST_CASE("A file the user adds to the previous result while a run is going is kept",
          "[robustness][output]") {
  // DIR is checked when the run starts; a study runs for hours, and the user may meanwhile put
  // notes into the previous result: the commit's exchange then removed them with it.
  ScratchFolder scratch("folder");
  const fs::path out = scratch.path() / "out";
  {
    shpb::OutputFolder first(out);
    write_bytes(first.file("summary.json"), "first");
    first.commit();
  }
  shpb::OutputFolder second(out);
  write_bytes(second.file("summary.json"), "second");
  write_bytes(out / "notes.txt", "the user's notes");  // while the second run works
  CHECK_THROWS_AS(second.commit(), shpb::InputError);
  CHECK(read_all(out / "notes.txt") == "the user's notes");
  CHECK(read_all(out / "summary.json") == "first");
}

TEST_CASE("A run that writes nothing leaves no parent folder it made for its output",
          "[robustness][output]") {
  // -o new/a/out: the run makes new/ and new/a/ for its temporary; interrupted or failed, it
  // left them behind, empty (docs/commands.md, Exit codes: "nothing").
  ScratchFolder scratch("folder");
  const fs::path made = scratch.path() / "new";
  { shpb::OutputFolder folder(made / "a" / "out"); }
  CHECK_FALSE(fs::exists(made));
  { shpb::OutputFile file(made / "a" / "table.csv"); }
  CHECK_FALSE(fs::exists(made));
  {  // a folder that was there stays, and so does one holding another entry
    fs::create_directories(made / "a");
    write_bytes(made / "notes.txt", "mine");
    shpb::OutputFolder folder(made / "a" / "b" / "out");
  }
  CHECK(fs::exists(made / "a"));
  CHECK_FALSE(fs::exists(made / "a" / "b"));
  {
    shpb::OutputFolder folder(made / "c" / "out");
    folder.commit();
  }
  CHECK(fs::is_directory(made / "c" / "out"));
}

}  // namespace tests_robustness_test_output_folder
