// The scene reader (docs/scene-format.md): JSON → Scene, every check at this boundary, each error
// naming the file, the JSON path, the value and the constraint (docs/commands.md).
#include <map>

#include "core/closest_match.hpp"
#include "core/csv_writer.hpp"  // format_double
#include "core/error.hpp"
#include "core/json_document.hpp"
#include "core/json_value.hpp"
#include "model/calibration.hpp"
#include "model/input_keys.hpp"
#include "model/input_limits.hpp"
#include "model/interface_name.hpp"
#include "model/material_reader.hpp"
#include "model/measurement_reader.hpp"
#include "model/plan_reader.hpp"
#include "model/scene.hpp"
#include "model/scene_validation.hpp"
#include "model/test_setup.hpp"

namespace shpb {

std::string gauge_position_problem(double position_m, double bar_length_m) {
  if (position_m >= 0 && position_m <= bar_length_m) return {};
  return "must lie on the bar: within [0, " + JsonValue::format(bar_length_m, Dimension::kLength) +
         "] from its left end";
}
namespace {

namespace fs = std::filesystem;

class SceneReader {
 public:
  explicit SceneReader(const fs::path& file)
      : file_(file), display_(file.string()), dir_(file.parent_path()) {}

  // The scene; a key refused in one of its objects is refused naming the others it belongs to (a
  // material file's own keys are that file's).
  Scene read(const nlohmann::json& j) {
    return read_placing_keys(display_, input_keys::kScenePlaces, [&] { return read_objects(j); });
  }

 private:
  Scene read_objects(const nlohmann::json& j) {
    const JsonValue root(j, display_, "");
    const auto o = root.object(input_keys::kScene);
    Scene scene;
    scene.file = file_;
    scene.name = default_name();
    if (auto v = o.get("name")) scene.name = v->string();
    if (auto v = o.get("notes")) v->string();
    if (auto v = o.get("materials")) read_materials(*v);

    const auto bars = o.require("bars", "the bars from left to right, at least two");
    const auto items = bars.array();
    if (items.size() < 2)
      throw bars.error_with_value(
          std::to_string(items.size()) + (items.size() == 1 ? " bar" : " bars"),
          "must list at least two bars (e.g. a striker and a bar)");
    for (std::size_t i = 0; i < items.size(); ++i)
      scene.bars.push_back(read_bar(items[i], i + 1 == items.size()));
    check_names(scene, items);

    if (auto v = o.get("specimen")) scene.specimen = bar_index(scene, *v);
    resolve_distances_to_specimen(scene, items);
    for (std::size_t i = 0; i < scene.bars.size(); ++i)
      if (!scene.bars[i].has_material && scene.specimen != i)
        throw JsonObject(items[i]).require(
            "material",
            "a name from materials, a file or an object (only the specimen may go "
            "without one, for `process`)");
    for (std::size_t i = 0; i < scene.bars.size(); ++i)
      if (const std::string what = radial_inertia_problem(scene, i); !what.empty())
        throw JsonObject(items[i]).require("inertia", "").error(what);
    if (auto v = o.get("contact")) scene.contact = read_contact(*v, scene);
    if (auto v = o.get("simulation")) scene.simulation = read_simulation(*v);
    if (auto v = o.get("contact")) check_face_friction(scene, *v);
    if (auto v = o.get("measurement")) {
      std::vector<std::string> gauges;
      for (const auto& b : scene.bars)
        for (const auto& g : b.gauges) gauges.push_back(g.name);
      std::vector<std::string> bar_names;
      for (const auto& b : scene.bars) bar_names.push_back(b.name);
      scene.measurement = read_measurement(*v, dir_, gauges, bar_names, scene.specimen);
    }
    for (const auto& entry : files_) scene.material_files.emplace_back(entry.first);
    // After the gauges are placed: the calibration replaces the nominal values for every command.
    if (auto v = o.get("calibration")) {
      const fs::path path = (dir_ / v->name()).lexically_normal();
      std::error_code ec;
      if (!fs::is_regular_file(path, ec))
        throw v->error("no such calibration file (looked for " + path.string() +
                       "; paths are relative to the scene)");
      apply_calibration(scene, read_calibration_file(path), path);
    }
    // Last, on the scene as every command takes it: the bounds `plan` may search within.
    if (auto v = o.get("plan")) scene.plan = read_plan_block(*v, scene, j, file_);
    return scene;
  }

