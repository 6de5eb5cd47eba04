// Nothing the user owns is ever lost (docs/outputs.md (conventions)): shpb replaces only folders
// that carry its own marker and nothing else, never a folder that is or holds an input of the
// run, never a report's figures/ it did not draw; a full disk or a killed run leaves the previous
// result byte for byte as it was. Every case runs the real executable.
#include <signal.h>
#include <sys/mount.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdlib>
#include <map>
#include <string>
#include <thread>

#include "../skip.hpp"
#include "child_process.hpp"
#include "measured_test.hpp"
#include "striker_on_bar_scene.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_robustness_test_lost_data {

namespace {

using namespace shpb_robust;

const fs::path kClassic = fs::path(SHPB_SOURCE_DIR) / "experiments/classic-al6061/scene.json";
constexpr double kLimit_s = 120.0;  // a hang, not a slow machine

// Every regular file under `dir` with its bytes, for byte-for-byte comparisons.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = read_all(e.path());
  return files;
}

}  // namespace

TEST_CASE("A folder with a foreign summary.json and the user's files is not replaced",
          "[robustness][lost-data]") {
  ScratchFolder scratch("lost");
  const fs::path dir = scratch.path() / "myproject";
  fs::create_directories(dir / "data");
  write_bytes(dir / "summary.json", "{\"mine\": true}\n");
  write_bytes(dir / "thesis.tex", "\\documentclass{article}\n");
  write_bytes(dir / "data" / "raw.csv", "t,v\n0,1\n");
  write_bytes(scratch.path() / "scene.json", striker_on_bar_scene("50 us"));
  const auto before = snapshot(dir);
  const Outcome o =
      run({"simulate", (scratch.path() / "scene.json").string(), "-o", dir.string(), "-q"},
          scratch.path(), kLimit_s);
  INFO(o.err);
  CHECK(o.code == 2);
  CHECK(o.err.find(".shpb-output") != std::string::npos);  // says what makes a folder shpb's
  CHECK(snapshot(dir) == before);
  CHECK(litter(scratch.path()).empty());
}

TEST_CASE("A file the user added to a shpb result keeps the folder from being replaced",
          "[robustness][lost-data]") {
  ScratchFolder scratch("lost");
  const fs::path out = scratch.path() / "out";
  write_bytes(scratch.path() / "scene.json", striker_on_bar_scene("50 us"));
  const std::vector<std::string> args = {"simulate", (scratch.path() / "scene.json").string(), "-o",
                                         out.string(), "-q"};
  REQUIRE(run(args, scratch.path(), kLimit_s).code == 0);
  REQUIRE(run(args, scratch.path(), kLimit_s).code == 0);  // shpb's own result is replaced
  write_bytes(out / "notes.txt", "my notes");
  const Outcome o = run(args, scratch.path(), kLimit_s);
  INFO(o.err);
  CHECK(o.code == 2);
  CHECK(o.err.find("notes.txt") != std::string::npos);
  CHECK(read_all(out / "notes.txt") == "my notes");
}

TEST_CASE("An output folder holding the scene being run is refused", "[robustness][lost-data]") {
  ScratchFolder scratch("lost");
  const fs::path res = scratch.path() / "res";
  // A shpb result into which the user then put the scene: the marker alone would not save it.
  write_bytes(scratch.path() / "scene.json", striker_on_bar_scene("50 us"));
  REQUIRE(run({"simulate", (scratch.path() / "scene.json").string(), "-o", res.string(), "-q"},
              scratch.path(), kLimit_s)
              .code == 0);
  fs::copy_file(scratch.path() / "scene.json", res / "scene.json");
  for (const fs::path& o_dir : {res, scratch.path()}) {  // -o the scene's folder, or an ancestor
    INFO("-o " << o_dir);
    const auto before = snapshot(res);
    const Outcome o = run({"simulate", (res / "scene.json").string(), "-o", o_dir.string(), "-q"},
                          scratch.path(), kLimit_s);
    INFO(o.err);
    CHECK(o.code == 2);
    CHECK(snapshot(res) == before);
  }
  // The scene itself as -o: not a folder.
  const Outcome o =
      run({"simulate", (res / "scene.json").string(), "-o", (res / "scene.json").string(), "-q"},
          scratch.path(), kLimit_s);
  CHECK(o.code == 2);
  CHECK(fs::is_regular_file(res / "scene.json"));
}

TEST_CASE("process --signals res/gauges.csv -o res is refused and res is kept",
          "[robustness][lost-data]") {
  ScratchFolder scratch("lost");
  const fs::path res = scratch.path() / "res";
  REQUIRE(run({"simulate", kClassic.string(), "-o", res.string(), "-q"}, scratch.path(), kLimit_s)
              .code == 0);
  const auto before = snapshot(res);
  const Outcome o = run({"process", kClassic.string(), "--signals", (res / "gauges.csv").string(),
                         "-o", res.string(), "-q"},
                        scratch.path(), kLimit_s);
  INFO(o.err);
  CHECK(o.code == 2);
  CHECK(o.err.find("input") != std::string::npos);
  CHECK(snapshot(res) == before);
  // Into another folder the same command works.
  CHECK(run({"process", kClassic.string(), "--signals", (res / "gauges.csv").string(), "-o",
             (scratch.path() / "curves").string(), "-q"},
            scratch.path(), kLimit_s)
            .code == 0);
}

