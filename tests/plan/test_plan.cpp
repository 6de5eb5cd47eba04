// `shpb plan` (docs/commands.md#plan): the planned scene, re-simulated on its own, loads the
// specimen at the target rate; a target the bounds cannot reach is exit 3 naming the bound; a bad
// plan block is exit 2 naming its JSON path, with nothing written.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "../app/polymer_bars.hpp"
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

// The loading of a run (docs/methods.md §12): from the specimen's rate first reaching a tenth of
// the target to its strain maximum, where `process`'s loading ends; [k0, k1] of specimen.csv.
struct Loading {
  std::map<std::string, std::vector<double>> specimen;
  std::size_t k0 = 0, k1 = 0;
  const std::vector<double>& rate() const { return specimen.at("strain_rate_1_s"); }
};
Loading loading(const fs::path& run, double rate) {
  Loading l{read_columns(run / "specimen.csv")};
  const auto& r = l.rate();
  const auto& e = l.specimen.at("strain");
  while (l.k0 + 1 < r.size() && r[l.k0] < 0.1 * rate) ++l.k0;
  l.k1 = l.k0;
  for (std::size_t k = l.k0; k < e.size(); ++k)
    if (e[k] > e[l.k1]) l.k1 = k;
  return l;
}

// The fraction of the loading over which specimen.csv's rate is within ±10 % of the target.
double fraction_in_band(const fs::path& run, double rate) {
  const Loading l = loading(run, rate);
  std::size_t in_band = 0;
  for (std::size_t k = l.k0; k <= l.k1; ++k) in_band += std::abs(l.rate()[k] - rate) <= 0.1 * rate;
  return double(in_band) / double(l.k1 + 1 - l.k0);
}

// When, as a fraction of the loading, the bars' forces on the specimen's faces (interfaces.csv,
// what the gauges measure) come within 5 % of each other to stay until unloading (the loading's
// last rate within ±10 % of the target): R = 2|P1 − P2|/|P1 + P2| ≤ 0.05, the denominator floored
// at 2 % of its peak (docs/methods.md §6).
double equilibrium_fraction(const fs::path& run, double rate) {
  constexpr double kRatio = 0.05, kFloor = 0.02;
  const Loading l = loading(run, rate);
  const auto f = read_columns(run / "interfaces.csv");
  const auto& p1 = f.at("incident-specimen_force_N");
  const auto& p2 = f.at("specimen-transmitter_force_N");
  const auto& t = l.specimen.at("time_s");
  std::size_t unloading = l.k0;
  for (std::size_t k = l.k0; k <= l.k1; ++k)
    if (std::abs(l.rate()[k] - rate) <= 0.1 * rate) unloading = k;
  double peak = 0;
  for (std::size_t k = 0; k < p1.size(); ++k) peak = std::max(peak, std::abs(p1[k] + p2[k]));
  std::size_t held_from = l.k0;
  for (std::size_t k = l.k0; k <= unloading; ++k)
    if (2 * std::abs(p1[k] - p2[k]) > kRatio * std::max(std::abs(p1[k] + p2[k]), kFloor * peak))
      held_from = k + 1;
  return (t[std::min(held_from, l.k1)] - t[l.k0]) / (t[l.k1] - t[l.k0]);
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
  constexpr double kBandRate = 2000, kMinFraction = 0.5;
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
  CHECK(fraction_in_band(dir.path() / "sim", kBandRate) >= kMinFraction);
  // The velocity is what changed: a 2000 1/s rate needs more than the scene's 15 m/s
  // (rate ≈ (v − 2c·ε_T)/L_s with ε_T > 0).
  const auto summary = nlohmann::json::parse(read_text(out / "summary.json"));
  CHECK(summary["chosen"]["striker_velocity_m_s"].get<double>() > 2000 * 0.005);
}

