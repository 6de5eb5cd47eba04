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

#include "child_process.hpp"

namespace {

using namespace shpb_robust;

const fs::path kClassic = fs::path(SHPB_SOURCE_DIR) / "experiments/classic-al6061/scene.json";
constexpr double kLimit_s = 120.0;     // a hang, not a slow machine
constexpr double kPromptExit_s = 1.0;  // "promptly": loops poll for a signal

// Striker on a bar; `duration` sets the size of field.csv (about 12 MB per ms at 1 MHz).
std::string bar_scene(const std::string& duration) {
  return R"({
  "name": "lost data",
  "bars": [
    {"name": "striker", "material": "steel", "length": "200 mm", "diameter": "12 mm",
     "velocity": "10 m/s"},
    {"name": "bar", "material": "steel", "length": "1 m", "diameter": "12 mm",
     "gauges": [{"name": "gauge", "position": "500 mm"}]}
  ],
  "materials": {"steel": {"model": "elastic", "density": "7850 kg/m3",
                          "youngs_modulus": "200 GPa", "poisson_ratio": 0.29}},
  "simulation": {"duration": ")" +
         duration + R"(", "sample_rate": "1 MHz"}
})";
}

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
  write_bytes(scratch.path() / "scene.json", bar_scene("50 us"));
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
  write_bytes(scratch.path() / "scene.json", bar_scene("50 us"));
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
  write_bytes(scratch.path() / "scene.json", bar_scene("50 us"));
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
  write_bytes(scratch.path() / "scene.json", bar_scene("50 us"));
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
  write_bytes(scratch.path() / "scene.json", bar_scene("50 us"));
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
  write_bytes(scratch.path() / "small.json", bar_scene("50 us"));
  write_bytes(scratch.path() / "big.json", bar_scene("1 ms"));
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
    CHECK(o.err.find(command == "simulate" ? ".csv" : "table.csv") != std::string::npos);
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
      CHECK(o.seconds < kPromptExit_s);
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

TEST_CASE("A stray temporary-looking folder with a huge number is left alone, not a crash",
          "[robustness][lost-data]") {
  ScratchFolder scratch("lost");
  const fs::path stray = scratch.path() / ".out.tmp-99999999999999999999-1";
  fs::create_directory(stray);
  write_bytes(stray / "keep.txt", "not shpb's");
  write_bytes(scratch.path() / "scene.json", bar_scene("50 us"));
  const Outcome o = run({"simulate", (scratch.path() / "scene.json").string(), "-o",
                         (scratch.path() / "out").string(), "-q"},
                        scratch.path(), kLimit_s);
  INFO(o.err);
  CHECK(o.code == 0);
  CHECK(read_all(stray / "keep.txt") == "not shpb's");
}