TEST_CASE("report never replaces a figures/ folder or report.html it did not write",
          "[robustness][lost-data]") {
  if (!shpb_test::have_matplotlib()) {
    WARN("SKIPPED: python3 with matplotlib and numpy is not installed");
    return;
  }
  ScratchFolder scratch("lost");
  const fs::path out = scratch.path() / "out";
  write_bytes(scratch.path() / "scene.json", striker_on_bar_scene("50 us"));
  REQUIRE(run({"simulate", (scratch.path() / "scene.json").string(), "-o", out.string(), "-q"},
              scratch.path(), kLimit_s)
              .code == 0);
  fs::create_directory(out / "figures");
  write_bytes(out / "figures" / "paper_fig1.pdf", "%PDF-1.4 the user's figure");
  Outcome o = run({"report", out.string()}, scratch.path(), kLimit_s);
  INFO(o.err);
  CHECK(o.code == 2);
  CHECK(o.err.find("figures") != std::string::npos);
  CHECK(read_all(out / "figures" / "paper_fig1.pdf") == "%PDF-1.4 the user's figure");
  CHECK_FALSE(fs::exists(out / "report.html"));

  // Its own figures/ it replaces, twice over; and the result stays shpb's to replace.
  fs::remove_all(out / "figures");
  REQUIRE(run({"report", out.string()}, scratch.path(), kLimit_s).code == 0);
  REQUIRE(run({"report", out.string()}, scratch.path(), kLimit_s).code == 0);
  CHECK(fs::exists(out / "figures" / "signals.png"));
  o = run({"simulate", (scratch.path() / "scene.json").string(), "-o", out.string(), "-q"},
          scratch.path(), kLimit_s);
  INFO(o.err);
  CHECK(o.code == 0);

  // A page of its own the user annotated since: neither the report nor a simulation into the
  // folder replaces it.
  REQUIRE(run({"report", out.string()}, scratch.path(), kLimit_s).code == 0);
  const std::string annotated = read_all(out / "report.html") + "<!-- the user's note -->";
  write_bytes(out / "report.html", annotated);
  o = run({"report", out.string()}, scratch.path(), kLimit_s);
  INFO(o.err);
  CHECK(o.code == 2);
  CHECK(o.err.find("changed since") != std::string::npos);
  o = run({"simulate", (scratch.path() / "scene.json").string(), "-o", out.string(), "-q"},
          scratch.path(), kLimit_s);
  INFO(o.err);
  CHECK(o.code == 2);
  CHECK(read_all(out / "report.html") == annotated);

  // A user's report.html beside shpb's results.
  ScratchFolder other("lost");
  const fs::path out2 = other.path() / "out";
  REQUIRE(run({"simulate", (scratch.path() / "scene.json").string(), "-o", out2.string(), "-q"},
              other.path(), kLimit_s)
              .code == 0);
  write_bytes(out2 / "report.html", "<html>my page</html>");
  CHECK(run({"report", out2.string()}, other.path(), kLimit_s).code == 2);
  CHECK(read_all(out2 / "report.html") == "<html>my page</html>");
}

TEST_CASE("report on a read-only folder is one error line, not a traceback",
          "[robustness][lost-data]") {
  if (!shpb_test::have_matplotlib()) {
    WARN("SKIPPED: python3 with matplotlib and numpy is not installed");
    return;
  }
  if (::geteuid() == 0) {
    // root writes through permission bits: a read-only mount stands in for them.
    WARN(
        "running as root: the read-only case is checked on a read-only tmpfs below if mounting "
        "is permitted");
  }
  ScratchFolder scratch("lost");
  const fs::path out = scratch.path() / "out";
  write_bytes(scratch.path() / "scene.json", striker_on_bar_scene("50 us"));
  REQUIRE(run({"simulate", (scratch.path() / "scene.json").string(), "-o", out.string(), "-q"},
              scratch.path(), kLimit_s)
              .code == 0);
  fs::path target = out;
  bool mounted = false;
  if (::geteuid() == 0) {
    const fs::path ro = scratch.path() / "ro";
    fs::create_directory(ro);
    if (::mount(out.c_str(), ro.c_str(), nullptr, MS_BIND, nullptr) != 0 ||
        ::mount(nullptr, ro.c_str(), nullptr, MS_BIND | MS_REMOUNT | MS_RDONLY, nullptr) != 0) {
      ::umount(ro.c_str());
      WARN("SKIPPED: cannot mount a read-only bind mount here");
      return;
    }
    mounted = true;
    target = ro;
  } else {
    fs::permissions(out, fs::perms::owner_write | fs::perms::group_write | fs::perms::others_write,
                    fs::perm_options::remove);
  }
  const Outcome o = run({"report", target.string()}, scratch.path(), kLimit_s);
  if (mounted) ::umount(target.c_str());
  INFO(o.err);
  CHECK((o.code == 2 || o.code == 3));
  CHECK(o.err.find("Traceback") == std::string::npos);
  CHECK(o.err.rfind("error: ", 0) == 0);
  CHECK(std::count(o.err.begin(), o.err.end(), '\n') == 1);
}

