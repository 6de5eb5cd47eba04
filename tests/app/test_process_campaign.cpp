// `shpb process` over a campaign (app/process_campaign.cpp): each test's folder is what the
// one-test command writes, campaign.csv holds each test's numbers exactly as processing it alone
// gives them, and shards merged equal the unsharded campaign byte for byte.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "../skip.hpp"
#include "output_schema_check.hpp"
#include "run_shpb.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_app_test_process_campaign {

namespace fs = std::filesystem;

namespace {
const fs::path kRoot(SHPB_SOURCE_DIR);

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream s(line);
  for (std::string c; std::getline(s, c, ',');) cells.push_back(c);
  if (!line.empty() && line.back() == ',') cells.push_back("");
  return cells;
}

// campaign.csv as rows of column → cell (warnings may hold commas: only the number columns are
// read, which come before them).
std::vector<std::map<std::string, std::string>> read_campaign_csv(const fs::path& csv) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  const auto header = split(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    const auto cells = split(line);
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i + 1 < header.size() && i < cells.size(); ++i)
      row[header[i]] = cells[i];
    rows.push_back(row);
  }
  return rows;
}

nlohmann::json summary(const fs::path& dir) {
  std::ifstream in(dir / "summary.json");
  return nlohmann::json::parse(in);
}

// The row's numbers against the test processed alone: equal to the last bit.
void check_row_equals_alone(const std::map<std::string, std::string>& row,
                            const nlohmann::json& alone) {
  INFO("test " << row.at("test"));
  if (alone["plateau_strain_rate_1_s"].is_null())  // no plateau: an empty cell
    CHECK(row.at("plateau_strain_rate_1_s").empty());
  else
    CHECK(std::stod(row.at("plateau_strain_rate_1_s")) ==
          alone["plateau_strain_rate_1_s"].get<double>());
  CHECK(std::stod(row.at("peak_stress_Pa")) == alone["peak_stress_Pa"].get<double>());
  CHECK(std::stod(row.at("striker_velocity_inferred_m_s")) ==
        alone["striker_velocity_m_s"]["inferred"].get<double>());
  if (alone["time_to_equilibrium_s"].is_null())
    CHECK(row.at("time_to_equilibrium_s").empty());
  else
    CHECK(std::stod(row.at("time_to_equilibrium_s")) ==
          alone["time_to_equilibrium_s"].get<double>());
}

// Three simulated tests of the classic Al 6061-T6 set-up at 10, 15 and 20 m/s, each a scene whose
// measurement is its simulated gauges.csv (no dispersion to correct: the 1D model has none).
struct Campaign3 {
  fs::path dir = shpb_test::scratch_dir("process_campaign");
  fs::path campaign = dir / "campaign.json";
  std::vector<std::string> names = {"v10", "v15", "v20"};
  Campaign3() {
    std::ifstream in(kRoot / "experiments/classic-al6061/scene.json");
    const nlohmann::json classic = nlohmann::json::parse(in);
    nlohmann::json tests = nlohmann::json::array();
    for (const std::string v : {"10", "15", "20"}) {
      nlohmann::json scene = classic;
      scene["bars"][0]["velocity"] = v + " m/s";
      scene["bars"][2]["material"] = (kRoot / "specimens/al6061-t6.json").string();
      const fs::path folder = dir / ("v" + v);
      fs::create_directories(folder);
      std::ofstream(folder / "sim.json") << scene.dump(1);
      const auto sim = shpb_test::run_shpb(
          {"simulate", (folder / "sim.json").string(), "-o", (folder / "sim").string(), "-q"});
      REQUIRE(sim.code == 0);
      scene["measurement"] = {
          {"file", (folder / "sim/gauges.csv").string()},
          {"time", {{"column", "time_s"}, {"unit", "s"}}},
          {"channels",
           {{{"gauge", "incident"}, {"column", "incident"}, {"unit", "strain"}},
            {{"gauge", "transmitted"}, {"column", "transmitted"}, {"unit", "strain"}}}},
          {"dispersion", {{"correction", "none"}}}};
      std::ofstream(folder / "scene.json") << scene.dump(1);
      tests.push_back({{"scene", "v" + v + "/scene.json"}, {"name", "v" + v}});
    }
    std::ofstream(campaign) << nlohmann::json{
        {"name", "Al 6061-T6 at three rates"},
        {"tests", tests}}.dump(1);
  }
  ~Campaign3() { fs::remove_all(dir); }
};
}  // namespace

