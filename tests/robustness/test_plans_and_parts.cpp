// Plans and parts are inputs (docs/outputs.md, plans and parts): they carry the digest of every
// file their runs read and are checked before use, so an input edited between shards, a part cut
// short or edited, or a shard number past what a plan can hold is an exit-2 line naming the file,
// never a merged result computed from two versions of the inputs, an out-of-bounds read or a
// wrapped-around shard. Every case runs the real executable.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "child_process.hpp"
#include "measured_test.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_robustness_test_plans_and_parts {

namespace {

using namespace shpb_robust;

constexpr double kLimit_s = kMeasuredTestLimit_s;

// A striker on a bar, its steel read from the file steel.json beside it: a study with an exact
// reference, each run well under a second.
const char* const kStrikerScene = R"({
  "name": "plans",
  "bars": [
    {"name": "striker", "material": "steel.json", "length": "200 mm", "diameter": "12 mm",
     "velocity": "10 m/s"},
    {"name": "bar", "material": "steel.json", "length": "1 m", "diameter": "12 mm",
     "gauges": [{"name": "gauge", "position": "500 mm"}]}
  ],
  "simulation": {"duration": "50 us", "sample_rate": "1 MHz"}
})";
const char* const kSteel = R"({"model": "elastic", "density": "7850 kg/m3",
  "youngs_modulus": "200 GPa", "poisson_ratio": 0.29})";

Outcome shpb(std::vector<std::string> args, const fs::path& dir) {
  args.push_back("-q");
  return run(args, dir, kLimit_s);
}

// scene.json and steel.json in `dir`, planned into dir/plan (one method, one stepping: few runs).
fs::path planned_study(const fs::path& dir) {
  write_bytes(dir / "steel.json", kSteel);
  write_bytes(dir / "scene.json", kStrikerScene);
  const Outcome o = shpb({"study", (dir / "scene.json").string(), "--plan", (dir / "plan").string(),
                          "--contact", "bipenalty", "--stepping", "global"},
                         dir);
  INFO(o.err);
  REQUIRE(o.code == 0);
  return dir / "plan";
}

nlohmann::json read_json(const fs::path& file) { return nlohmann::json::parse(read_all(file)); }

}  // namespace

TEST_CASE("A material file edited between study shards is named by the next shard and the merge",
          "[robustness][plans]") {
  ScratchFolder scratch("plans");
  const fs::path plan = planned_study(scratch.path());
  REQUIRE(
      shpb({"study", "--run", plan.string(), "--shard", "0/2", "--threads", "1"}, scratch.path())
          .code == 0);
  write_bytes(scratch.path() / "steel.json", std::string(kSteel) + "\n");  // one byte more
  check_refused(shpb({"study", "--run", plan.string(), "--shard", "1/2"}, scratch.path()),
                "steel.json");
  CHECK_FALSE(fs::exists(plan / "parts" / "1-of-2.json"));
  check_refused(shpb({"study", "--merge", plan.string()}, scratch.path()), "steel.json");
  CHECK_FALSE(fs::exists(plan / "result"));
}

TEST_CASE("A study part with shortened gauge arrays or foreign columns is refused naming it",
          "[robustness][plans]") {
  ScratchFolder scratch("plans");
  const fs::path plan = planned_study(scratch.path());
  REQUIRE(
      shpb({"study", "--run", plan.string(), "--shard", "0/1", "--threads", "1"}, scratch.path())
          .code == 0);
  const fs::path part = plan / "parts" / "0-of-1.json";
  const nlohmann::json good = read_json(part);
  REQUIRE(good.at("results").at(0).at("gauges").at("values").at(0).size() > 2);
  const std::vector<std::function<void(nlohmann::json&)>> damages = {
      [](nlohmann::json& j) {  // the values of the first gauge cut short
        auto& v = j["results"][0]["gauges"]["values"][0];
        v.erase(v.end() - 2, v.end());
      },
      [](nlohmann::json& j) {  // the times cut short: values longer than the clock
        auto& t = j["results"][0]["gauges"]["time_s"];
        t.erase(t.end() - 2, t.end());
      },
      [](nlohmann::json& j) { j["results"][0]["gauges"]["values"].erase(0); },
      [](nlohmann::json& j) { j["results"][0]["gauges"]["columns"][0] = "other"; },
      [](nlohmann::json& j) { j.erase("inputs"); },
  };
  for (std::size_t d = 0; d < damages.size(); ++d) {
    INFO("damage " << d);
    nlohmann::json j = good;
    damages[d](j);
    write_bytes(part, j.dump());
    check_refused(shpb({"study", "--merge", plan.string()}, scratch.path()), "0-of-1.json");
    CHECK_FALSE(fs::exists(plan / "result"));
  }
  write_bytes(part, good.dump());
  CHECK(shpb({"study", "--merge", plan.string()}, scratch.path()).code == 0);
}