TEST_CASE("A full disk fails the run naming the file and keeps the previous result",
          "[robustness][lost-data]") {
  ScratchFolder scratch("lost");
  const fs::path disk = scratch.path() / "disk";
  fs::create_directory(disk);
  // 6 MB: room for one 50 µs result (~0.7 MB), not for a 1 ms one (~12 MB of field.csv).
  if (::mount("tmpfs", disk.c_str(), "tmpfs", 0, "size=6m") != 0) {
    WARN("SKIPPED: mounting a small tmpfs is not permitted here (needs root or CAP_SYS_ADMIN)");
    return;
  }
  struct Unmount {
    fs::path p;
    ~Unmount() { ::umount2(p.c_str(), MNT_DETACH); }
  } unmount{disk};
  write_bytes(scratch.path() / "small.json", striker_on_bar_scene("50 us"));
  write_bytes(scratch.path() / "big.json", striker_on_bar_scene("1 ms"));
  const fs::path out = disk / "out";
  for (const std::string command : {"simulate", "dispersion"}) {
    INFO(command);
    std::vector<std::string> good, big;
    if (command == "simulate") {
      good = {"simulate", (scratch.path() / "small.json").string(), "-o", out.string(), "-q"};
      big = {"simulate", (scratch.path() / "big.json").string(), "-o", out.string(), "-q"};
    } else {
      good = {"dispersion", "--poisson", "0.29", "-o", (disk / "table.csv").string()};
      // A table bigger than the disk: 120 000 rows of ~80 bytes.
      big = {"dispersion", "--poisson", "0.29",
             "--points",   "120000",    "--max-a-over-lambda",
             "0.5",        "-o",        (disk / "table.csv").string()};
    }
    const Outcome first = run(good, scratch.path(), kLimit_s);
    INFO(first.err);
    REQUIRE(first.code == 0);
    const auto before = snapshot(disk);
    const Outcome o = run(big, scratch.path(), kLimit_s);
    INFO(o.err);
    CHECK(o.code == 3);
    CHECK(o.err.find("No space left on device") != std::string::npos);
    // The file by the name the user gave, not the hidden temporary it was written as.
    CHECK(o.err.find(command == "simulate"
                         ? out.string() + "/"
                         : (disk / "table.csv").string() + ":") != std::string::npos);
    CHECK(o.err.find(".tmp-") == std::string::npos);
    CHECK(snapshot(disk) == before);  // byte for byte, no temporary left
    CHECK(litter(disk).empty());
  }
}

TEST_CASE("dispersion -o killed or interrupted keeps the previous file",
          "[robustness][lost-data][interrupt]") {
  ScratchFolder scratch("lost");
  const fs::path table = scratch.path() / "table.csv";
  REQUIRE(run({"dispersion", "--poisson", "0.29", "-o", table.string()}, scratch.path(), kLimit_s)
              .code == 0);
  const std::string previous = read_all(table);
  REQUIRE(previous.size() > 1000);
  // 1e6 points take many seconds: signal it while it writes.
  const std::vector<std::string> slow = {"dispersion", "--poisson", "0.3",         "--points",
                                         "1000000",    "-o",        table.string()};
  for (const int sig : {SIGKILL, SIGTERM, SIGINT}) {
    INFO("signal " << sig);
    Child child(slow, scratch.path());
    REQUIRE(child.started());
    REQUIRE(child.wait_until_interruptible(kLimit_s));
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    child.signal(sig);
    const Outcome o = child.wait(kLimit_s);
    if (sig == SIGKILL) {
      CHECK(o.signal == SIGKILL);
    } else {
      CHECK(o.code == 130);
      CHECK(o.seconds < prompt_exit_s());
      CHECK(litter(scratch.path()).empty());
    }
    CHECK(read_all(table) == previous);
  }
  // The next run removes what the killed one left and writes the new table whole.
  REQUIRE(run({"dispersion", "--poisson", "0.3", "-o", table.string()}, scratch.path(), kLimit_s)
              .code == 0);
  CHECK(litter(scratch.path()).empty());
  CHECK(read_all(table) != previous);
}

