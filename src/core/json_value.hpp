#pragma once
// A JSON value together with where it came from (file and JSON path such as `bars[2].length`), so
// that every check can report "<file>: <path>: <value>: <constraint>" (docs/commands.md). Objects
// are opened with the list of keys they allow: an unknown key is an error at once, with a "did you
// mean" when it is close to an allowed one.
#include <cstdint>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/closest_match.hpp"
#include "core/enum_names.hpp"
#include "core/error.hpp"
#include "core/units.hpp"

namespace shpb {

class JsonObject;

// The refusal of a key an object does not allow (JsonValue::object), "did you mean" among that
// object's keys; a reader that knows the file's other objects says where the key belongs
// (placed(): one rule, core/closest_match.hpp key_suggestion_text).
class UnknownKeyError : public InputError {
 public:
  UnknownKeyError(std::string file, std::string path, std::string key,
                  std::vector<std::string> allowed);
  const std::string& file() const { return file_; }
  // The same refusal, the key looked for in the objects of `schema` too.
  InputError placed(const std::vector<KeyPlace>& schema) const;

 private:
  std::string file_, path_, key_;
  std::vector<std::string> allowed_;
};

// read(), a key it refuses in `file` said with where it belongs among `schema` (the objects of
// that file: UnknownKeyError::placed); a refusal in another file (a material file a scene names)
// as it is.
template <class Read>
auto read_placing_keys(const std::string& file, const std::vector<KeyPlace>& schema, Read&& read) {
  try {
    return read();
  } catch (const UnknownKeyError& e) {
    if (e.file() != file) throw;
    throw e.placed(schema);
  }
}

class JsonValue {
 public:
  JsonValue(const nlohmann::json& json, std::string file, std::string path)
      : json_(&json), file_(std::move(file)), path_(std::move(path)) {}

  const nlohmann::json& json() const { return *json_; }
  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  std::string text() const;  // the value as written (compact, shortened)

  // "<file>: <path>: <value>: <constraint>"; the value defaults to text().
  InputError error(const std::string& constraint) const;
  InputError error_with_value(const std::string& value, const std::string& constraint) const;

  bool is_string() const { return json_->is_string(); }
  bool is_number() const { return json_->is_number(); }
  bool is_object() const { return json_->is_object(); }

  // A finite number (SI) or a string "<number> <unit>" of dimension `d`.
  double quantity(Dimension d) const;
  // Constrained quantities; messages show the SI value with its unit ("-0.005 m: must be > 0").
  double positive_quantity(Dimension d) const;
  double non_negative_quantity(Dimension d) const;
  double quantity_in(Dimension d, double lo, double hi, bool lo_open, bool hi_open) const;

  std::int64_t integer(std::int64_t lo, std::int64_t hi) const;  // a whole number in [lo, hi]
  bool boolean() const;
  std::string string() const;  // any string
  std::string name() const;    // a non-empty string usable as a CSV column name
  // A column's name in a file the user brings ("DMS1 A (bar 1,0m)"): found there, never written
  // as a column, so a comma or a quote is allowed; see header_name_problem().
  std::string header_name() const;
  // A name() that also names a file or folder: see file_name_problem().
  std::string file_name(const std::vector<std::string>& reserved) const;
  std::vector<JsonValue> array() const;  // the elements of an array
  JsonObject object(const std::vector<std::string>& allowed_keys) const;

  // Formats an SI value of dimension d for messages: "-0.005 m".
  static std::string format(double value_si, Dimension d);

 private:
  const nlohmann::json* json_;
  std::string file_;
  std::string path_;
};

// `s` as a JSON string, quotes included: a line break, a control character or a byte that is not
// UTF-8 in a path or key the user gave stays within a message's one line.
std::string json_quoted(std::string_view s);

// Why `s` is not a name of a column in a file the user brings, or "": not empty, no line break or
// control character, no white space at either end (a header's fields are read trimmed).
std::string header_name_problem(std::string_view s);
// Why `s` is not a name (bars, gauges, tests: they become CSV columns and rows), or "": a
// header_name_problem()-free name with no comma or quote.
std::string name_problem(std::string_view s);
// Why `s` is not a name that also names a file or folder (a campaign's test folders), or "": a
// name, no path separator ('/', '\\'), not "." or "..", and none of `reserved` (the other files
// of the same folder), compared ignoring case as some file systems do.
std::string file_name_problem(std::string_view s, const std::vector<std::string>& reserved);

class JsonObject {
 public:
  explicit JsonObject(JsonValue value) : value_(std::move(value)) {}

  const JsonValue& value() const { return value_; }
  bool has(std::string_view key) const { return value_.json().contains(key); }
  std::optional<JsonValue> get(std::string_view key) const;
  // Throws "<path>.<key>: (missing): required — <what>" when absent.
  JsonValue require(std::string_view key, const std::string& what) const;

 private:
  JsonValue value_;
};

// The value a table of names (core/enum_names.hpp) gives the string `v`; else v's error, offering
// the closest name.
template <typename Enum, std::size_t N>
Enum enum_from(const JsonValue& v, const EnumName<Enum> (&table)[N]) {
  const std::string s = v.string();
  if (const auto e = enum_value(table, s)) return *e;
  throw v.error(suggestion_text(s, enum_names(table)));
}

// `parent.key` or `parent["odd key"]`, `parent[3]`.
std::string json_child_path(const std::string& parent, std::string_view key);
std::string json_element_path(const std::string& parent, std::size_t index);

}  // namespace shpb