TEST_CASE("A planned striker longer than the scene's records its whole test in the planned scene",
          "[app][plan]") {
  // The classic scene (800 µs, set for its 300 mm striker) at 500 1/s to strain 0.1: a pulse of
  // strain/rate, 200 µs, needs a striker of ~500 mm, and the reflected pulse of a striker longer
  // than 490 mm has not passed the incident gauge (1 m from the specimen: 603 µs after impact)
  // by 800 µs. The planned scene's own gauges, reduced by `process`, must give the strain its
  // specimen reaches (the 1D gauges carry the faces' state exactly; 2 % allows the reduction's
  // end-of-loading sample).
  constexpr double kStrainAgreement = 0.02, kStrikerOutlasting_m = 0.49;
  ScratchDir dir("plan_long_striker");
  const fs::path scene = classic_with_plan(
      dir.path(),
      {{"striker", {{"velocity", {"2 m/s", "40 m/s"}}, {"length", {"100 mm", "1 m"}}}}});
  const auto [plan, proc, err] =
      plan_then_process(dir.path(), scene, {"--rate", "500 1/s", "--strain", "0.1"});
  REQUIRE(plan["chosen"]["striker_length_m"].get<double>() > kStrikerOutlasting_m);
  const double reached = plan["predicted"]["strain_reached"];
  INFO("specimen " << reached << ", processed gauges " << proc["max_strain"]);
  CHECK(std::abs(proc["max_strain"].get<double>() - reached) <= kStrainAgreement * reached);
}

TEST_CASE("A plan's rate is the plateau of the whole test, to the strain maximum", "[app][plan]") {
  // The classic 300 mm striker, velocity free, on the 5 mm Al 6061-T6 specimen at 2500 1/s: the
  // 120 µs pulse takes the specimen past the target strain 0.15, and the test a lab reduces runs
  // to the strain maximum. Its rate, in the planned scene re-simulated on its own (median over the
  // loading) and as `process` quotes it from the planned gauges (mean over its loading), is the
  // target within the secant's 2 % and the meshes' difference (1 %). Judged to the target strain
  // only, the plan read the first half of a test that then slowed as the specimen hardened: 5 %
  // below the target over all of it.
  constexpr double kTarget = 2500, kRateAgreement = 0.03;
  ScratchDir dir("plan_whole_test");
  const fs::path scene =
      classic_with_plan(dir.path(), {{"striker", {{"velocity", {"2 m/s", "40 m/s"}}}}});
  const auto [plan, proc, err] =
      plan_then_process(dir.path(), scene, {"--rate", "2500 1/s", "--strain", "0.15"});
  const auto sim = run_shpb({"simulate", (dir.path() / "out" / "scene.json").string(), "-o",
                             (dir.path() / "sim").string(), "-q"});
  INFO(sim.err);
  REQUIRE(sim.code == 0);
  const Loading l = loading(dir.path() / "sim", kTarget);
  REQUIRE(l.specimen.at("strain")[l.k1] > 0.15);
  std::vector<double> r(l.rate().begin() + l.k0, l.rate().begin() + l.k1 + 1);
  std::nth_element(r.begin(), r.begin() + r.size() / 2, r.end());
  const double median = r[r.size() / 2];
  const double quoted = proc["strain_rate"]["mean_over_loading_1_s"];
  INFO("re-simulated median " << median << ", process's mean " << quoted);
  CHECK(std::abs(median - kTarget) <= kRateAgreement * kTarget);
  CHECK(std::abs(quoted - kTarget) <= kRateAgreement * kTarget);
}