TEST_CASE("dispersion -o replaces only a table it wrote, never a file of the user's",
          "[robustness][lost-data]") {
  // docs/outputs.md, Conventions: no file shpb did not write is replaced. A dispersion table
  // starts with its header; an empty file holds nothing to lose.
  ScratchFolder scratch("lost");
  const fs::path notes = scratch.path() / "notes.csv", link = scratch.path() / "link.csv";
  write_bytes(notes, "my measurements\n1,2\n");
  fs::create_symlink(notes, link);
  for (const fs::path& target : {notes, link}) {
    INFO("-o " << target);
    check_refused(
        run({"dispersion", "--poisson", "0.29", "-o", target.string()}, scratch.path(), kLimit_s),
        "shpb replaces only a file it wrote");
    CHECK(read_all(notes) == "my measurements\n1,2\n");
    CHECK(fs::is_symlink(link));
  }
  CHECK(litter(scratch.path()).empty());
  // Its own table, with or without the frequency column, and an empty file are replaced.
  const fs::path table = scratch.path() / "table.csv";
  write_bytes(table, "");
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{}, {"--radius", "5 mm", "--c0", "5000 m/s"}, {}}) {
    std::vector<std::string> args = {"dispersion", "--poisson", "0.29", "-o", table.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const Outcome o = run(args, scratch.path(), kLimit_s);
    INFO(o.err);
    CHECK(o.code == 0);
    CHECK(read_all(table).rfind("a_over_lambda,c_over_c0,cg_over_c0,f_a_over_c0", 0) == 0);
  }
  // "-o tables/" names a folder: refused, not a file "tables" made in its stead.
  check_refused(
      run({"dispersion", "--poisson", "0.29", "-o", (scratch.path() / "tables/").string()},
          scratch.path(), kLimit_s),
      "a file name was expected");
  CHECK_FALSE(fs::exists(scratch.path() / "tables"));
}

TEST_CASE("A stray temporary-looking folder with a huge number is left alone, not a crash",
          "[robustness][lost-data]") {
  ScratchFolder scratch("lost");
  const fs::path stray = scratch.path() / ".out.tmp-99999999999999999999-1";
  fs::create_directory(stray);
  write_bytes(stray / "keep.txt", "not shpb's");
  write_bytes(scratch.path() / "scene.json", striker_on_bar_scene("50 us"));
  const Outcome o = run({"simulate", (scratch.path() / "scene.json").string(), "-o",
                         (scratch.path() / "out").string(), "-q"},
                        scratch.path(), kLimit_s);
  INFO(o.err);
  CHECK(o.code == 0);
  CHECK(read_all(stray / "keep.txt") == "not shpb's");
}

TEST_CASE("study --merge PLAN -o PLAN, or -o inside its parts, is refused and the plan kept",
          "[robustness][lost-data]") {
  ScratchFolder scratch("lost");
  const fs::path plan = scratch.path() / "plan";
  write_bytes(scratch.path() / "scene.json", striker_on_bar_scene("50 us"));
  const auto quiet = [&](std::vector<std::string> args) {
    args.push_back("-q");
    return run(args, scratch.path(), kLimit_s);
  };
  REQUIRE(quiet({"study", (scratch.path() / "scene.json").string(), "--plan", plan.string(),
                 "--contact", "bipenalty", "--stepping", "global"})
              .code == 0);
  REQUIRE(quiet({"study", "--run", plan.string(), "--shard", "0/1", "--threads", "1"}).code == 0);
  const auto before = snapshot(plan);
  for (const fs::path& o_dir : {plan, plan / "parts", plan / "parts" / "mine"}) {
    INFO("-o " << o_dir);
    check_refused(quiet({"study", "--merge", plan.string(), "-o", o_dir.string()}),
                  "input of this run");
    CHECK(snapshot(plan) == before);
  }
  // The default, DIR/result, is not an input.
  CHECK(quiet({"study", "--merge", plan.string()}).code == 0);
  CHECK(fs::exists(plan / "result" / "pareto.csv"));
}

TEST_CASE("Campaign test names are folder names: no path, no '.', '..', no campaign file name",
          "[robustness][lost-data]") {
  ScratchFolder scratch("lost");
  const fs::path dir = scratch.path() / "campaign";
  measured_test(dir);
  // A result elsewhere on disk that an absolute test name would replace.
  const fs::path elsewhere = scratch.path() / "elsewhere";
  REQUIRE(
      run({"simulate", (dir / "sim.json").string(), "-o", elsewhere.string(), "-q"}, dir, kLimit_s)
          .code == 0);
  const auto before = snapshot(scratch.path());
  for (const std::string& name :
       std::vector<std::string>{"../x", elsewhere.string(), "a/b", "a\\\\b", ".", "..",
                                "campaign.csv", "Summary.json", "parts", ".shpb-temporary"}) {
    INFO("test name " << name);
    write_bytes(dir / "c.json",
                R"({"tests": [{"scene": "measured.json", "name": ")" + name + R"("}]})");
    const auto now = snapshot(scratch.path());
    check_refused(run({"process", "--campaign", (dir / "c.json").string(), "-o",
                       (dir / "out").string(), "-q"},
                      dir, kLimit_s),
                  "tests[0].name");
    CHECK(snapshot(scratch.path()) == now);
    CHECK_FALSE(fs::exists(dir / "out"));
  }
  fs::remove(dir / "c.json");
  CHECK(snapshot(scratch.path()) == before);
  // A scene file named as a campaign file names its test so: refused too.
  fs::copy_file(dir / "measured.json", dir / "campaign.csv.json");
  check_refused(run({"process", (dir / "measured.json").string(),
                     (dir / "campaign.csv.json").string(), "-o", (dir / "out").string(), "-q"},
                    dir, kLimit_s),
                "campaign.csv");
}