TEST_CASE("A scene or measured file edited after its campaign shard ran is named at the merge",
          "[robustness][plans]") {
  ScratchFolder scratch("plans");
  const fs::path dir = scratch.path() / "t";
  measured_campaign(dir);
  const fs::path out = dir / "out";
  const auto campaign = [&](std::vector<std::string> more) {
    std::vector<std::string> a = {"process", "--campaign", (dir / "c.json").string(), "-o",
                                  out.string()};
    a.insert(a.end(), more.begin(), more.end());
    return shpb(a, dir);
  };
  for (const char* shard : {"0/2", "1/2"}) REQUIRE(campaign({"--shard", shard}).code == 0);
  for (const fs::path& edited : {dir / "second.json", dir / "sim" / "gauges.csv"}) {
    INFO(edited);
    const std::string original = read_all(edited);
    write_bytes(edited, original + "\n");
    check_refused(campaign({"--merge"}), edited.filename().string());
    CHECK_FALSE(fs::exists(out / "result"));
    write_bytes(edited, original);
  }
  CHECK(campaign({"--merge"}).code == 0);
}

TEST_CASE("A truncated or garbled curve.csv in a campaign part is refused, not merged",
          "[robustness][plans]") {
  ScratchFolder scratch("plans");
  const fs::path dir = scratch.path() / "t";
  measured_test(dir);
  const fs::path out = dir / "out";
  REQUIRE(
      shpb({"process", (dir / "measured.json").string(), "-o", out.string(), "--shard", "0/1"}, dir)
          .code == 0);
  const fs::path curve = out / "parts" / "0-of-1" / "measured" / "curve.csv";
  const std::string whole = read_all(curve);
  REQUIRE(std::count(whole.begin(), whole.end(), '\n') > 10);
  const std::size_t half_line = whole.rfind('\n', whole.size() / 2) + 1;
  std::string garbled = whole;
  garbled[whole.find(',', half_line) + 1] = 'x';
  for (const std::string& broken :
       {whole.substr(0, half_line), whole.substr(0, half_line + 5), garbled}) {
    write_bytes(curve, broken);
    check_refused(shpb({"process", (dir / "measured.json").string(), "-o", out.string(),
                        "--flow-stress-at", "0.02", "--merge"},
                       dir),
                  "curve.csv");
    CHECK_FALSE(fs::exists(out / "result"));
  }
}

TEST_CASE("A shard count past what a plan can hold (2^64-1, or overflowing) is refused",
          "[robustness][plans]") {
  ScratchFolder scratch("plans");
  const fs::path plan = planned_study(scratch.path());
  for (const std::string shard :
       {"1/18446744073709551615", "0/18446744073709551615", "0/18446744073709551616"}) {
    INFO(shard);
    check_refused(shpb({"study", "--run", plan.string(), "--shard", shard}, scratch.path()),
                  "--shard");
    CHECK((!fs::exists(plan / "parts") || fs::is_empty(plan / "parts")));
    write_bytes(scratch.path() / "c.json", R"({"tests": [{"scene": "scene.json"}]})");
    check_refused(shpb({"process", "--campaign", (scratch.path() / "c.json").string(), "-o",
                        (scratch.path() / "out").string(), "--shard", shard},
                       scratch.path()),
                  "--shard");
  }
}

}  // namespace tests_robustness_test_plans_and_parts
