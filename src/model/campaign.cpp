#include "model/campaign.hpp"

#include <set>

#include "core/error.hpp"
#include "core/json_document.hpp"
#include "core/json_value.hpp"
#include "core/output_folder.hpp"
#include "model/input_keys.hpp"

namespace shpb {
namespace fs = std::filesystem;

const std::vector<std::string>& campaign_output_names() {
  static const std::vector<std::string> names = {"campaign.csv",  "summary.json", "part.json",
                                                 "parts",         "result",       kOutputMarker,
                                                 kTemporaryMarker};
  return names;
}

namespace {
// "experiments/x/scene.json" is named by its folder, other files by their stem (as scenes are).
std::string name_of_scene(const fs::path& scene) {
  if (scene.stem() == "scene") {
    const auto folder = fs::absolute(scene).parent_path().filename().string();
    if (!folder.empty()) return folder;
  }
  return scene.stem().string();
}
Campaign read_campaign_objects(const fs::path& file) {
  Campaign c;
  c.file = file;
  c.display = file.string();
  c.document = read_json_object_file(file, c.display);
  const JsonValue root(c.document, c.display, "");
  const auto o = root.object(input_keys::kCampaign);
  c.name = file.stem().string();
  if (auto v = o.get("name")) c.name = v->name();
  if (auto v = o.get("notes")) v->string();

  const auto tests = o.require("tests", "the campaign's tests: [{\"scene\": FILE, \"name\": ...}]");
  const auto items = tests.array();
  if (items.empty()) throw tests.error("must list at least one test");
  std::set<std::string> names;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const auto t = items[i].object(input_keys::kCampaignTest);
    CampaignTest test;
    test.json_path = items[i].path();
    const auto scene = t.require("scene", "the test's scene file, relative to the campaign file");
    const fs::path written = scene.string();
    if (written.empty()) throw scene.error("expected a scene file name");
    test.scene = written.is_absolute() ? written : file.parent_path() / written;
    std::error_code ec;
    // The path as JSON text: a line break or control character in it stays on the one line.
    if (!fs::exists(test.scene, ec))
      throw scene.error("no such file (" + json_quoted(test.scene.string()) + ")");
    if (!fs::is_regular_file(test.scene, ec)) throw scene.error("is not a regular file");
    test.name = name_of_scene(test.scene);
    if (auto v = t.get("name")) {
      test.name = v->file_name(campaign_output_names());
    } else if (const std::string why = file_name_problem(test.name, campaign_output_names());
               !why.empty()) {
      throw scene.error_with_value(json_quoted(written.string()),
                                   "names the test " + json_quoted(test.name) + ", which " + why +
                                       " (give the test a \"name\")");
    }
    if (!names.insert(test.name).second)
      throw(t.get("name") ? *t.get("name") : scene)
          .error_with_value("\"" + test.name + "\"",
                            "test names must be unique (they name output folders and rows)");
    if (auto v = t.get("weight")) test.weight = v->positive_quantity(Dimension::kDimensionless);
    c.tests.push_back(std::move(test));
  }
  for (const auto& key : input_keys::kCampaignFit)
    if (!c.fit && o.has(key)) c.fit = read_fit_spec(c);
  return c;
}

}  // namespace

// A key refused in one object of the file names the other it belongs to ("weight" at the top
// level: a key of tests[]).
Campaign read_campaign(const fs::path& file) {
  return read_placing_keys(file.string(), input_keys::kCampaignPlaces,
                           [&] { return read_campaign_objects(file); });
}

Campaign campaign_of_scenes(const std::vector<fs::path>& scenes) {
  Campaign c;
  c.name = "campaign";
  std::set<std::string> names;
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    CampaignTest test;
    test.scene = scenes[i];
    test.name = name_of_scene(scenes[i]);
    test.json_path = "scene " + std::to_string(i + 1);
    if (const std::string why = file_name_problem(test.name, campaign_output_names()); !why.empty())
      throw input_error(scenes[i].string(), "", "\"" + test.name + "\"",
                        "names the test, which " + why +
                            " (use a campaign file with a name per "
                            "test)");
    if (!names.insert(test.name).second)
      throw input_error(scenes[i].string(), "", "\"" + test.name + "\"",
                        "two scenes named alike (test names name output folders and rows): "
                        "use a campaign file with a name per test");
    c.tests.push_back(std::move(test));
  }
  return c;
}

}  // namespace shpb