TEST_CASE("The user's files that look like shpb temporaries beside -o are left alone",
          "[robustness][lost-data]") {
  ScratchFolder scratch("lost");
  write_bytes(scratch.path() / "scene.json", striker_on_bar_scene("50 us"));
  const fs::path parent = scratch.path() / "work";
  fs::create_directories(parent / ".res.tmp-123456-old");
  write_bytes(parent / ".res.tmp-2024-05-01.tar", "the user's archive");
  write_bytes(parent / ".res.tmp-4000000-backup", "the user's backup");
  write_bytes(parent / ".res.tmp-123456-old" / "notes.txt", "the user's notes");
  // Exactly the old naming (".<name>.tmp-<pid>-<random>") with a dead pid, but no marker.
  fs::create_directories(parent / ".res.tmp-4000001-1234");
  write_bytes(parent / ".res.tmp-4000001-1234" / "data.csv", "1,2\n");
  const auto before = snapshot(parent);
  const Outcome o = run(
      {"simulate", (scratch.path() / "scene.json").string(), "-o", (parent / "res").string(), "-q"},
      scratch.path(), kLimit_s);
  INFO(o.err);
  REQUIRE(o.code == 0);
  auto after = snapshot(parent);
  for (auto it = after.begin(); it != after.end();)  // the new result aside
    it = it->first.rfind("res/", 0) == 0 ? after.erase(it) : std::next(it);
  CHECK(after == before);
}

TEST_CASE("The temporary folder of a killed run is removed by the next run into the same -o",
          "[robustness][lost-data]") {
  ScratchFolder scratch("lost");
  write_bytes(scratch.path() / "small.json", striker_on_bar_scene("50 us"));
  write_bytes(scratch.path() / "long.json", striker_on_bar_scene("20 ms"));
  const fs::path out = scratch.path() / "out";
  Child child({"simulate", (scratch.path() / "long.json").string(), "-o", out.string(), "-q"},
              scratch.path());
  REQUIRE(child.started());
  const auto start = std::chrono::steady_clock::now();
  while (litter(scratch.path()).empty() &&
         std::chrono::steady_clock::now() - start < std::chrono::duration<double>(kLimit_s))
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  REQUIRE(litter(scratch.path()).size() == 1);
  child.signal(SIGKILL);
  CHECK(child.wait(kLimit_s).signal == SIGKILL);
  REQUIRE(litter(scratch.path()).size() == 1);
  const Outcome o =
      run({"simulate", (scratch.path() / "small.json").string(), "-o", out.string(), "-q"},
          scratch.path(), kLimit_s);
  INFO(o.err);
  CHECK(o.code == 0);
  CHECK(litter(scratch.path()).empty());
}

TEST_CASE("fit -o the folder of the starting material (a previous fit.json) is refused",
          "[robustness][lost-data]") {
  ScratchFolder scratch("lost");
  const fs::path dir = scratch.path() / "t";
  measured_test(dir);
  // A previous fit's folder, its fit.json edited by hand: shpb's to replace, but an input now.
  const fs::path previous = dir / "previous";
  fs::create_directories(previous);
  write_bytes(previous / "fit.json", kAluminium);
  write_bytes(previous / ".shpb-output",
              "shpb output folder: written by shpb, replaced only by shpb\ncommand: fit\n"
              "file: fit.json\n");
  write_bytes(dir / "campaign.json", R"({"tests": [{"scene": "measured.json"}],
    "material": "previous/fit.json", "free": {"yield_stress": ["100 MPa", "200 MPa"]},
    "stages": ["curve"]})");
  const auto before = snapshot(previous);
  check_refused(
      run({"fit", (dir / "campaign.json").string(), "-o", previous.string(), "-q"}, dir, kLimit_s),
      "input of this run");
  CHECK(snapshot(previous) == before);
}

TEST_CASE("Campaign process -o holding a scene's measured file is refused and the file kept",
          "[robustness][lost-data]") {
  ScratchFolder scratch("lost");
  const fs::path dir = scratch.path() / "t";
  measured_campaign(dir);
  const auto before = snapshot(dir / "sim");
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"process", (dir / "measured.json").string(),
                                 (dir / "second.json").string()},
        std::vector<std::string>{"process", "--campaign", (dir / "c.json").string()}}) {
    std::vector<std::string> a = args;
    a.insert(a.end(), {"-o", (dir / "sim").string(), "-q"});
    INFO(a[1]);
    check_refused(run(a, dir, kLimit_s), "input of this run");
    CHECK(snapshot(dir / "sim") == before);
  }
}