  // "experiments/classic-al6061/scene.json" is named by its folder, other files by their stem.
  std::string default_name() const {
    const auto stem = file_.stem().string();
    if (stem == "scene") {
      const auto folder = fs::absolute(file_).parent_path().filename().string();
      if (!folder.empty()) return folder;
    }
    return stem;
  }

  void read_materials(const JsonValue& v) {
    if (!v.is_object()) throw v.error("expected an object of named materials { \"steel\": {...} }");
    for (const auto& [key, value] : v.json().items()) {
      const JsonValue m(value, display_, json_child_path(v.path(), key));
      materials_.emplace(key, read_material(m, key));
    }
  }

  MaterialSpec material(const JsonValue& v) {
    if (v.is_object()) return read_material(v, "inline");
    if (!v.is_string())
      throw v.error("expected a name from materials, a path to a material .json file or an object");
    const std::string s = v.string();
    if (auto it = materials_.find(s); it != materials_.end()) return it->second;
    const bool looks_like_path =
        s.find('/') != std::string::npos || (s.size() > 5 && s.substr(s.size() - 5) == ".json");
    if (!looks_like_path) {
      std::vector<std::string> names;
      for (const auto& [name, m] : materials_) names.push_back(name);
      const auto near = closest_match(s, names);
      throw v.error(near ? "no such material in materials; did you mean \"" + *near + "\"?"
                         : "no such material in materials, and not a path to a .json file");
    }
    const fs::path path = (dir_ / s).lexically_normal();
    std::error_code ec;
    if (!fs::is_regular_file(path, ec))
      throw v.error("no such material file (looked for " + path.string() +
                    "; paths are relative to the scene)");
    auto [it, inserted] = files_.try_emplace(path.string());
    if (inserted) it->second = read_material_file(path, path.string());
    return it->second;
  }

  BarSpec read_bar(const JsonValue& v, bool last) {
    const auto o = v.object(input_keys::kBar);
    BarSpec b;
    b.name = o.require("name", "a unique name such as \"incident\"").name();
    // `process` needs no specimen material (geometry is enough): checked once the specimen is
    // known.
    if (auto m = o.get("material"))
      b.material = material(*m);
    else
      b.has_material = false;
    b.length_m = o.require("length", "e.g. \"2 m\"").positive_quantity(Dimension::kLength);
    const auto diameter = o.get("diameter");
    const auto area = o.get("area");
    if (diameter && area) throw area->error("give either diameter or area, not both");
    if (area) {
      b.area_m2 = area->positive_quantity(Dimension::kArea);
      b.area_given = true;
      b.diameter_m = std::sqrt(4 * b.area_m2 / M_PI);  // equivalent circular diameter
    } else {
      b.diameter_m = o.require("diameter", "e.g. \"19.05 mm\" (or give area)")
                         .positive_quantity(Dimension::kLength);
      b.area_m2 = M_PI * b.diameter_m * b.diameter_m / 4;
    }
    if (auto x = o.get("velocity")) b.velocity_m_s = x->quantity(Dimension::kVelocity);
    if (auto x = o.get("elements")) b.elements = static_cast<int>(x->integer(1, kMaxElements));
    if (auto x = o.get("gap")) {
      if (last) throw x->error(kLastBarGap);
      b.gap_m = x->non_negative_quantity(Dimension::kLength);
    }
    if (auto x = o.get("notes")) x->string();
    if (auto x = o.get("inertia")) b.inertia = x->boolean();  // radial_inertia_problem, once placed
    if (auto x = o.get("gauges")) {
      for (const auto& g : x->array()) {
        const auto go = g.object(input_keys::kGauge);
        GaugeSpec gauge;
        gauge.name = go.require("name", "a unique gauge name").name();
        const auto to_specimen = go.get("distance_to_specimen");
        if (to_specimen && go.get("position"))
          throw to_specimen->error("give either position or distance_to_specimen, not both");
        const auto pos = to_specimen ? *to_specimen
                                     : go.require("position",
                                                  "distance from the bar's left end, e.g. \"1 m\" "
                                                  "(or distance_to_specimen)");
        gauge.position_m = pos.quantity(Dimension::kLength);
        if (to_specimen)  // on the bar once the specimen is known (resolve_distances_to_specimen)
          gauge.distance_to_specimen_m = gauge.position_m;
        else if (const std::string what = gauge_position_problem(gauge.position_m, b.length_m);
                 !what.empty())
          throw pos.error_with_value(JsonValue::format(gauge.position_m, Dimension::kLength), what);
        b.gauges.push_back(gauge);
      }
    }
    return b;
  }