TEST_CASE("A campaign's rows equal each test processed alone; flow stress on its own curve",
          "[app][process][campaign]") {
  const Campaign3 c;
  const fs::path out = c.dir / "out";
  const auto r = shpb_test::run_shpb({"process", "--campaign", c.campaign.string(), "-o",
                                      out.string(), "--flow-stress-at", "0.02,0.05", "-q"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto rows = read_campaign_csv(out / "campaign.csv");
  REQUIRE(rows.size() == 3);
  for (std::size_t i = 0; i < 3; ++i) {
    const auto& row = rows[i];
    CHECK(row.at("test") == c.names[i]);
    const fs::path alone = c.dir / ("alone_" + c.names[i]);
    REQUIRE(shpb_test::run_shpb({"process", (c.dir / c.names[i] / "scene.json").string(), "-o",
                                 alone.string(), "-q"})
                .code == 0);
    check_row_equals_alone(row, summary(alone));
    // The test's folder is the one-test command's output.
    CHECK(shpb_test::read_text(out / c.names[i] / "curve.csv") ==
          shpb_test::read_text(alone / "curve.csv"));
    // Flow stress at 5 %: between the 3-wave stresses of the two samples around 5 % strain.
    std::ifstream curve(alone / "curve.csv");
    std::string line;
    std::getline(curve, line);
    const auto header = split(line);
    const auto col = [&](const std::string& n) {
      return static_cast<std::size_t>(std::find(header.begin(), header.end(), n) - header.begin());
    };
    double prev_strain = 0, prev_stress = 0;
    bool found = false;
    while (!found && std::getline(curve, line)) {
      const auto cells = split(line);
      const double e = std::stod(cells[col("strain")]),
                   s = std::stod(cells[col("stress_3wave_Pa")]);
      if (prev_strain < 0.05 && e >= 0.05) {
        const double f = std::stod(row.at("flow_stress_Pa_at_0.05"));
        CHECK(f >= std::min(prev_stress, s));
        CHECK(f <= std::max(prev_stress, s));
        found = true;
      }
      prev_strain = e;
      prev_stress = s;
    }
    CHECK(found == !row.at("flow_stress_Pa_at_0.05").empty());
  }
  // Faster striker, higher plateau strain rate (Δε̇ ∝ ΔV for the same specimen).
  CHECK(std::stod(rows[0].at("plateau_strain_rate_1_s")) <
        std::stod(rows[2].at("plateau_strain_rate_1_s")));

  SECTION("Two shards merged equal the unsharded campaign byte for byte") {
    const fs::path work = c.dir / "sharded";
    for (const char* shard : {"1/2", "0/2"})
      REQUIRE(shpb_test::run_shpb({"process", "--campaign", c.campaign.string(), "-o",
                                   work.string(), "--shard", shard, "-q"})
                  .code == 0);
    const auto merged =
        shpb_test::run_shpb({"process", "--campaign", c.campaign.string(), "-o", work.string(),
                             "--merge", "--flow-stress-at", "0.02,0.05", "-q"});
    INFO(merged.err);
    REQUIRE(merged.code == 0);
    CHECK(shpb_test::read_text(work / "result/campaign.csv") ==
          shpb_test::read_text(out / "campaign.csv"));
    for (const auto& n : c.names)
      CHECK(shpb_test::read_text(work / "result" / n / "curve.csv") ==
            shpb_test::read_text(out / n / "curve.csv"));
    fs::remove_all(work / "parts/1-of-2");
    const auto missing = shpb_test::run_shpb(
        {"process", "--campaign", c.campaign.string(), "-o", work.string(), "--merge", "-q"});
    CHECK(missing.code == 2);
    CHECK(missing.err.find("missing part 1-of-2 (run 1)") != std::string::npos);
  }
  SECTION("Scenes on the command line are a campaign named by their folders") {
    const auto two = shpb_test::run_shpb({"process", (c.dir / "v10/scene.json").string(),
                                          (c.dir / "v20/scene.json").string(), "-o",
                                          (c.dir / "two").string(), "-q"});
    REQUIRE(two.code == 0);
    const auto rows2 = read_campaign_csv(c.dir / "two/campaign.csv");
    REQUIRE(rows2.size() == 2);
    CHECK(rows2[1].at("test") == "v20");
    CHECK(rows2[1].at("peak_stress_Pa") == rows[2].at("peak_stress_Pa"));
    // `shpb report` draws every test's curve on one figure.
    if (!shpb_test::have_matplotlib()) {
      SHPB_SKIP("python3 with matplotlib and numpy absent: report not checked");
    }
    const auto report = shpb_test::run_shpb({"report", (c.dir / "two").string()});
    INFO(report.err);
    CHECK(report.code == 0);
    CHECK(fs::exists(c.dir / "two/figures/campaign_stress_strain.png"));
  }
}

// The shards draw each test's measurement.uncertainty and the merge copies their folders, so
// --draws and --seed given to --merge changed nothing (exit 0, the shards' bands under the merge's
// options); a shard writes no campaign.csv, so --flow-stress-at given to it was dropped. Each is
// refused as `study --merge` refuses what its plan holds: one line, before anything is read.
TEST_CASE("process --merge refuses draws and --shard a flow stress: they cannot act there",
          "[app][process][campaign]") {
  const fs::path dir = shpb_test::scratch_dir("campaign_step_options");
  const std::string campaign = (kRoot / "experiments/measured-campaign.json").string();
  const std::string why_merge =
      ": not with --merge: the shards drew each test's measurement.uncertainty and the merge "
      "copies their tests (run the shards again to change the draws)\n";
  for (const auto& [option, value] :
       std::vector<std::pair<std::string, std::string>>{{"--draws", "20"}, {"--seed", "7"}}) {
    const auto r = shpb_test::run_shpb(
        {"process", "--campaign", campaign, "-o", dir.string(), "--merge", option, value, "-q"});
    CHECK(r.code == 2);
    CHECK(r.err == "error: " + option + why_merge);
  }
  const auto shard = shpb_test::run_shpb({"process", "--campaign", campaign, "-o", dir.string(),
                                          "--shard", "0/2", "--flow-stress-at", "0.02", "-q"});
  CHECK(shard.code == 2);
  CHECK(shard.err ==
        "error: --flow-stress-at: not with --shard: a shard writes no campaign.csv (give it to "
        "--merge, which writes it)\n");
  CHECK(fs::is_empty(dir));  // nothing written
  // Each option where it acts is taken: --threads with the merge (it draws nothing, and the
  // result does not depend on it) is not refused by this rule (the parts not made yet are).
  const auto threads = shpb_test::run_shpb(
      {"process", "--campaign", campaign, "-o", dir.string(), "--merge", "--threads", "1", "-q"});
  CHECK(threads.code == 2);
  CHECK(threads.err.find("no parts (K-of-N) found") != std::string::npos);
}

TEST_CASE("The three measured experiments as one campaign", "[app][process][campaign][data]") {
  const fs::path dir = shpb_test::scratch_dir("measured_campaign");
  const fs::path campaign = kRoot / "experiments/measured-campaign.json";
  // The LANL copper scene declares measurement.uncertainty: the campaign draws it as the one-test
  // command does (few draws: the bands' equality is checked, not their width).
  const std::vector<std::string> draws = {"--draws", "20", "--seed", "7", "-q"};
  std::vector<std::string> args = {"process", "--campaign",           campaign.string(),
                                   "-o",      (dir / "out").string(), "--flow-stress-at",
                                   "0.02"};
  args.insert(args.end(), draws.begin(), draws.end());
  const auto r = shpb_test::run_shpb(args);
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto rows = read_campaign_csv(dir / "out/campaign.csv");
  REQUIRE(rows.size() == 3);
  const std::vector<std::string> scenes = {"epoxy-resin-sample01", "lanl-cu-ofe-273k",
                                           "lanl-pmma13-mini-kolsky"};
  const std::vector<std::string> names = {"epoxy-resin", "cu-ofe-273k", "pmma-mini-kolsky"};
  for (std::size_t i = 0; i < 3; ++i) {
    const fs::path alone = dir / ("alone" + std::to_string(i));
    std::vector<std::string> one = {"process",
                                    (kRoot / "experiments" / scenes[i] / "scene.json").string(),
                                    "-o", alone.string()};
    one.insert(one.end(), draws.begin(), draws.end());
    REQUIRE(shpb_test::run_shpb(one).code == 0);
    check_row_equals_alone(rows[i], summary(alone));
    // The test's folder is the one-test command's, uncertainty bands included.
    const auto read = [](const fs::path& f) {
      std::ifstream in(f, std::ios::binary);
      return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    };
    const std::string curve = read(dir / "out" / names[i] / "curve.csv");
    CHECK(curve == read(alone / "curve.csv"));
    CHECK(summary(dir / "out" / names[i]).contains("uncertainty") ==
          summary(alone).contains("uncertainty"));
    if (names[i] == "cu-ofe-273k") {
      CHECK(curve.find("stress_3wave_p97.5_Pa") != std::string::npos);
      shpb_test::check_schema_columns(alone / "curve.csv", "curve");  // with the band columns
      CHECK(summary(dir / "out" / names[i])["uncertainty"]["draws"] == 20);
    }
  }
  fs::remove_all(dir);
}

}  // namespace tests_app_test_process_campaign