TEST_CASE("An -o that is a symbolic link to a folder is written through: the link stays",
          "[robustness][lost-data]") {
  ScratchFolder scratch("lost");
  write_bytes(scratch.path() / "scene.json", striker_on_bar_scene("50 us"));
  const fs::path target = scratch.path() / "results" / "run1", link = scratch.path() / "latest";
  const std::vector<std::string> args = {"simulate", (scratch.path() / "scene.json").string(), "-o",
                                         link.string(), "-q"};
  fs::create_directories(target);
  fs::create_directory_symlink(target, link);
  for (int run_number = 0; run_number < 2; ++run_number) {  // into the empty target, then over it
    const Outcome o = run(args, scratch.path(), kLimit_s);
    INFO(o.err);
    REQUIRE(o.code == 0);
    CHECK(fs::is_symlink(link));
    CHECK(fs::read_symlink(link) == target);
    CHECK(fs::is_regular_file(target / "gauges.csv"));
  }
  CHECK(litter(scratch.path()).empty());
  CHECK(litter(target.parent_path()).empty());
  // A link to nothing is refused, not replaced by a folder.
  const fs::path dangling = scratch.path() / "dangling";
  fs::create_directory_symlink(scratch.path() / "nowhere", dangling);
  check_refused(
      run({"simulate", (scratch.path() / "scene.json").string(), "-o", dangling.string(), "-q"},
          scratch.path(), kLimit_s),
      "symbolic link");
  CHECK(fs::is_symlink(dangling));
  CHECK_FALSE(fs::exists(scratch.path() / "nowhere"));
}

TEST_CASE("An -o ending in . or .. names that folder, written as any other -o",
          "[robustness][lost-data]") {
  ScratchFolder scratch("lost");
  write_bytes(scratch.path() / "scene.json", striker_on_bar_scene("50 us"));
  const fs::path out = scratch.path() / "out";
  fs::create_directories(out / "sub");
  // "-o out/sub/.." (out holds only the empty sub/: refused, it is not shpb's), then "-o out/."
  // (as "-o ." in an empty current folder) into the empty out/, then over that result.
  const auto simulate = [&](const fs::path& given) {
    return run({"simulate", (scratch.path() / "scene.json").string(), "-o", given.string(), "-q"},
               scratch.path(), kLimit_s);
  };
  check_refused(simulate(out / "sub" / ".."), ".shpb-output");
  CHECK(fs::is_directory(out / "sub"));
  fs::remove(out / "sub");
  for (int run_number = 0; run_number < 2; ++run_number) {
    const Outcome o = simulate(out / ".");
    INFO(o.err);
    CHECK(o.code == 0);
    CHECK(fs::is_regular_file(out / "gauges.csv"));
    CHECK(litter(scratch.path()).empty());
    CHECK(litter(out).empty());
  }
}

// Whether `shpb report DIR`'s script is drawing: its temporary folder ".report-…" exists in DIR.
bool report_drawing(const fs::path& dir) {
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().rfind(".report-", 0) == 0) return true;
  return false;
}

// Runs signalled while the script draws before a test gives up: a signal that lands in the
// report's last renames is too late, and five in a row would mean the script does not stop.
constexpr int kSignalAttempts = 5;

// Waits (at most kLimit_s) until the script draws.
bool wait_until_drawing(const fs::path& dir) {
  const auto start = std::chrono::steady_clock::now();
  while (!report_drawing(dir) &&
         std::chrono::steady_clock::now() - start < std::chrono::duration<double>(kLimit_s))
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  return report_drawing(dir);
}

// A striker-on-bar result simulated into scratch/out, for the report tests to draw; returns the
// command, which run again replaces it.
std::vector<std::string> simulated_result(const ScratchFolder& scratch) {
  write_bytes(scratch.path() / "scene.json", striker_on_bar_scene("50 us"));
  std::vector<std::string> simulate = {"simulate", (scratch.path() / "scene.json").string(), "-o",
                                       (scratch.path() / "out").string(), "-q"};
  REQUIRE(run(simulate, scratch.path(), kLimit_s).code == 0);
  return simulate;
}

TEST_CASE("report stopped by SIGINT or SIGTERM exits 130 promptly and keeps the previous report",
          "[robustness][lost-data]") {
  if (!shpb_test::have_matplotlib()) {
    WARN("SKIPPED: python3 with matplotlib and numpy is not installed");
    return;
  }
  // The signal goes to shpb alone (kill PID), not to its Python: it was not passed on, and the
  // report was drawn and put in place, exit 0 (docs/commands.md, Exit codes: 130). Signalled
  // while the script draws (its temporary folder is present): a signal at a fixed share of a timed
  // run came after the whole report when the timed run was the slower one (a loaded machine).
  ScratchFolder scratch("lost");
  const fs::path out = scratch.path() / "out";
  simulated_result(scratch);
  const std::vector<std::string> args = {"report", out.string()};
  REQUIRE(run(args, scratch.path(), kLimit_s).code == 0);
  const auto report = snapshot(out);
  for (const int sig : {SIGINT, SIGTERM}) {
    // Its temporary folder stays while the report is put in place, where a signal is too late
    // and the report finishes (exit 0, docs/commands.md): then it is signalled again.
    Outcome o;
    for (int attempt = 0; attempt < kSignalAttempts && o.code != 130; ++attempt) {
      Child child(args, scratch.path());
      REQUIRE(child.wait_until_interruptible(kLimit_s));
      REQUIRE(wait_until_drawing(out));
      child.signal(sig);
      o = child.wait(kLimit_s);
    }
    INFO("signal " << sig << ": " << o.err);
    CHECK(o.code == 130);
    CHECK(o.seconds < prompt_exit_s());
    CHECK(snapshot(out) == report);
    CHECK_FALSE(report_drawing(out));
  }
}