  // `distance_to_specimen` is the distance the pulse travels in the bars to the specimen face it
  // loads (model/test_setup.hpp: distance_to_specimen_m, whose inverse this is).
  static void resolve_distances_to_specimen(Scene& scene, const std::vector<JsonValue>& items) {
    for (std::size_t i = 0; i < scene.bars.size(); ++i)
      for (std::size_t k = 0; k < scene.bars[i].gauges.size(); ++k) {
        GaugeSpec& g = scene.bars[i].gauges[k];
        if (!g.distance_to_specimen_m) continue;
        const auto given = JsonObject(JsonObject(items[i]).get("gauges")->array()[k])
                               .require("distance_to_specimen", "");
        if (!scene.specimen || *scene.specimen == i)
          throw given.error(scene.specimen
                                ? "a gauge on the specimen has no distance to it; give position"
                                : "needs \"specimen\" (the distance is to its face); give "
                                  "position from the bar's left end instead");
        const double d = *g.distance_to_specimen_m;
        const GaugePlacement place = place_gauge_at_distance(scene, i, d);
        if (!place.problem.empty())
          throw given.error_with_value(JsonValue::format(d, Dimension::kLength), place.problem);
        g.position_m = place.position_m;
      }
  }

  // Bar names and gauge names are unique (they name CSV columns); "time_s" is taken.
  void check_names(const Scene& scene, const std::vector<JsonValue>& items) const {
    std::map<std::string, std::string> bars, gauges;  // name → path of first use
    for (std::size_t i = 0; i < scene.bars.size(); ++i) {
      const auto bar = JsonObject(items[i]);
      const auto name_path = json_child_path(items[i].path(), "name");
      if (auto [it, ok] = bars.emplace(scene.bars[i].name, name_path); !ok)
        throw bar.require("name", "").error("duplicate bar name (also at " + it->second + ")");
      const auto gauge_items = bar.get("gauges");
      for (std::size_t k = 0; k < scene.bars[i].gauges.size(); ++k) {
        const auto g = JsonObject(gauge_items->array()[k]).require("name", "");
        const auto& name = scene.bars[i].gauges[k].name;
        if (name == "time_s") throw g.error("\"time_s\" is the time column; choose another name");
        if (auto [it, ok] = gauges.emplace(name, g.path()); !ok)
          throw g.error("duplicate gauge name (also at " + it->second + ")");
      }
    }
    // Interface columns are "<left>-<right>_...": bars "a-b","c" and "a","b-c" would share them.
    std::map<std::string, std::size_t> interfaces;  // interface name → left bar index
    for (std::size_t i = 0; i + 1 < scene.bars.size(); ++i)
      if (auto [it, ok] = interfaces.emplace(interface_name(scene, i), i); !ok)
        throw JsonObject(items[i + 1])
            .require("name", "")
            .error("the interface " + it->first + " (bars " + std::to_string(i) + " and " +
                   std::to_string(i + 1) + ") has the name of the interface between bars " +
                   std::to_string(it->second) + " and " + std::to_string(it->second + 1) +
                   " (interfaces.csv columns would collide); rename a bar");
  }

  static std::vector<std::string> bar_names(const Scene& scene) {
    std::vector<std::string> names;
    for (const auto& b : scene.bars) names.push_back(b.name);
    return names;
  }

  static std::size_t bar_index(const Scene& scene, const JsonValue& v) {
    const std::string s = v.string();
    for (std::size_t i = 0; i < scene.bars.size(); ++i)
      if (scene.bars[i].name == s) return i;
    throw v.error("no bar of that name; " + suggestion_text(s, bar_names(scene)));
  }

