// `shpb process A.json B.json … -o DIR` or `shpb process --campaign FILE -o DIR`
// (docs/commands.md): every test processed as the one-test `process` does (process_into) into
// DIR/<test>/, and one campaign.csv of the figures that compare tests. With --shard K/N every N-th
// test goes into the part DIR/parts/K-of-N/ (written atomically, skipped if it exists); --merge
// checks that the parts hold every test once and writes DIR/result/ as the unsharded run writes
// DIR.
#include "analysis/process_campaign.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "analysis/process_outputs.hpp"
#include "analysis/processing.hpp"
#include "core/checked_write.hpp"
#include "core/csv_writer.hpp"
#include "core/error.hpp"
#include "core/file_digest.hpp"
#include "core/interpolation.hpp"
#include "core/options_check.hpp"
#include "core/output_folder.hpp"
#include "core/shards.hpp"
#include "model/campaign.hpp"
#include "model/scene.hpp"
#include "model/scene_inputs.hpp"
#include "output_schema.hpp"
#include "version.hpp"

namespace shpb {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

void say(const CampaignOptions& options, const std::string& line) {
  if (options.progress) options.progress(line);
}
std::string number_cell(const nlohmann::json& j) {
  return j.is_number() ? format_double(j.get<double>()) : std::string();
}

// Engineering 3-wave stress where the engineering strain of curve.csv first reaches `strain`
// (linear between the two samples around it); NaN if it never does.
double flow_stress(const std::vector<double>& strain, const std::vector<double>& stress,
                   double at) {
  for (std::size_t i = 1; i < strain.size(); ++i)
    if (strain[i - 1] < at && strain[i] >= at) {
      const double f = (at - strain[i - 1]) / (strain[i] - strain[i - 1]);
      return lerp(stress[i - 1], stress[i], f);
    }
  if (!strain.empty() && strain.front() == at) return stress.front();
  return std::numeric_limits<double>::quiet_NaN();
}

// The columns `names` of a CSV file written by shpb (header, then rows of finite numbers): read
// strictly, so a part's file cut short or garbled is refused, never taken for values that are not
// there.
std::vector<std::vector<double>> read_columns(const fs::path& csv,
                                              const std::vector<std::string>& names) {
  std::ifstream in(csv, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string remedy =
      ": not as shpb process writes it (cut short or edited?): process the "
      "test again";
  if (text.empty() || text.back() != '\n')
    throw input_error(csv.string(), "", "", "does not end with a line break" + remedy);
  std::stringstream lines(text);
  std::string line;
  std::getline(lines, line);
  std::vector<std::string> header;
  std::stringstream hs(line);
  for (std::string h; std::getline(hs, h, ',');) header.push_back(h);
  std::vector<std::size_t> index;
  for (const auto& n : names) {
    const auto it = std::find(header.begin(), header.end(), n);
    if (it == header.end()) throw input_error(csv.string(), "line 1", n, "column missing");
    index.push_back(static_cast<std::size_t>(it - header.begin()));
  }
  std::vector<std::vector<double>> columns(names.size());
  std::vector<double> row;
  for (std::size_t number = 2; std::getline(lines, line); ++number) {
    row.clear();
    std::size_t start = 0;
    for (;;) {
      const std::size_t comma = std::min(line.find(',', start), line.size());
      const std::string cell = line.substr(start, comma - start);
      char* end = nullptr;
      const double v = std::strtod(cell.c_str(), &end);
      // An empty field is an undefined number (a band where too few draws reach, docs/outputs.md):
      // refused only in the columns read.
      const bool read = std::find(index.begin(), index.end(), row.size()) != index.end();
      if ((cell.empty() && read) ||
          (!cell.empty() && (end != cell.c_str() + cell.size() || !std::isfinite(v))))
        throw input_error(
            csv.string(),
            "line " + std::to_string(number) + ", column " + std::to_string(row.size() + 1),
            "\"" + cell + "\"", "not a number" + remedy);
      row.push_back(v);
      if (comma == line.size()) break;
      start = comma + 1;
    }
    if (row.size() != header.size())
      throw input_error(csv.string(), "line " + std::to_string(number),
                        std::to_string(row.size()) + " cells",
                        std::to_string(header.size()) + " expected, as in the header" + remedy);
    for (std::size_t k = 0; k < names.size(); ++k) columns[k].push_back(row[index[k]]);
  }
  return columns;
}

std::string strain_label(double strain) { return format_double(strain); }

std::vector<std::string> campaign_header(const std::vector<double>& flow_strains) {
  namespace k = schema::campaign;  // the column names (src/core/output_schema.json)
  std::vector<std::string> h = {k::test, k::scene, k::plateau_strain_rate_1_s, k::peak_stress_Pa};
  for (double e : flow_strains) h.push_back("flow_stress_Pa_at_" + strain_label(e));
  for (const char* c : {k::time_to_equilibrium_s, k::striker_velocity_m_s,
                        k::striker_velocity_inferred_m_s, k::warnings})
    h.push_back(c);
  return h;
}

// One row of campaign.csv from a test's folder (its summary.json and curve.csv): the numbers
// exactly as the one-test `process` wrote them.
std::vector<std::string> campaign_row(const CampaignTest& test, const fs::path& folder,
                                      const std::vector<double>& flow_strains) {
  std::ifstream in(folder / "summary.json");
  const nlohmann::json s = nlohmann::json::parse(in);
  std::vector<std::string> cells = {quote_cell(test.name), quote_cell(test.scene.string()),
                                    number_cell(s.at("plateau_strain_rate_1_s")),
                                    number_cell(s.at("peak_stress_Pa"))};
  if (!flow_strains.empty()) {
    const auto c = read_columns(
        folder / schema::curve::kFile,
        {schema::curve::strain, schema::curve::stress_3wave_Pa, schema::curve::time_s});
    // Not quoted at a strain the specimen reaches in its ring-up (processing.hpp).
    const auto& first = s.at("equilibrium").value("first_s", nlohmann::json());
    const double ring_up = ring_up_strain(
        c[2], c[0], first.is_number() ? std::optional<double>(first.get<double>()) : std::nullopt);
    for (double e : flow_strains) {
      const double f =
          e <= ring_up ? std::numeric_limits<double>::quiet_NaN() : flow_stress(c[0], c[1], e);
      cells.push_back(format_field(f));
    }
  }
  cells.push_back(number_cell(s.at("time_to_equilibrium_s")));
  const auto& v = s.at("striker_velocity_m_s");
  cells.push_back(number_cell(v.at("scene")));
  cells.push_back(number_cell(v.at("inferred")));
  std::string warnings;
  for (const auto& w : s.at("warnings"))
    warnings += (warnings.empty() ? "" : " | ") + w.get<std::string>();
  cells.push_back(quote_cell(warnings));
  return cells;
}

// campaign.csv and summary.json of the campaign into `dir`, from the test folders `folders`.
void write_campaign(const Campaign& c, const std::vector<fs::path>& folders,
                    const std::vector<double>& flow_strains, const fs::path& dir) {
  CsvWriter csv(dir / schema::campaign::kFile, campaign_header(flow_strains));
  Json tests = Json::array();
  for (std::size_t i = 0; i < c.tests.size(); ++i) {
    try {
      csv.row(campaign_row(c.tests[i], folders[i], flow_strains));
    } catch (const nlohmann::json::exception& e) {  // a part's folder changed by hand
      throw input_error(
          (folders[i] / "summary.json").string(), "", "",
          std::string("not as shpb process writes it (") + e.what() + "): process the test again");
    }
    tests.push_back(Json{{"name", c.tests[i].name},
                         {"scene", c.tests[i].scene.string()},
                         {"folder", c.tests[i].name}});
  }
  csv.close();
  Json s;
  s["version"] = kVersion;
  s["command"] = "process";
  s["campaign"] = c.name;
  if (!c.display.empty()) s["campaign_file"] = c.display;
  s["tests"] = tests;
  s["flow_stress_strains"] = flow_strains;
  s["campaign_csv"] =
      "one row per test, from its folder's summary.json (plateau strain rate, headline peak "
      "stress, time to equilibrium, striker velocity as the scene gives it and as inferred, "
      "warnings joined by ' | ') and curve.csv (flow_stress_Pa_at_<e>: 3-wave engineering "
      "stress where the engineering strain first reaches e, linear between samples; empty if it "
      "never does, or reaches it in the ring-up, before the face forces first agree: "
      "equilibrium.first_s)";
  write_text_file(dir / "summary.json", s.dump(2) + "\n");
}

// Processes one test into `folder` as the one-test command does.
void process_test(const CampaignTest& test, const fs::path& folder, std::size_t i, std::size_t n,
                  const CampaignOptions& options) {
  say(options, "test " + std::to_string(i + 1) + "/" + std::to_string(n) + " \"" + test.name +
                   "\" (" + test.scene.string() + ")");
  const MonteCarloOptions monte_carlo = options.monte_carlo();
  process_into(test.scene, {}, folder, &monte_carlo, options.print_warnings);
}

// The list of tests a part was written for: its check against the merge's own list.
Json tests_json(const Campaign& c) {
  Json t = Json::array();
  for (const auto& test : c.tests)
    t.push_back(Json{{"name", test.name}, {"scene", fs::absolute(test.scene).lexically_normal()}});
  return t;
}

// --shard K/N: every N-th test into the part DIR/parts/K-of-N, with what it was computed from.
fs::path process_shard(const CampaignOptions& args, const Campaign& c,
                       const std::vector<fs::path>& inputs) {
  const std::size_t n = c.tests.size();
  const Shard shard = parse_shard("--shard", args.shard);
  const fs::path part = args.output / "parts" / part_name(shard);
  if (fs::exists(part)) {
    say(args, part.string() + " exists, shard skipped");
    return part;
  }
  OutputFolder out(part, "process", inputs);
  const auto runs = shard_runs(n, shard);
  for (std::size_t i : runs) process_test(c.tests[i], out.path() / c.tests[i].name, i, n, args);
  // What the part was computed from, and what it holds: both checked by the merge.
  std::vector<fs::path> written;
  for (std::size_t i : runs)
    for (const auto& e : fs::recursive_directory_iterator(out.path() / c.tests[i].name))
      if (e.is_regular_file()) written.push_back(e.path());
  std::sort(written.begin(), written.end());
  Json j{{"command", "process"},
         {"shard", args.shard},
         {"tests", tests_json(c)},
         {"inputs", input_digests(inputs)},
         {"files", input_digests(written, out.path())}};
  write_text_file(out.file("part.json"), j.dump(1) + "\n");
  out.commit();
  return out.final_path();
}

// --merge: the parts checked (every test once, inputs and files unchanged), DIR/result written.
fs::path merge_campaign(const CampaignOptions& args, const Campaign& c,
                        std::vector<fs::path> inputs) {
  const std::size_t n = c.tests.size();
  const fs::path parts_dir = args.output / "parts";
  const std::vector<Part> parts = find_parts(parts_dir, "");
  check_parts_cover(parts_dir, n, parts);
  const std::string expected = tests_json(c).dump();
  std::vector<fs::path> folders(n);
  for (const Part& p : parts) {
    const fs::path part_file = p.path / "part.json";
    std::ifstream in(part_file);
    nlohmann::json part;
    std::string tests;
    try {
      part = nlohmann::json::parse(in);
      tests = part.at("tests").dump();
    } catch (const std::exception&) {
      throw input_error(part_file.string(), "", "",
                        "missing or damaged: remove the part and run its shard again");
    }
    if (tests != expected)
      throw input_error(part_file.string(), "tests", "",
                        "a part of another list of tests: remove it and run its shard again");
    const std::string again = "remove the part and run its shard again";
    check_input_digests(part.contains("inputs") ? part["inputs"] : nlohmann::json(), part_file,
                        "inputs", "the shard ran", again);
    check_input_digests(part.contains("files") ? part["files"] : nlohmann::json(), part_file,
                        "files", "the shard wrote it", again, p.path);
    for (std::size_t i : shard_runs(n, p.shard)) folders[i] = p.path / c.tests[i].name;
  }
  inputs.push_back(parts_dir);
  OutputFolder out(args.output / "result", "process", inputs);
  for (std::size_t i = 0; i < n; ++i) {
    std::error_code ec;
    fs::copy(folders[i], out.path() / c.tests[i].name, fs::copy_options::recursive, ec);
    if (ec || !fs::exists(folders[i] / "summary.json"))
      throw input_error(folders[i].string(), "", "",
                        "the test's folder is missing or incomplete in its part: remove the part "
                        "and run its shard again");
  }
  write_campaign(c, folders, args.flow_strains, out.path());  // errors name the parts
  out.commit();
  say(args, "merged " + std::to_string(parts.size()) + " parts (" + std::to_string(n) +
                " tests) into " + out.final_path().string());
  return out.final_path();
}

Campaign campaign_of(const CampaignOptions& args) {
  return args.campaign ? read_campaign(*args.campaign) : campaign_of_scenes(args.scenes);
}

// Every scene read and checked before anything is processed or written: a bad scene is refused
// as the one-scene command refuses it (exit 2, its one line), not after the tests before it.
// The files they name (and the campaign file) are the run's inputs: no output folder may hold
// one, and a part records their digests for the merge.
std::vector<fs::path> campaign_inputs(const CampaignOptions& args, const Campaign& c) {
  std::vector<fs::path> inputs;
  if (args.campaign) inputs.push_back(*args.campaign);
  if (c.fit && !c.fit->material_file.empty()) inputs.push_back(c.fit->material_file);  // read too
  for (const auto& test : c.tests)
    for (const auto& f : scene_inputs(read_scene(test.scene))) inputs.push_back(f);
  return inputs;
}

}  // namespace

std::vector<fs::path> process_campaign_inputs(const CampaignOptions& options) {
  return campaign_inputs(options, campaign_of(options));
}

MonteCarloOptions CampaignOptions::monte_carlo() const {
  MonteCarloOptions o;
  o.draws = draws.value_or(o.draws);
  o.seed = seed.value_or(o.seed);
  o.threads = threads;
  return o;
}

bool CampaignOptions::IsValid(std::string* error) const {
  std::optional<InputError> e;
  const char* drawn = first_given({{draws.has_value(), "--draws"}, {seed.has_value(), "--seed"}});
  if (!campaign && scenes.empty())
    e = input_error("process", "", "", "a scene, several scenes or --campaign FILE is needed");
  else if (campaign && !scenes.empty())
    e = input_error(campaign->string(), "", "", "give scenes or --campaign, not both");
  else if (merge && !shard.empty())
    e = input_error("--merge", "", "", "the merge comes after the shards: not with --shard");
  else if (merge && drawn)
    e = not_with_step(drawn, "--merge",
                      "the shards drew each test's measurement.uncertainty and the merge copies "
                      "their tests (run the shards again to change the draws)");
  else if (!shard.empty() && !flow_strains.empty())
    e = not_with_step("--flow-stress-at", "--shard",
                      "a shard writes no campaign.csv (give it to --merge, which writes it)");
  else if (std::string why; !monte_carlo().IsValid(&why))
    e = InputError(why);
  for (double s : flow_strains)
    if (!e && !(s > 0 && s < 1))
      e = input_error("--flow-stress-at", "", format_double(s),
                      "engineering strains in (0, 1) expected, e.g. 0.02,0.05");
  if (e) *error = e->what();
  return !e;
}

fs::path process_campaign(const CampaignOptions& args) {
  require_valid(args);
  const Campaign c = campaign_of(args);
  const std::size_t n = c.tests.size();
  std::vector<fs::path> inputs = campaign_inputs(args, c);

  if (!args.shard.empty()) return process_shard(args, c, inputs);
  if (args.merge) return merge_campaign(args, c, std::move(inputs));
  OutputFolder out(args.output, "process", inputs);
  std::vector<fs::path> folders;
  for (std::size_t i = 0; i < n; ++i) {
    folders.push_back(out.path() / c.tests[i].name);
    process_test(c.tests[i], folders.back(), i, n, args);
  }
  write_campaign(c, folders, args.flow_strains, out.path());
  out.commit();
  say(args, std::to_string(n) + " tests; wrote " + out.final_path().string() + "/campaign.csv");
  return out.final_path();
}

}  // namespace shpb