TEST_CASE("report killed outright puts no report in place after it is gone",
          "[robustness][lost-data]") {
  if (!shpb_test::have_matplotlib()) {
    WARN("SKIPPED: python3 with matplotlib and numpy is not installed");
    return;
  }
  // SIGKILL to shpb cannot be passed on: its Python went on alone and put the report in place
  // after shpb was gone. It now stops with its parent (tools/report.py, PR_SET_PDEATHSIG).
  ScratchFolder scratch("lost");
  const fs::path out = scratch.path() / "out";
  simulated_result(scratch);
  const std::vector<std::string> args = {"report", out.string()};
  const double whole_s = seconds_after_startup(args, scratch.path(), kLimit_s);
  // Killed while the script draws into its temporary folder: a kill at a fixed share of a timed
  // run came after the whole report when the timed run was the slower one (a loaded machine).
  // The folder stays while the report is put in place, whose renames the script finishes (a
  // whole report, by design): a kill that lands there is tried again.
  for (int attempt = 0; attempt < kSignalAttempts; ++attempt) {
    fs::remove_all(out / "figures");  // the timed (or a finished) run's report
    fs::remove(out / "report.html");
    Child child(args, scratch.path());
    REQUIRE(child.wait_until_interruptible(kLimit_s));
    REQUIRE(wait_until_drawing(out));
    child.signal(SIGKILL);
    CHECK(child.wait(kLimit_s).signal == SIGKILL);
    // Time for the script to have finished its report, had it gone on alone.
    std::this_thread::sleep_for(std::chrono::duration<double>(1.5 * whole_s));
    if (!fs::exists(out / "report.html")) break;
  }
  CHECK_FALSE(fs::exists(out / "report.html"));
  CHECK_FALSE(fs::exists(out / "figures"));
}

TEST_CASE("report whose Python is killed outright fails with exit 3 and leaves no temporary",
          "[robustness][lost-data]") {
  if (!shpb_test::have_matplotlib())
    SHPB_SKIP("python3 with matplotlib and numpy is not installed");
  // The out-of-memory killer picks the largest process, the drawing Python: shpb said "internal
  // error" (exit 4, a bug) and left the script's temporary folder in DIR, for which the next
  // simulate -o DIR refused DIR (a file shpb did not write). The run failed (exit 3, one line
  // naming the signal), its temporaries are removed and DIR stays shpb's to replace.
  ScratchFolder scratch("lost");
  const fs::path out = scratch.path() / "out";
  const std::vector<std::string> simulate = simulated_result(scratch);
  Child child({"report", out.string()}, scratch.path());
  REQUIRE(child.started());
  REQUIRE(wait_until_drawing(out));
  const fs::path children = fs::path("/proc") / std::to_string(child.pid()) / "task" /
                            std::to_string(child.pid()) / "children";
  pid_t python = 0;
  std::ifstream(children) >> python;
  REQUIRE(python > 0);
  ::kill(python, SIGKILL);
  const Outcome o = child.wait(kLimit_s);
  INFO(o.err);
  CHECK(o.code == 3);
  CHECK(std::count(o.err.begin(), o.err.end(), '\n') == 1);
  CHECK(o.err.find("killed by signal 9") != std::string::npos);
  CHECK_FALSE(report_drawing(out));
  const Outcome again = run(simulate, scratch.path(), kLimit_s);
  INFO(again.err);
  CHECK(again.code == 0);
}

TEST_CASE("report removes the temporaries of a report that was killed, and only those",
          "[robustness][lost-data]") {
  if (!shpb_test::have_matplotlib()) {
    WARN("SKIPPED: python3 with matplotlib and numpy is not installed");
    return;
  }
  // A report killed outright (SIGKILL, a closed terminal) left its temporary figures folder in
  // DIR for ever, and DIR, holding an entry its marker does not list, could no longer be replaced
  // by the command that wrote it (exit 2, "holds .report-…, which shpb did not write").
  ScratchFolder scratch("lost");
  const fs::path out = scratch.path() / "out";
  const std::vector<std::string> simulate = simulated_result(scratch);
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  // The names of tools/shpb_report/main.py: ".report-<host>-<pid>-<8 random>" and its twins.
  const auto temporary = [&](pid_t pid) {
    return out / (".report-" + std::string(host) + "-" + std::to_string(pid) + "-abcd_123");
  };
  const fs::path killed = temporary(dead_pid()), running = temporary(::getpid());
  for (const fs::path& d : {killed, running}) {
    fs::create_directory(d);
    write_bytes(d / ".shpb-report",
                "figures written by shpb report; replaced only by shpb report\n");
    write_bytes(d / "gauges.png", "\x89PNG");
  }
  write_bytes(killed.string() + ".html", "<html></html>");
  const Outcome o = run({"report", out.string()}, scratch.path(), kLimit_s);
  INFO(o.err);
  CHECK(o.code == 0);
  CHECK_FALSE(fs::exists(killed));
  CHECK_FALSE(fs::exists(killed.string() + ".html"));
  CHECK(fs::exists(running / "gauges.png"));  // a report running now: not ours to remove
  fs::remove_all(running);
  const Outcome again = run(simulate, scratch.path(), kLimit_s);
  INFO(again.err);
  CHECK(again.code == 0);
}

