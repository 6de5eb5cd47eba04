#include <catch2/catch.hpp>
#include <string>

#include "core/closest_match.hpp"
#include "core/json_document.hpp"
#include "core/json_value.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_core_test_json_value {

using namespace shpb;

namespace {
std::string message_of(const std::string& text) {
  try {
    parse_json_object(text, "f.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}
}  // namespace

TEST_CASE("Did you mean: close misspellings are matched, unrelated words are not", "[core][json]") {
  const std::vector<std::string> keys = {"length", "diameter", "area", "velocity", "gauges"};
  CHECK(closest_match("lenght", keys) == "length");      // transposition
  CHECK(closest_match("Diameter", keys) == "diameter");  // case
  CHECK(closest_match("velocty", keys) == "velocity");   // missing letter
  CHECK(closest_match("gauge", keys) == "gauges");
  CHECK_FALSE(closest_match("temperature", keys));
  CHECK(closest_match("youngs-modulus", {"youngs_modulus"}) == "youngs_modulus");  // '-' as '_'
  CHECK(suggestion_text("colour", {"red", "green"}) == "expected one of: red, green");
}

TEST_CASE("JSON paths name keys and array elements as a reader would write them", "[core][json]") {
  CHECK(json_child_path("", "bars") == "bars");
  CHECK(json_element_path("bars", 2) == "bars[2]");
  CHECK(json_child_path("bars[2]", "length") == "bars[2].length");
  CHECK(json_child_path("materials", "steel-c350") == "materials.steel-c350");
  CHECK(json_child_path("materials", "steel c350") == "materials[\"steel c350\"]");
}

TEST_CASE("Constrained values report the SI value and the constraint", "[core][json]") {
  const nlohmann::json j = nlohmann::json::parse(R"({"a": "-5 mm", "b": 0.7, "c": 2.5})");
  const JsonObject o = JsonValue(j, "f.json", "").object({"a", "b", "c"});
  CHECK_THROWS_WITH(o.get("a")->positive_quantity(Dimension::kLength),
                    "f.json: a: -0.005 m: must be > 0");
  CHECK_THROWS_WITH(o.get("b")->quantity_in(Dimension::kDimensionless, -1, 0.5, true, true),
                    "f.json: b: 0.7: must be in (-1, 0.5)");
  CHECK_THROWS_WITH(o.get("c")->integer(1, 10),
                    "f.json: c: 2.5: expected a whole number in [1, 10]");
  CHECK_THROWS_WITH(o.require("d", "e.g. 3"), "f.json: d: (missing): required: e.g. 3");
  CHECK_THROWS_WITH(JsonValue(j, "f.json", "").object({"a", "b"}),
                    "f.json: c: unknown key: expected one of: a, b");
}

TEST_CASE("Documents that are not one JSON object are refused with their place", "[core][json]") {
  CHECK(message_of("") == "f.json: empty file: expected a JSON object");
  CHECK(message_of("[1]") == "f.json: (top level): [1]: expected a JSON object { ... }");
  CHECK(message_of("{\"a\": 1, \"b\": {\"c\": [1, {\"d\": 1, \"d\": 2}]}}") ==
        "f.json: b.c[1].d: duplicate key (each key may appear once)");
  // A key that is not a plain name is quoted, as json_child_path spells it for every other message.
  CHECK(message_of("{\"bar one\": {\"\": {\"x\": 1, \"x\": 2}}}") ==
        "f.json: [\"bar one\"][\"\"].x: duplicate key (each key may appear once)");
  CHECK(message_of("{\"a\": [1, 2e999]}") ==
        "f.json: a[1]: number overflow parsing '2e999': expected a number within the range of a "
        "double");
  CHECK(message_of("{\n  \"a\": 1,\n}").rfind("f.json: line 3, column 1: ", 0) == 0);
}

}  // namespace tests_core_test_json_value