  static ContactMethod contact_method(const JsonValue& v) {
    return enum_from(v, kContactMethodNames);
  }

  static PenaltyParams read_penalty(const JsonObject& o) {
    PenaltyParams p;
    if (auto x = o.get("stiffness_factor"))
      p.stiffness_factor = x->positive_quantity(Dimension::kDimensionless);
    if (auto x = o.get("stiffness")) p.stiffness_N_m = x->positive_quantity(Dimension::kStiffness);
    if (auto x = o.get("rise_time")) {
      p.rise_time_s = x->positive_quantity(Dimension::kTime);
      if (p.stiffness_factor || p.stiffness_N_m)
        throw x->error("give one of stiffness_factor, stiffness and rise_time, not several");
    }
    if (p.stiffness_factor && p.stiffness_N_m)
      throw o.get("stiffness")
          ->error("give one of stiffness_factor, stiffness and rise_time, not several");
    if (auto x = o.get("mass_ratio"))
      p.mass_ratio = x->positive_quantity(Dimension::kDimensionless);
    return p;
  }

  // Coulomb coefficient of the specimen faces; the closed forms of docs/methods.md §8 are
  // first-order in μ, and lubricated to dry metal faces span about 0.02–0.3.
  static double read_friction(const JsonValue& v) {
    return v.quantity_in(Dimension::kDimensionless, 0, 1, false, true);
  }

  static ContactSpec read_contact(const JsonValue& v, const Scene& scene) {
    const auto o = v.object(input_keys::kContact);
    ContactSpec c;
    if (auto m = o.get("method")) c.method = contact_method(*m);
    if (auto f = o.get("friction")) c.friction = read_friction(*f);
    c.penalty = read_penalty(o);
    if (auto list = o.get("interfaces")) {
      for (const auto& item : list->array()) {
        const auto io = item.object(input_keys::kInterface);
        const auto between =
            io.require("between", "two neighbouring bars, e.g. [\"striker\", \"incident\"]");
        const auto pair = between.array();
        if (pair.size() != 2) throw between.error("expected two bar names");
        const std::size_t a = bar_index(scene, pair[0]), b = bar_index(scene, pair[1]);
        if (a + 1 != b && b + 1 != a)
          throw between.error("the two bars must be neighbours in the chain");
        InterfaceOverride ov;
        ov.left_bar = std::min(a, b);
        for (const auto& other : c.interfaces)
          if (other.left_bar == ov.left_bar)
            throw between.error("this interface is already listed");
        if (auto m = io.get("method")) ov.method = contact_method(*m);
        ov.penalty = read_penalty(io);
        if (auto f = io.get("friction")) ov.friction = read_friction(*f);
        c.interfaces.push_back(ov);
      }
    }
    return c;
  }

  // Face friction is the Dharan–Hauser factor of faces that slide over a flowing bar of its
  // current diameter and length (docs/methods.md §8.2): a bonded (glued) face does not slide, and
  // small kinematics keeps the bar's original section. Checked where it acts: the faces of the
  // specimen or a pulse shaper with a material law.
  static void check_face_friction(const Scene& scene, const JsonValue& contact) {
    const auto o = JsonObject(contact);
    for (std::size_t k = 0; k + 1 < scene.bars.size(); ++k) {
      if (interface_friction(scene.contact, k) <= 0) continue;
      bool acts = false;
      for (const std::size_t b : {k, k + 1}) {
        const BarSpec& bar = scene.bars[b];
        acts |= (scene.specimen == b || squeezed_bar(b, scene.bars.size())) && bar.has_material &&
                !bar.material.is_elastic();
      }
      if (!acts) continue;
      // The value that gives this face its μ: its own override, else contact.friction.
      std::optional<JsonValue> given = o.get("friction");
      for (std::size_t j = 0; j < scene.contact.interfaces.size(); ++j)
        if (scene.contact.interfaces[j].left_bar == k && scene.contact.interfaces[j].friction)
          given = JsonObject(o.get("interfaces")->array()[j]).get("friction");
      const std::string face = scene.bars[k].name + "|" + scene.bars[k + 1].name;
      if (interface_method(scene.contact, k) == ContactMethod::kBonded)
        throw given->error("the face " + face +
                           " is bonded and does not slide; face friction (docs/methods.md §8.2) "
                           "acts on sliding faces: give it 0 there");
      if (!scene.simulation.finite_strain)
        throw given->error("face friction on " + face +
                           " follows the current diameter and length of the squeezed bar "
                           "(docs/methods.md §8.2), which \"kinematics\": \"small\" does not "
                           "model; use finite kinematics (the default)");
    }
  }

