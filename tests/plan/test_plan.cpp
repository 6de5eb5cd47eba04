// `shpb plan` (docs/commands.md#plan): the planned scene, re-simulated on its own, loads the
// specimen at the target rate; a target the bounds cannot reach is exit 3 naming the bound; a bad
// plan block is exit 2 naming its JSON path, with nothing written.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "../app/run_shpb.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_plan_test_plan {

namespace fs = std::filesystem;
using shpb_test::read_text;
using shpb_test::run_shpb;
using shpb_test::ScratchDir;

namespace {

const fs::path kClassic = fs::path(SHPB_SOURCE_DIR) / "experiments" / "classic-al6061";

// The classic Al 6061-T6 scene (5 mm specimen, 300 mm striker) with `plan` as its plan block,
// written to `dir` with its specimen material by absolute path.
fs::path classic_with_plan(const fs::path& dir, const nlohmann::json& plan,
                           const std::string& striker_length = "") {
  nlohmann::json j = nlohmann::json::parse(read_text(kClassic / "scene.json"));
  if (!striker_length.empty()) j["bars"][0]["length"] = striker_length;
  for (auto& b : j["bars"])
    if (b["material"].get<std::string>().find('/') != std::string::npos)
      b["material"] = (kClassic / b["material"].get<std::string>()).lexically_normal().string();
  j["plan"] = plan;
  const fs::path file = dir / "scene.json";
  std::ofstream(file) << j.dump(2);
  return file;
}

// The fraction of the loading — from the strain rate first reaching a tenth of the target to the
// target strain — over which specimen.csv's rate is within ±10 % of the target.
double fraction_in_band(const fs::path& specimen_csv, double rate, double strain) {
  std::ifstream in(specimen_csv);
  std::string line;
  std::getline(in, line);  // time_s,strain,strain_rate_1_s,...
  std::size_t loading = 0, in_band = 0;
  bool started = false;
  while (std::getline(in, line)) {
    std::stringstream s(line);
    std::string cell;
    std::vector<double> v;
    while (std::getline(s, cell, ',')) v.push_back(std::stod(cell));
    if (!started && v[2] >= 0.1 * rate) started = true;
    if (!started) continue;
    if (v[1] >= strain) break;
    ++loading;
    in_band += std::abs(v[2] - rate) <= 0.1 * rate;
  }
  return loading ? double(in_band) / double(loading) : 0.0;
}

// The columns of a CSV file written by shpb, by name.
std::map<std::string, std::vector<double>> read_columns(const fs::path& csv) {
  std::ifstream in(csv);
  std::string line, cell;
  std::getline(in, line);
  std::vector<std::string> names;
  for (std::stringstream s(line); std::getline(s, cell, ',');) names.push_back(cell);
  std::map<std::string, std::vector<double>> out;
  while (std::getline(in, line)) {
    std::stringstream s(line);
    for (std::size_t i = 0; i < names.size() && std::getline(s, cell, ','); ++i)
      out[names[i]].push_back(std::stod(cell));
  }
  return out;
}

// When, as a fraction of the loading (the rate first at a tenth of the target to the target
// strain), the bars' forces on the specimen's faces (interfaces.csv, what the gauges measure)
// come within 5 % of each other to stay: R = 2|P1 − P2|/|P1 + P2| ≤ 0.05, the denominator floored
// at 2 % of its peak (docs/methods.md §6).
double equilibrium_fraction(const fs::path& run, double rate, double strain) {
  constexpr double kRatio = 0.05, kFloor = 0.02;
  const auto s = read_columns(run / "specimen.csv");
  const auto f = read_columns(run / "interfaces.csv");
  const auto& p1 = f.at("incident-specimen_force_N");
  const auto& p2 = f.at("specimen-transmitter_force_N");
  const auto& t = s.at("time_s");
  std::size_t k0 = 0, k1 = 0;
  while (k0 < t.size() && s.at("strain_rate_1_s")[k0] < 0.1 * rate) ++k0;
  for (k1 = k0; k1 + 1 < t.size() && s.at("strain")[k1] < strain;) ++k1;
  double peak = 0;
  for (std::size_t k = 0; k < p1.size(); ++k) peak = std::max(peak, std::abs(p1[k] + p2[k]));
  std::size_t held_from = k0;
  for (std::size_t k = k0; k <= k1; ++k)
    if (2 * std::abs(p1[k] - p2[k]) > kRatio * std::max(std::abs(p1[k] + p2[k]), kFloor * peak))
      held_from = k + 1;
  return (t[std::min(held_from, k1)] - t[k0]) / (t[k1] - t[k0]);
}

// `shpb plan` of `scene` with `args`, then `process` of the planned scene's own gauges: the two
// summary.json, or the failing command's exit (INFO'd) stops the test.
struct PlannedAndProcessed {
  nlohmann::json plan, process;
  std::string plan_err;
};
PlannedAndProcessed plan_then_process(const fs::path& dir, const fs::path& scene,
                                      std::vector<std::string> args) {
  const fs::path out = dir / "out";
  args.insert(args.begin(), {"plan", scene.string()});
  args.insert(args.end(), {"-o", out.string(), "--threads", "2", "-q"});
  const auto r = run_shpb(args);
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto p =
      run_shpb({"process", (out / "scene.json").string(), "--signals",
                (out / "simulation" / "gauges.csv").string(), "-o", (dir / "proc").string(), "-q"});
  INFO(p.err);
  REQUIRE(p.code == 0);
  return {nlohmann::json::parse(read_text(out / "summary.json")),
          nlohmann::json::parse(read_text(dir / "proc" / "summary.json")), r.err};
}

// The classic scene with the striker's velocity free (2–40 m/s) and a 3 mm specimen, its steps
// planned for `max_strain` when given.
fs::path classic_3mm_velocity_free(const fs::path& dir, std::optional<double> max_strain = {}) {
  const fs::path scene = classic_with_plan(dir, {{"striker", {{"velocity", {"2 m/s", "40 m/s"}}}}});
  nlohmann::json j = nlohmann::json::parse(read_text(scene));
  j["bars"][2]["length"] = "3 mm";
  if (max_strain) j["simulation"]["max_strain"] = *max_strain;
  std::ofstream(scene) << j.dump(2);
  return scene;
}

}  // namespace