TEST_CASE("Two runs at once into the same new -o both succeed and leave one whole result",
          "[robustness][lost-data]") {
  // Both find DIR missing; the second to finish found it there when it moved its result: it
  // failed after all its work, exit 2 "cannot move the result into place". The last to finish
  // now replaces the first's result.
  constexpr int kRounds = 60;  // a race: on main 0 to 30 rounds in 100 failed
  ScratchFolder scratch("lost");
  write_bytes(scratch.path() / "scene.json", striker_on_bar_scene("50 us"));
  const fs::path out = scratch.path() / "out";
  const std::vector<std::string> args = {"simulate", (scratch.path() / "scene.json").string(), "-o",
                                         out.string(), "-q"};
  fs::create_directories(scratch.path() / "a");  // each child's stdout and stderr
  fs::create_directories(scratch.path() / "b");
  for (int round = 0; round < kRounds; ++round) {
    fs::remove_all(out);
    Child first(args, scratch.path() / "a"), second(args, scratch.path() / "b");
    const Outcome a = first.wait(kLimit_s), b = second.wait(kLimit_s);
    INFO("round " << round << ": " << a.err << b.err);
    CHECK(a.code == 0);
    CHECK(b.code == 0);
    CHECK(fs::is_regular_file(out / "gauges.csv"));
    CHECK(litter(scratch.path()).empty());
  }
}

TEST_CASE("An -o that is a mount point is refused before the run", "[robustness][lost-data]") {
  // The result is renamed into place, which a mount point refuses: the run did all its work and
  // then failed ("Device or resource busy"). A folder inside it is written as any other.
  ScratchFolder scratch("lost");
  const fs::path disk = scratch.path() / "disk";
  fs::create_directory(disk);
  if (::mount("tmpfs", disk.c_str(), "tmpfs", 0, "size=4m") != 0) {
    WARN("SKIPPED: mounting a small tmpfs is not permitted here (needs root or CAP_SYS_ADMIN)");
    return;
  }
  struct Unmount {
    fs::path p;
    ~Unmount() { ::umount2(p.c_str(), MNT_DETACH); }
  } unmount{disk};
  write_bytes(scratch.path() / "scene.json", striker_on_bar_scene("50 us"));
  const auto simulate = [&](const fs::path& out) {
    return run({"simulate", (scratch.path() / "scene.json").string(), "-o", out.string(), "-q"},
               scratch.path(), kLimit_s);
  };
  check_refused(simulate(disk), "mount point");
  CHECK(fs::is_empty(disk));
  CHECK(litter(scratch.path()).empty());
  CHECK(simulate(disk / "out").code == 0);
}

TEST_CASE("An -o that is a bind mount on the same device is refused before the run",
          "[robustness][lost-data]") {
  // A bind mount is on its parent's device, so the device check missed it: the run did all its
  // work, then failed renaming over it (exit 2 or 3, "Device or resource busy"). Its name holds
  // a space, which /proc/self/mountinfo writes as \040. `dispersion -o FILE` onto a bind-mounted
  // file likewise.
  ScratchFolder scratch("lost");
  const fs::path data = scratch.path() / "data", mounted = scratch.path() / "bound here";
  fs::create_directory(data);
  fs::create_directory(mounted);
  const fs::path table = scratch.path() / "table.csv", bound_table = scratch.path() / "bound.csv";
  const std::string header = "a_over_lambda,c_over_c0,cg_over_c0,f_a_over_c0\n";
  write_bytes(table, header);
  write_bytes(bound_table, "");
  if (::mount(data.c_str(), mounted.c_str(), nullptr, MS_BIND, nullptr) != 0)
    SHPB_SKIP("a bind mount is not permitted here (needs root or CAP_SYS_ADMIN)");
  struct Unmount {
    fs::path p;
    ~Unmount() { ::umount2(p.c_str(), MNT_DETACH); }
  } unmount{mounted};
  REQUIRE(::mount(table.c_str(), bound_table.c_str(), nullptr, MS_BIND, nullptr) == 0);
  const Unmount unmount_file{bound_table};
  write_bytes(scratch.path() / "scene.json", striker_on_bar_scene("50 us"));
  check_refused(
      run({"simulate", (scratch.path() / "scene.json").string(), "-o", mounted.string(), "-q"},
          scratch.path(), kLimit_s),
      "mount point");
  CHECK(fs::is_empty(data));
  check_refused(
      run({"dispersion", "--poisson", "0.3", "-o", bound_table.string()}, scratch.path(), kLimit_s),
      "mount point");
  CHECK(read_all(table) == header);
  CHECK(litter(scratch.path()).empty());
}

}  // namespace tests_robustness_test_lost_data