  static SimulationSpec read_simulation(const JsonValue& v) {
    const auto o = v.object(input_keys::kSimulation);
    SimulationSpec s;
    if (auto x = o.get("duration")) s.duration_s = x->positive_quantity(Dimension::kTime);
    if (auto x = o.get("sample_rate"))
      s.sample_rate_Hz = x->positive_quantity(Dimension::kFrequency);
    if (auto x = o.get("stepping")) s.stepping = enum_from(*x, kSteppingNames);
    if (auto x = o.get("courant")) {
      s.courant = x->quantity(Dimension::kDimensionless);
      if (const std::string what = courant_problem(*s.courant); !what.empty())
        throw x->error_with_value(format_double(*s.courant), what);
    }
    if (auto x = o.get("kinematics")) s.finite_strain = enum_from(*x, kKinematicsNames);
    // An engineering strain in (0, 1): the step shrinks with the shortest element.
    if (auto x = o.get("max_strain"))
      s.max_strain = x->quantity_in(Dimension::kDimensionless, 0, 0.95, true, false);
    // A gauge error ("1 %"), checked with the command line's in validate_scene().
    if (auto x = o.get("tolerance")) {
      try {
        s.tolerance = x->quantity(Dimension::kDimensionless);
      } catch (const InputError&) {
        throw x->error(tolerance_problem(0));  // "abc", "1 mm": say what is expected
      }
      if (const std::string what = tolerance_problem(*s.tolerance); !what.empty())
        throw x->error(what);
    }
    return s;
  }

  fs::path file_;
  std::string display_;
  fs::path dir_;
  std::map<std::string, MaterialSpec> materials_;
  std::map<std::string, MaterialSpec> files_;  // material files already read, by path
};

}  // namespace

Scene read_scene(const std::filesystem::path& file) {
  return read_scene_text(read_json_file_text(file, file.string()), file);
}

Scene read_scene_text(const std::string& text, const std::filesystem::path& file) {
  Scene scene = SceneReader(file).read(parse_json_object(text, file.string()));
  scene.source_text = text;
  return scene;
}

std::string radial_inertia_problem(const Scene& scene, std::size_t i) {
  const BarSpec& b = scene.bars[i];
  if (!b.inertia) return {};
  if (b.material.is_elastic())
    return "radial inertia applies to a flowing specimen: give the bar a material law (bilinear, "
           "johnson-cook or viscoelastic)";
  // The closed form of a Kolsky specimen (model/specimen_response.hpp).
  if (scene.specimen != i && !squeezed_bar(i, scene.bars.size()))
    return "radial inertia is modelled for a bar squeezed between two others (the specimen or a "
           "pulse shaper)";
  return {};
}

// The gauged bars nearest to the specimen on either side: the incident and transmitter bars.
std::optional<std::size_t> Scene::incident_bar() const {
  if (!specimen) return std::nullopt;
  for (std::size_t i = *specimen; i-- > 0;)
    if (!bars[i].gauges.empty()) return i;
  return std::nullopt;
}

std::optional<std::size_t> Scene::transmitter_bar() const {
  if (!specimen) return std::nullopt;
  for (std::size_t i = *specimen + 1; i < bars.size(); ++i)
    if (!bars[i].gauges.empty()) return i;
  return std::nullopt;
}

std::string_view to_string(ContactMethod m) { return enum_name(kContactMethodNames, m); }
std::string_view to_string(Stepping s) { return enum_name(kSteppingNames, s); }
std::string_view to_string(MaterialModel m) { return enum_name(kMaterialModelNames, m); }
std::optional<ContactMethod> contact_method_from_string(std::string_view s) {
  return enum_value(kContactMethodNames, s);
}
std::optional<Stepping> stepping_from_string(std::string_view s) {
  return enum_value(kSteppingNames, s);
}
}  // namespace shpb