TEST_CASE(
    "A pulse that outlasts the target's hardening is no plan, and the striker it needs is named",
    "[app][plan]") {
  // The classic 300 mm striker on a 3 mm Al 6061-T6 specimen at 5000 1/s (steps planned for strain
  // 0.8): its 120 µs pulse takes the specimen on to strain ~0.58 while its hardening slows it, so
  // its rate has no plateau over the test (within ±10 % of the target over less than half of it).
  // Exit 3 names the band and the striker whose pulse lasts strain/rate: 2L/c = 0.15/5000 s, c of
  // the C350 bars √(200 GPa/8080 kg/m³).
  const double c = std::sqrt(200e9 / 8080), needed = 0.15 * c / (2 * 5000);
  ScratchDir dir("plan_overshoot");
  const fs::path out = dir.path() / "out";
  const auto r = run_shpb({"plan", classic_3mm_velocity_free(dir.path(), 0.8).string(), "--rate",
                           "5000 1/s", "-o", out.string(), "--threads", "2", "-q"});
  INFO(r.err);
  CHECK(r.code == 3);
  CHECK(r.err.find("the rate stays within ±10 % of 5000 1/s") != std::string::npos);
  char striker[64];
  std::snprintf(striker, sizeof striker, "a shorter striker (about %.3g m", needed);
  CHECK(r.err.find(striker) != std::string::npos);
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("The planned scene simulated is the plan's verification run; its progress ends at 100 %",
          "[app][plan]") {
  // docs/commands.md#plan: scene.json is the planned scene, ready for `shpb simulate`; at the
  // verification's gauge error (--tolerance, 0.5 % by default) it is the same run as
  // simulation/, to the last digit. Its values were rounded to four digits (18.71 m/s for
  // 18.7124 m/s): a run of another set-up, on other meshes when a length was rounded.
  ScratchDir dir("plan_scene_exact");
  const fs::path scene =
      classic_with_plan(dir.path(), {{"striker", {{"velocity", {"2 m/s", "40 m/s"}}}}});
  const fs::path out = dir.path() / "out";
  const auto r = run_shpb(
      {"plan", scene.string(), "--rate", "2500 1/s", "-o", out.string(), "--threads", "2"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  // Its progress (docs/commands.md: a plain line every 10 % and at the end) ends at 100 %: it
  // stopped at 90 %, and on a terminal the closing line was written after the bar.
  CHECK(r.err.find("planning: 100%\nplanned ") != std::string::npos);
  const auto sim = run_shpb({"simulate", (out / "scene.json").string(), "-o",
                             (dir.path() / "sim").string(), "--tolerance", "0.5 %", "-q"});
  INFO(sim.err);
  REQUIRE(sim.code == 0);
  for (const char* file : {"specimen.csv", "gauges.csv"}) {
    INFO(file);
    CHECK(read_text(dir.path() / "sim" / file) == read_text(out / "simulation" / file));
  }
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
  INFO(r.err);
  CHECK(r.code == 3);
  CHECK(r.err.find("plan.striker.velocity") != std::string::npos);
  // At 5 m/s the specimen's rate never reaches a tenth of the target, so there is no rate to
  // scale a velocity from (an extrapolation from zero read "about 5e+09 m/s would be needed").
  CHECK(r.err.find("never reaches 10 % of 2e+04 1/s") != std::string::npos);
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("An infeasible plan names the criterion its closest set-up misses most", "[app][plan]") {
  // The classic bars, striker 100 mm–1 m at 2–40 m/s, on a 5 mm Ti-6Al-4V specimen at 2500 1/s
  // to strain 0.15: no unshaped set-up meets the criteria. The line names the criterion the
  // closest set-up misses most, relative to its threshold (docs/methods.md §12, "Infeasible
  // targets"): it named the band missed by a tenth beside equilibrium reached at two thirds of
  // the loading, and, with the loading to the strain maximum, a strain missed by 0.2 % beside a
  // band missed by a quarter, with a striker the bounds allow.
  constexpr double kStrain = 0.15, kBand = 0.5, kEquilibrium = 0.25;
  ScratchDir dir("plan_binding");
  const fs::path scene = classic_with_plan(
      dir.path(),
      {{"striker", {{"velocity", {"2 m/s", "40 m/s"}}, {"length", {"100 mm", "1 m"}}}}});
  nlohmann::json j = nlohmann::json::parse(read_text(scene));
  j["bars"][2]["material"] =
      (fs::path(SHPB_SOURCE_DIR) / "specimens" / "ti6al4v.json").lexically_normal().string();
  std::ofstream(scene) << j.dump(2);
  const auto r = run_shpb({"plan", scene.string(), "--rate", "2500", "--strain", "0.15", "-o",
                           (dir.path() / "out").string(), "--threads", "2", "-q"});
  INFO(r.err);
  REQUIRE(r.code == 3);
  // The closest set-up, as the line describes it: "rate in band over B % of the loading,
  // equilibrium at Q %, strain S".
  auto after = [&](const std::string& key) {
    const auto at = r.err.find(key);
    REQUIRE(at != std::string::npos);
    return std::stod(r.err.substr(at + key.size()));
  };
  const double band = after("rate in band over ") / 100,
               equilibrium = after("equilibrium at ") / 100, strain = after("%, strain ");
  const double missed_strain = std::max(0.0, kStrain - strain) / kStrain,
               missed_band = std::max(0.0, kBand - band) / kBand,
               missed_equilibrium = std::max(0.0, equilibrium - kEquilibrium) / (1 - kEquilibrium);
  const double worst = std::max({missed_strain, missed_band, missed_equilibrium});
  REQUIRE(worst > 0);
  const std::string named = r.err.substr(r.err.find("): ") + 3);
  if (worst == missed_band) CHECK(named.rfind("the rate stays within", 0) == 0);
  if (worst == missed_strain) CHECK(named.rfind("the target strain", 0) == 0);
  if (worst == missed_equilibrium) CHECK(named.rfind("equilibrium", 0) == 0);
}

TEST_CASE(
    "An infeasible plan never names a striker length or velocity the bounds allow as the cause",
    "[app][plan]") {
  // 7075-T6 aluminium bars (19 mm, 1.5 m, c0 = 5051 m/s), a 6 × 6 mm bilinear stainless specimen
  // (yield 300 MPa, tangent 2 GPa) 3–6 mm long, strikers 100–600 mm at 3–30 m/s, 3000 1/s to
  // strain 0.3: a
  // loading of 100 µs needs a striker of E c0/(2R) = 0.253 m, which the bounds allow, but the
  // specimen hardens and slows on these soft bars and no unshaped set-up holds the band. The line
  // named the 100 mm striker's strain, "a striker of at least 0.253 m; the longest allowed is
  // 0.6 m". It must name what the set-ups with a long enough striker miss.
  constexpr double kRate = 3000, kStrain = 0.3, kBarWaveSpeed = 5051.3;
  const double needed = kStrain * kBarWaveSpeed / (2 * kRate);
  ScratchDir dir("plan_striker_allowed");
  nlohmann::json bar = {{"material", "al7075"}, {"length", "1.5 m"}, {"diameter", "19 mm"}};
  nlohmann::json scene = {
      {"bars",
       {{{"name", "striker"},
         {"material", "al7075"},
         {"length", "200 mm"},
         {"diameter", "19 mm"},
         {"velocity", "10 m/s"}},
        {{"name", "incident"},
         {"material", "al7075"},
         {"length", "1.5 m"},
         {"diameter", "19 mm"},
         {"gauges", {{{"name", "incident"}, {"position", "0.75 m"}}}}},
        {{"name", "specimen"}, {"material", "ss"}, {"length", "6 mm"}, {"diameter", "6 mm"}},
        {{"name", "transmitter"},
         {"material", "al7075"},
         {"length", "1.5 m"},
         {"diameter", "19 mm"},
         {"gauges", {{{"name", "transmitted"}, {"position", "0.75 m"}}}}}}},
      {"specimen", "specimen"},
      {"materials",
       {{"al7075",
         {{"model", "elastic"},
          {"density", "2810 kg/m3"},
          {"youngs_modulus", "71.7 GPa"},
          {"poisson_ratio", 0.33}}},
        {"ss",
         {{"model", "bilinear"},
          {"density", "7900 kg/m3"},
          {"youngs_modulus", "193 GPa"},
          {"poisson_ratio", 0.29},
          {"yield_stress", "300 MPa"},
          {"tangent_modulus", "2 GPa"}}}}},
      {"simulation", {{"duration", "700 us"}, {"sample_rate", "10 MHz"}}},
      {"plan",
       {{"striker", {{"length", {"100 mm", "600 mm"}}, {"velocity", {"3 m/s", "30 m/s"}}}},
        {"specimen", {{"length", {"3 mm", "6 mm"}}}}}}};
  std::ofstream(dir.path() / "scene.json") << scene.dump(2);
  const auto r =
      run_shpb({"plan", (dir.path() / "scene.json").string(), "--rate", "3000", "--strain", "0.3",
                "-o", (dir.path() / "out").string(), "--threads", "2", "-q"});
  INFO(r.err);
  REQUIRE(r.code == 3);
  CHECK(r.err.find('\n') == r.err.size() - 1);
  CHECK(r.err.find("a striker of at least") == std::string::npos);
  // The set-up the line describes has a striker long enough for the strain.
  const std::string closest = "(the closest: striker ";
  const auto at = r.err.find(closest);
  REQUIRE(at != std::string::npos);
  CHECK(std::stod(r.err.substr(at + closest.size())) >= needed);
  CHECK_FALSE(fs::exists(dir.path() / "out"));
  // The specimen's length fixed at 6 mm: the closest set-up was a 570 mm striker at the 30 m/s
  // bound, its rate fallen to 1380 1/s over its long loading, and the line asked for 65 m/s while
  // shorter strikers reached 3000 1/s within the bounds. The velocity bound does not bind.
  scene["plan"].erase("specimen");
  std::ofstream(dir.path() / "scene.json") << scene.dump(2);
  const auto fixed =
      run_shpb({"plan", (dir.path() / "scene.json").string(), "--rate", "3000", "--strain", "0.3",
                "-o", (dir.path() / "out").string(), "--threads", "2", "-q"});
  INFO(fixed.err);
  REQUIRE(fixed.code == 3);
  CHECK(fixed.err.find('\n') == fixed.err.size() - 1);
  CHECK(fixed.err.find("plan.striker.velocity: at its upper bound") == std::string::npos);
}

TEST_CASE("A band no allowed shaper meets asks for another shaper, not for one", "[app][plan]") {
  // A 1 mm × 10 mm OFHC copper wafer on the classic bars at 3000 1/s to strain 0.11, a 0.5–1 mm
  // × 4 mm copper shaper allowed: the wafer's strong hardening slows its rate through the loading
  // (rate ≈ (v − 2c ε_T)/L_s), and no set-up holds the band (the closest 35 % of the loading). The
  // shaper was searched: the line asks for one the plan block does not allow; it said "allow a
  // pulse shaper (plan.shaper)".
  ScratchDir dir("plan_shaper_remedy");
  const fs::path scene = classic_with_plan(
      dir.path(),
      {{"striker", {{"velocity", {"2 m/s", "40 m/s"}}, {"length", {"100 mm", "1 m"}}}},
       {"shaper",
        {{"material",
          (fs::path(SHPB_SOURCE_DIR) / "specimens" / "pulse-shaper-copper.json").string()},
         {"thickness", {"0.5 mm", "1 mm"}},
         {"diameter", "4 mm"}}}});
  nlohmann::json j = nlohmann::json::parse(read_text(scene));
  j["bars"][2]["material"] =
      (fs::path(SHPB_SOURCE_DIR) / "specimens" / "ofhc-copper.json").string();
  j["bars"][2]["length"] = "1 mm";
  j["bars"][2]["diameter"] = "10 mm";
  std::ofstream(scene) << j.dump(2);
  const auto r = run_shpb({"plan", scene.string(), "--rate", "3000", "--strain", "0.11", "-o",
                           (dir.path() / "out").string(), "--threads", "2", "-q"});
  INFO(r.err);
  REQUIRE(r.code == 3);
  REQUIRE(r.err.find("the rate stays within") != std::string::npos);
  CHECK(r.err.find("allow a pulse shaper") == std::string::npos);
  CHECK(r.err.find("than plan.shaper allows") != std::string::npos);
}

TEST_CASE("A plan on polymer bars runs on the meshes a polymer bar's run gets", "[app][plan]") {
  // PMMA bars (a generalized Maxwell law) on a soft specimen: the search's 3 % and the
  // verification's 0.5 % meshed the bars with the gauge-error model, which does not cover a
  // polymer bar's attenuation (docs/methods.md §1.1): 98 802 elements on the 2 m incident bar,
  // 2430 x the automatic meshes' node updates, and the plan did not end in 25 CPU-minutes. It now
  // runs its candidates on the automatic meshes and ends with a plan or the closest set-up.
  ScratchDir dir("plan_polymer");
  nlohmann::json scene = shpb_test::polymer_bar_scene();
  scene["plan"] = {{"striker", {{"velocity", {"1 m/s", "20 m/s"}}}}};
  const fs::path file = dir.path() / "scene.json";
  std::ofstream(file) << scene.dump(2);
  const auto r = run_shpb({"plan", file.string(), "--rate", "400", "-o",
                           (dir.path() / "out").string(), "--threads", "2", "-q"});
  INFO(r.err);
  CHECK(
      (r.code == 0 ||
       (r.code == 3 && r.err.find("no set-up within the plan's bounds meets 400 1/s (the closest: "
                                  "striker 0.15 m at ") != std::string::npos)));
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
    // validate reads the block as plan does: the same one line.
    const auto v = run_shpb({"validate", scene.string()});
    CHECK(v.code == 2);
    CHECK(v.err == r.err);
  }
}

TEST_CASE("A tension test is refused by plan, naming the striker's velocity", "[app][plan]") {
  // The bonded tension experiment: its striker is pulled away (-10 m/s). plan searches
  // compression tests only (a positive velocity bound), and planned it as one, the sign turned.
  ScratchDir dir("plan_tension");
  nlohmann::json j = nlohmann::json::parse(
      read_text(fs::path(SHPB_SOURCE_DIR) / "experiments" / "tension-bonded" / "scene.json"));
  j.erase("measurement");
  j["plan"] = {{"striker", {{"velocity", {"2 m/s", "40 m/s"}}}}};
  const fs::path scene = dir.path() / "scene.json", out = dir.path() / "out";
  std::ofstream(scene) << j.dump(2);
  const auto r =
      run_shpb({"plan", scene.string(), "--rate", "1000", "--strain", "0.05", "-o", out.string()});
  INFO(r.err);
  CHECK(r.code == 2);
  CHECK(r.err.rfind("error: " + scene.string() + ": bars[0].velocity: -10 m/s: ", 0) == 0);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK_FALSE(fs::exists(out));
  const auto v = run_shpb({"validate", scene.string()});
  CHECK(v.code == 2);
  CHECK(v.err == r.err);
}

TEST_CASE("At a high rate a shorter specimen brings the bars' forces into equilibrium early",
          "[app][plan][release-only]") {
  // 5000 1/s on the classic Al 6061-T6 specimen from a 100 mm striker: the 5 mm specimen's faces
  // ring 5-9 % apart for half the loading (its plastic wave crosses it slowly), a coarse mesh
  // damps that ringing; a 3 mm one settles within a few microseconds. The plan may cut the
  // specimen to 3-5 mm. The criteria (docs/methods.md §12): the rate within ±10 % over at least
  // half the loading, equilibrium of the bars' forces before a quarter of it.
  constexpr double kRate = 5000, kMinBand = 0.5, kMaxEquilibrium = 0.25;
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
  CHECK(fraction_in_band(sim, kRate) >= kMinBand);
  CHECK(equilibrium_fraction(sim, kRate) <= kMaxEquilibrium);
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
  // plateau), so the plan ends with exit 3 naming the closest set-up, its rate in the band over
  // less than the half of the loading a plan needs.
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
  const std::string band = "rate in band over ";
  REQUIRE(r.err.find(band) != std::string::npos);
  CHECK(std::stod(r.err.substr(r.err.find(band) + band.size())) < 50);
  const std::string key = "no shaper";
  const auto at = r.err.rfind(" at ", r.err.find(key));
  REQUIRE(at != std::string::npos);
  const double planned = std::stod(r.err.substr(at + 4));
  CHECK(std::abs(planned - velocity) <= kVelocityTolerance * velocity);
}

}  // namespace tests_plan_test_plan
