// Plan, run, merge (study/shards.hpp, study/study_plan.hpp): shards split a plan's runs exactly
// once; a study merged from parts equals the in-process one apart from wall times; every way a
// set of parts can be wrong is an exit-2 error naming it. The engines themselves (GNU parallel,
// Slurm) are exercised by tests/cluster.
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>

#include "../app/run_shpb.hpp"
#include "../solver/test_scenes.hpp"
#include "core/error.hpp"
#include "study/shards.hpp"
#include "study/study_plan.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_study_test_shards {

using namespace shpb;
namespace fs = std::filesystem;

namespace {
// pareto.csv without its wall_time_s column (the 5th) and the front by wall time (the 8th): what
// must not depend on how it was run.
std::string without_wall_times(const fs::path& csv) {
  std::ifstream in(csv);
  std::string out;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string c; std::getline(s, c, ',');) cells.push_back(c);
    if (line.ends_with(",")) cells.push_back("");
    for (std::size_t i = 0; i < cells.size(); ++i)
      if (i != 4 && i != 7) out += cells[i] + ",";
    out += "\n";
  }
  return out;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const std::string kScene = std::string(SHPB_SOURCE_DIR) + "/experiments/striker-on-bar/scene.json";
}  // namespace

TEST_CASE("Shard K/N takes every N-th run from K, and N shards take every run once",
          "[study][shards]") {
  CHECK(shard_runs(10, parse_shard("--shard", "1/4")) == std::vector<std::size_t>{1, 5, 9});
  CHECK(shard_runs(2, parse_shard("--shard", "3/4")).empty());
  for (const char* bad : {"4/4", "1/0", "-1/4", "1", "a/b", "1/4/2", "/4", "1/"})
    CHECK_THROWS_AS(parse_shard("--shard", bad), InputError);
  std::vector<int> seen(37, 0);
  for (std::size_t k = 0; k < 8; ++k)
    for (std::size_t r : shard_runs(37, {k, 8})) ++seen[r];
  CHECK(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; }));
}

TEST_CASE("Missing and duplicated parts are named", "[study][shards]") {
  const fs::path dir = "parts";
  const std::vector<Part> three_of_four = {
      {"0-of-4.json", {0, 4}}, {"1-of-4.json", {1, 4}}, {"3-of-4.json", {3, 4}}};
  CHECK_NOTHROW(check_parts_cover(dir, 2, three_of_four));  // 2 runs: shards 2, 3 hold none
  CHECK(error_of([&] { check_parts_cover(dir, 10, three_of_four); }) ==
        "parts: missing part 2-of-4 (runs 2, 6): run those shards again (--shard K/N)");
  CHECK(error_of([&] { check_parts_cover(dir, 10, {}); }).find("no parts") != std::string::npos);
  const std::vector<Part> mixed = {
      {"0-of-2.json", {0, 2}}, {"1-of-2.json", {1, 2}}, {"2-of-4.json", {2, 4}}};
  CHECK(error_of([&] {
          check_parts_cover(dir, 10, mixed);
        }).find("duplicated part: 2-of-4 and 0-of-2 both hold run 2") != std::string::npos);
}

TEST_CASE("A stability sweep run in shards through parts equals the in-process sweep",
          "[study][shards]") {
  const double area = 2.85e-4;
  const Scene scene = test::chain({test::bar("striker", test::steel(), 0.1, area, 20, 10.0),
                                   test::bar("bar", test::steel(), 0.5, area, 100)},
                                  1e-4, ContactMethod::kPenalty, Stepping::kAsynchronous);
  const StabilityStudy whole = run_stability_sweep(scene, {ContactMethod::kPenalty}, 2);
  StudyPlan plan;
  plan.id = new_plan_id();
  plan.sweep = Sweep::kStability;
  plan.stability = stability_jobs(stability_grid({ContactMethod::kPenalty}));
  const Scene probe = stability_probe_scene(scene);
  StudyResults merged;
  merged.stability.resize(plan.runs());
  for (std::size_t k = 0; k < 3; ++k) {
    const auto runs = shard_runs(plan.runs(), {k, 3});
    StudyResults own;
    own.stability.resize(plan.runs());
    for (std::size_t r : runs) own.stability[r] = run_stability_job(probe, plan.stability[r]);
    // Through the part's text, as between machines.
    const auto text = part_json(plan, own, runs).dump();
    read_part(nlohmann::json::parse(text), "part", plan, runs, merged);
  }
  const StabilityStudy sharded = assemble_stability(probe, plan.stability, merged.stability);
  REQUIRE(sharded.rows.size() == whole.rows.size());
  REQUIRE(sharded.boundaries.size() == whole.boundaries.size());
  for (std::size_t i = 0; i < whole.rows.size(); ++i) {
    INFO("point " << i);
    CHECK(sharded.rows[i].point.courant == whole.rows[i].point.courant);
    CHECK(sharded.rows[i].verdict.stable == whole.rows[i].verdict.stable);
    CHECK(sharded.rows[i].verdict.energy_growth == whole.rows[i].verdict.energy_growth);
  }
  for (std::size_t i = 0; i < whole.boundaries.size(); ++i)
    CHECK(sharded.boundaries[i].critical_courant == whole.boundaries[i].critical_courant);
}