TEST_CASE("A planned striker velocity, re-simulated on its own, holds the target rate",
          "[app][plan][release-only]") {
  // The criterion of a usable test: the rate within ±10 % of the target over at least half of the
  // loading (docs/methods.md §12).
  constexpr double kBandRate = 2000, kStrain = 0.15, kMinFraction = 0.5;
  ScratchDir dir("plan_band");
  const fs::path scene =
      classic_with_plan(dir.path(), {{"striker", {{"velocity", {"2 m/s", "40 m/s"}}}}});
  const fs::path out = dir.path() / "out";
  const auto r = run_shpb({"plan", scene.string(), "--rate", "2000 1/s", "-o", out.string(),
                           "--tolerance", "1 %", "--threads", "2", "-q"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  // The planned scene alone, at a finer mesh than the search's.
  const auto sim = run_shpb({"simulate", (out / "scene.json").string(), "-o",
                             (dir.path() / "sim").string(), "--tolerance", "1 %", "-q"});
  INFO(sim.err);
  REQUIRE(sim.code == 0);
  CHECK(fraction_in_band(dir.path() / "sim" / "specimen.csv", kBandRate, kStrain) >= kMinFraction);
  // The velocity is what changed: a 2000 1/s rate needs more than the scene's 15 m/s
  // (rate ≈ (v − 2c·ε_T)/L_s with ε_T > 0).
  const auto summary = nlohmann::json::parse(read_text(out / "summary.json"));
  CHECK(summary["chosen"]["striker_velocity_m_s"].get<double>() > 2000 * 0.005);
}

TEST_CASE("A planned striker longer than the scene's records its whole test in the planned scene",
          "[app][plan]") {
  // A 900 mm striker in the classic scene (800 µs, set for its 300 mm striker): the reflected
  // pulse of a 360 µs loading passes the incident gauge ~1 ms after impact. The planned scene's
  // own gauges, reduced by `process`, must give the strain its specimen reaches (the 1D gauges
  // carry the faces' state exactly; 2 % allows the reduction's end-of-loading sample).
  constexpr double kStrainAgreement = 0.02;
  ScratchDir dir("plan_long_striker");
  const fs::path scene =
      classic_with_plan(dir.path(), {{"striker", {{"velocity", {"2 m/s", "40 m/s"}}}}}, "900 mm");
  const auto [plan, proc, err] =
      plan_then_process(dir.path(), scene, {"--rate", "500 1/s", "--strain", "0.1"});
  const double reached = plan["predicted"]["strain_reached"];
  INFO("specimen " << reached << ", processed gauges " << proc["max_strain"]);
  CHECK(std::abs(proc["max_strain"].get<double>() - reached) <= kStrainAgreement * reached);
}

TEST_CASE(
    "plan says the mean rate process will quote when the pulse loads the specimen far past the "
    "target strain",
    "[app][plan]") {
  // The classic 300 mm striker on a 3 mm Al 6061-T6 specimen at 5000 1/s: the criteria, judged up
  // to strain 0.15, are met, but the 120 µs pulse takes the specimen on to strain ~0.5 while its
  // hardening slows it. The whole loading's mean rate is stated, equal to `process`'s mean over
  // the loading of the planned gauges (the 1D gauges carry the faces' state; 2 % allows the
  // reduction's first and last samples), and a mean more than the ±10 % band off is warned about.
  // The steps are planned for strain 0.8, so that a test to ~0.5 is one the plan may propose.
  constexpr double kRateAgreement = 0.02, kRateBand = 0.1, kTarget = 5000;
  ScratchDir dir("plan_overshoot");
  const auto [plan, proc, err] = plan_then_process(
      dir.path(), classic_3mm_velocity_free(dir.path(), 0.8), {"--rate", "5000 1/s"});
  REQUIRE(plan["predicted"].contains("test_mean_rate_1_s"));
  const double stated = plan["predicted"]["test_mean_rate_1_s"];
  const double quoted = proc["strain_rate"]["mean_over_loading_1_s"];
  INFO("plan's whole-loading mean " << stated << ", process " << quoted);
  CHECK(std::abs(stated - quoted) <= kRateAgreement * quoted);
  REQUIRE(std::abs(quoted - kTarget) > kRateBand * kTarget);
  CHECK(err.find("warning: the pulse loads the specimen on to strain") != std::string::npos);
  CHECK(plan["warnings"].size() == 1);
}

TEST_CASE("A plan is never a test the simulation's planned steps cannot verify", "[app][plan]") {
  // The classic 300 mm striker, velocity free, on a 3 mm specimen at 5000 1/s takes the specimen
  // to a mean strain of ~0.48: within the default simulation.max_strain 0.5 on the search's meshes,
  // while its shortest element runs ahead of the mean and crossed 0.5 on finer ones (exit 3). A
  // plan keeps the mean below 90 % of max_strain, so this one has no set-up: exit 3 naming it.
  ScratchDir dir("plan_max_strain");
  const fs::path scene = classic_3mm_velocity_free(dir.path());
  const fs::path out = dir.path() / "out";
  const auto r = run_shpb(
      {"plan", scene.string(), "--rate", "5000 1/s", "-o", out.string(), "--threads", "2", "-q"});
  INFO(r.err);
  CHECK(r.code == 3);
  CHECK(r.err.find("simulation.max_strain") != std::string::npos);
  CHECK_FALSE(fs::exists(out / "scene.json"));
}

TEST_CASE("A rate beyond the striker's velocity bound is exit 3 naming that bound", "[app][plan]") {
  ScratchDir dir("plan_infeasible");
  const fs::path scene =
      classic_with_plan(dir.path(), {{"striker", {{"velocity", {"2 m/s", "5 m/s"}}}}});
  const fs::path out = dir.path() / "out";
  // 20 000 1/s on a 5 mm specimen needs the specimen's faces 100 m/s apart: far beyond 5 m/s.
  const auto r = run_shpb({"plan", scene.string(), "--rate", "20000 1/s", "-o", out.string(),
                           "--search-tolerance", "10 %", "--tolerance", "10 %", "-q"});
  CHECK(r.code == 3);
  CHECK(r.err.find("plan.striker.velocity") != std::string::npos);
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("A bad plan block is exit 2 naming its JSON path, with nothing written", "[app][plan]") {
  ScratchDir dir("plan_bad");
  const fs::path out = dir.path() / "out";
  struct Case {
    nlohmann::json plan;
    std::string path;
  };
  const std::vector<Case> cases = {
      {{{"striker", {{"velocity", {"40 m/s", "2 m/s"}}}}}, "plan.striker.velocity"},
      {{{"striker", {{"length", "-1 m"}, {"velocity", "10 m/s"}}}}, "plan.striker.length"},
      {{{"striker", {{"velocity", "10 m/s"}}}, {"shaper", {{"material", "no-such-metal"}}}},
       "plan.shaper.material"},
      {{{"striker", {{"velocity", "10 m/s"}}}, {"specimen", {{"width", "1 mm"}}}}, "plan.specimen"},
      {{{"speed", 1}}, "plan"},
  };
  for (const auto& c : cases) {
    const fs::path scene = classic_with_plan(dir.path(), c.plan);
    const auto r = run_shpb({"plan", scene.string(), "--rate", "1000", "-o", out.string(), "-q"});
    INFO(c.plan.dump() << "\n" << r.err);
    CHECK(r.code == 2);
    CHECK(r.err.find(c.path) != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK_FALSE(fs::exists(out));
  }
}

TEST_CASE("At a high rate a shorter specimen brings the bars' forces into equilibrium early",
          "[app][plan][release-only]") {
  // 5000 1/s on the classic Al 6061-T6 specimen from a 100 mm striker: the 5 mm specimen's faces
  // ring 5-9 % apart for half the loading (its plastic wave crosses it slowly), a coarse mesh
  // damps that ringing; a 3 mm one settles within a few microseconds. The plan may cut the
  // specimen to 3-5 mm. The criteria (docs/methods.md §12): the rate within ±10 % over at least
  // half the loading, equilibrium of the bars' forces before a quarter of it.
  constexpr double kRate = 5000, kStrain = 0.15, kMinBand = 0.5, kMaxEquilibrium = 0.25;
  ScratchDir dir("plan_equilibrium");
  const fs::path scene = classic_with_plan(dir.path(),
                                           {{"striker", {{"velocity", {"2 m/s", "40 m/s"}}}},
                                            {"specimen", {{"length", {"3 mm", "5 mm"}}}}},
                                           "100 mm");
  const fs::path out = dir.path() / "out";
  const auto r = run_shpb({"plan", scene.string(), "--rate", "5000 1/s", "-o", out.string(),
                           "--tolerance", "1 %", "--threads", "2", "-q"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const fs::path sim = dir.path() / "sim";
  const auto run = run_shpb(
      {"simulate", (out / "scene.json").string(), "-o", sim.string(), "--tolerance", "1 %", "-q"});
  INFO(run.err);
  REQUIRE(run.code == 0);
  CHECK(fraction_in_band(sim / "specimen.csv", kRate, kStrain) >= kMinBand);
  CHECK(equilibrium_fraction(sim, kRate, kStrain) <= kMaxEquilibrium);
  // The best unshaped set-up is reported beside the chosen one (here the chosen one itself), and
  // no shaped one: the plan allowed none.
  const auto summary = nlohmann::json::parse(read_text(out / "summary.json"));
  REQUIRE(summary["unshaped"].is_object());
  CHECK(summary["unshaped"]["predicted"]["band_fraction"] == summary["predicted"]["band_fraction"]);
  CHECK((summary.contains("shaped") && summary["shaped"].is_null()));
}

TEST_CASE("The LANL PMMA record's striker velocity is planned back from its rate and strain",
          "[app][plan][release-only]") {
  // The measured PMMA #13 mini-Kolsky record, reduced by `process`, gives its striker velocity
  // (from the incident plateau), mean strain rate and largest strain. Planned for that rate and
  // strain with the striker length fixed, no shaper and the specimen law fitted to this record
  // (specimens/pmma-lanl-mini-kolsky-fitted.json), the striker velocity comes back within 10 %:
  // the spread of the fit's own velocity (95 % interval ±7 %) and more than a gas gun's launch
  // scatter. The record itself holds its rate within ±10 % over only a fifth of the loading (no
  // plateau), so the plan ends with exit 3 naming the rate band and the closest set-up.
  constexpr double kVelocityTolerance = 0.10;
  const fs::path exp = fs::path(SHPB_SOURCE_DIR) / "experiments" / "lanl-pmma13-mini-kolsky";
  ScratchDir dir("plan_pmma");
  const auto p = run_shpb(
      {"process", (exp / "scene.json").string(), "-o", (dir.path() / "process").string(), "-q"});
  INFO(p.err);
  REQUIRE(p.code == 0);
  const auto record = nlohmann::json::parse(read_text(dir.path() / "process" / "summary.json"));
  const double velocity = record["striker_velocity_m_s"]["inferred"].get<double>();
  const double rate = record["strain_rate"]["mean_over_loading_1_s"].get<double>();
  const double strain = record["max_strain"].get<double>();
  const auto r =
      run_shpb({"plan", (exp / "plan.json").string(), "--rate", std::to_string(rate), "--strain",
                std::to_string(strain), "-o", (dir.path() / "plan").string(), "-q"});
  INFO(r.err);
  CHECK(r.code == 3);
  CHECK(r.err.find("the rate stays within ±10 %") != std::string::npos);
  const std::string key = "no shaper";
  const auto at = r.err.rfind(" at ", r.err.find(key));
  REQUIRE(at != std::string::npos);
  const double planned = std::stod(r.err.substr(at + 4));
  CHECK(std::abs(planned - velocity) <= kVelocityTolerance * velocity);
}

}  // namespace tests_plan_test_plan
