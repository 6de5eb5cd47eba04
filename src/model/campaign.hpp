#pragma once
// A campaign file: several tests of one material, each a scene with its measurement. The same
// file drives `shpb process` over many tests and `shpb fit` (which reads its own keys, `material`,
// `free`, `nuisance`, `stages`, from `document` with the same file and JSON paths in messages).
//
//   { "name": "...", "notes": "...",
//     "tests": [ { "scene": "a/scene.json", "name": "1000 per s", "weight": 1 }, ... ],
//     "material": ..., "free": {...}, "nuisance": [...], "stages": [...] }
//
// Scenes are relative to the campaign file; test names are unique (they name output folders and
// CSV rows: names as bars' and gauges' are, and folder names — no path separator, not "." or "..",
// none of campaign_output_names()) and default to the scene's own name; weights are > 0 (default
// 1).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "model/fit_spec.hpp"

namespace shpb {

struct CampaignTest {
  std::string name;
  std::filesystem::path scene;  // resolved against the campaign file's folder
  double weight = 1;
  std::string json_path;  // "tests[2]": where the test is written, for messages
};

struct Campaign {
  std::filesystem::path file;
  std::string display;  // the file as the user named it
  std::string name;
  std::vector<CampaignTest> tests;
  nlohmann::json document;  // the whole file, for the readers of command-specific keys
  // The fit's keys (model/fit_spec.hpp), when the file has any: read and checked for every command.
  std::optional<FitSpec> fit;
};

// The files and folders a campaign's output folder holds besides its test folders
// (analysis/process_campaign.cpp): no test may be named as one of them.
const std::vector<std::string>& campaign_output_names();

// Reads and checks the file, the fit's keys included when it has any (a file is judged the same by
// `process --campaign` and `fit`): exit-2 InputErrors name the file and JSON path. Scenes must
// exist as regular files; they are read by the command that uses them.
Campaign read_campaign(const std::filesystem::path& file);

// The campaign of scene files named on the command line (`shpb process A.json B.json`): each
// test named as the scene is (its folder for "…/scene.json"), weight 1; names must be unique.
Campaign campaign_of_scenes(const std::vector<std::filesystem::path>& scenes);

}  // namespace shpb