// Release only (18 s under the sanitizers): plan, run and merge through the executable run
// sanitized in the tests of edited material files, foreign parts and refused merges, the pareto
// sweep in its own test, and sharded sweeps in process in the stability and Monte Carlo tests.
TEST_CASE("shpb study --plan/--run/--merge equals the in-process sweep apart from wall times",
          "[study][shards][app][release-only]") {
  const fs::path dir = shpb_test::scratch_dir("study_shards");
  const fs::path plan = dir / "plan";
  auto run = [](std::vector<std::string> args) {
    args.push_back("--quiet");
    return shpb_test::run_shpb(args);
  };
  REQUIRE(run({"study", kScene, "--plan", plan.string()}).code == 0);
  REQUIRE(fs::exists(plan / "plan.json"));
  for (const char* shard : {"0/3", "1/3", "2/3"})
    REQUIRE(run({"study", "--run", plan.string(), "--shard", shard, "--threads", "1"}).code == 0);
  // A part that exists is skipped (not rewritten).
  const auto written = fs::last_write_time(plan / "parts" / "1-of-3.json");
  REQUIRE(run({"study", "--run", plan.string(), "--shard", "1/3"}).code == 0);
  CHECK(fs::last_write_time(plan / "parts" / "1-of-3.json") == written);
  REQUIRE(run({"study", "--merge", plan.string()}).code == 0);
  REQUIRE(run({"study", kScene, "-o", (dir / "whole").string(), "--threads", "2"}).code == 0);
  CHECK(without_wall_times(plan / "result" / "pareto.csv") ==
        without_wall_times(dir / "whole" / "pareto.csv"));
  // Every planned case ran once: the merged summary counts the plan's cases (the reference apart).
  const auto planned = nlohmann::json::parse(shpb_test::read_text(plan / "plan.json"));
  std::size_t cases = 0;
  for (const auto& r : planned.at("runs")) cases += r.at("kind") == "case" ? 1 : 0;
  CHECK(nlohmann::json::parse(shpb_test::read_text(plan / "result" / "summary.json"))
            .at("runs")
            .get<std::size_t>() == cases);

  SECTION("Wrong sets of parts and wrong uses are exit-2 errors that name the problem") {
    auto fails = [&](std::vector<std::string> args, const std::string& says) {
      const auto r = run(args);
      INFO(r.err);
      CHECK(r.code == 2);
      CHECK(r.err.rfind("error: ", 0) == 0);
      CHECK(r.err.find(says) != std::string::npos);
      CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);  // one line
    };
    fails({"study", "--run", plan.string()}, "--shard");
    fails({"study", "--run", plan.string(), "--shard", "3/3"}, "0 <= K < N");
    fails({"study", kScene, "--plan", plan.string()}, "not empty");
    fails({"study", "--run", (dir / "nowhere").string(), "--shard", "0/1"}, "plan.json");
    // A shard of another split: its runs are held twice.
    REQUIRE(run({"study", "--run", plan.string(), "--shard", "0/6"}).code == 0);
    fails({"study", "--merge", plan.string(), "-o", (dir / "m").string()}, "duplicated part");
    fs::remove(plan / "parts" / "0-of-6.json");
    // A part of another plan.
    REQUIRE(run({"study", kScene, "--plan", (dir / "other").string()}).code == 0);
    REQUIRE(run({"study", "--run", (dir / "other").string(), "--shard", "2/3"}).code == 0);
    fs::copy_file(dir / "other" / "parts" / "2-of-3.json", plan / "parts" / "2-of-3.json",
                  fs::copy_options::overwrite_existing);
    fails({"study", "--merge", plan.string(), "-o", (dir / "m").string()}, "another plan");
    fs::remove(plan / "parts" / "2-of-3.json");
    fails({"study", "--merge", plan.string(), "-o", (dir / "m").string()}, "missing part 2-of-3");
    CHECK_FALSE(fs::exists(dir / "m"));
    // Sweeps are the names of kSweepNames, on the command line and in a plan.
    fails({"study", kScene, "-o", (dir / "m").string(), "--sweep", "stabilty"}, "--sweep");
    const fs::path odd = dir / "odd";
    REQUIRE(run({"study", kScene, "--plan", odd.string()}).code == 0);
    auto j = nlohmann::json::parse(shpb_test::read_text(odd / "plan.json"));
    j["sweep"] = "stabilty";
    std::ofstream(odd / "plan.json") << j.dump();
    fails({"study", "--run", odd.string(), "--shard", "0/1"},
          (odd / "plan.json").string() + ": sweep: \"stabilty\": ");
    CHECK_FALSE(fs::exists(odd / "parts" / "0-of-1.json"));
  }
  SECTION("A scene changed after planning is refused") {
    const fs::path scene = dir / "scene.json";
    fs::copy_file(kScene, scene);
    REQUIRE(run({"study", scene.string(), "--plan", (dir / "p2").string()}).code == 0);
    std::ofstream(scene, std::ios::app) << "\n";
    const auto r = run({"study", "--run", (dir / "p2").string(), "--shard", "0/2"});
    CHECK(r.code == 2);
    CHECK(r.err.find("changed since the plan") != std::string::npos);
  }
  fs::remove_all(dir);
}

// plan.json is read by the project's reader and schema checks (core/json_value.hpp): a damaged or
// hand-edited plan is refused with the file, the JSON path, the value and what was expected, not
// the JSON library's own text ("[json.exception.type_error.302] type must be number, but is
// string" inside a generic line). Planning runs nothing: seconds.
TEST_CASE("study --run refuses a damaged plan.json with its JSON path and value",
          "[study][shards][app]") {
  const fs::path dir = shpb_test::scratch_dir("study_damaged_plan");
  const fs::path plan = dir / "plan";
  REQUIRE(shpb_test::run_shpb({"study", kScene, "--plan", plan.string(), "-q"}).code == 0);
  const fs::path file = plan / "plan.json";
  const std::string good = shpb_test::read_text(file);
  auto refused = [&](const std::function<void(nlohmann::json&)>& edit) {
    auto j = nlohmann::json::parse(good);
    edit(j);
    std::ofstream(file) << j.dump(1);
    const auto r = shpb_test::run_shpb({"study", "--run", plan.string(), "--shard", "0/1", "-q"});
    INFO(r.err);
    CHECK(r.code == 2);
    CHECK(r.err.find("json.exception") == std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(fs::is_empty(plan / "parts"));  // no part written
    return r.err;
  };
  const std::string at = "error: " + file.string() + ": ";
  CHECK(refused([](auto& j) {
          j["runs"][2]["resolution"] = "fine";
        }).starts_with(at + "runs[2].resolution: \"fine\": "));
  CHECK(refused([](auto& j) {
          j["runs"][1]["finite_links"] = 1;
        }).starts_with(at + "runs[1].finite_links: 1: "));
  CHECK(refused([](auto& j) {
          j["runs"][0]["method"] = "penalti";
        }).starts_with(at + "runs[0].method: \"penalti\": "));
  CHECK(refused([](auto& j) {
          j["runs"][0].erase("stepping");
        }).starts_with(at + "runs[0].stepping: (missing): "));
  CHECK(
      refused([](auto& j) { j["options"]["refine"] = 0; }).starts_with(at + "options.refine: 0: "));
  CHECK(refused([](auto& j) {
          j["runs"][3]["kind"] = "point";
        }).starts_with(at + "runs[3].kind: \"point\": not a run of a pareto plan"));
  CHECK(refused([](auto& j) { j["runs"] = "all"; }).starts_with(at + "runs: \"all\": "));
  // Text that is not JSON: its line and column, as a scene's.
  std::ofstream(file) << good.substr(0, good.size() / 2);
  const auto cut = shpb_test::run_shpb({"study", "--run", plan.string(), "--shard", "0/1", "-q"});
  CHECK(cut.code == 2);
  CHECK(cut.err.starts_with(at));
  CHECK(cut.err.find("line ") != std::string::npos);
  // The plan as written still runs (the checks refuse nothing shpb writes).
  std::ofstream(file) << good;
  CHECK(shpb_test::run_shpb({"study", "--run", plan.string(), "--shard", "5/6", "-q"}).code == 0);
}

// The plan holds the sweep and its options: given again to --run or --merge they were ignored
// without a word (`--merge PLAN --sweep pareto` merged a stability plan, exit 0). Refused before
// the plan is read.
TEST_CASE("study --run and --merge refuse the options a plan holds", "[study][shards][app]") {
  const std::string plan = (shpb_test::scratch_dir("study_planned_options") / "plan").string();
  const std::vector<std::vector<std::string>> given = {
      {"--sweep", "pareto"}, {"--contact", "penalty"}, {"--stepping", "global"},
      {"--courant", "0.5"},  {"--tolerance", "1 %"},   {"--refine", "2"}};
  for (const auto& option : given)
    for (const std::vector<std::string>& step :
         {std::vector<std::string>{"--run", plan, "--shard", "0/1"},
          std::vector<std::string>{"--merge", plan}}) {
      std::vector<std::string> args = {"study"};
      args.insert(args.end(), step.begin(), step.end());
      args.insert(args.end(), option.begin(), option.end());
      const auto r = shpb_test::run_shpb(args);
      INFO(step[0] << " " << option[0]);
      CHECK(r.code == 2);
      CHECK(r.err == "error: " + option[0] +
                         ": not with --run or --merge: the plan holds the sweep and its options "
                         "(plan again to change them)\n");
    }
}

}  // namespace tests_study_test_shards
