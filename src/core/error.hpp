#pragma once
// Errors that cross the program's boundary. Every message starts with "error:" when printed by
// main, and names the file, the place (JSON path or CSV line/column), the value and the constraint
// (docs/commands.md): "scene.json: bars[2].length: -0.005 m: must be > 0".
#include <cstddef>
#include <stdexcept>
#include <string>

namespace shpb {

// Bad input or usage: exit code 2, nothing written.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A numerical failure the program detected (instability, NaN): exit code 3.
class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An output could not be written (disk full, I/O error, permissions changed during the run):
// exit code 3, the message names the file and the system's reason; the previous result is kept.
class WriteError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The run was interrupted (SIGINT/SIGTERM): exit code 130, previous results left intact.
class Interrupted : public std::runtime_error {
 public:
  Interrupted() : std::runtime_error("interrupted") {}
};

// A place or value quoted from an input is cut to this many bytes: a field or header of
// megabytes (a line without separators) would otherwise be the whole message.
inline constexpr std::size_t kMaxQuoted = 200;

// `s` cut to kMaxQuoted bytes (at a UTF-8 character's start), saying how long it was.
inline std::string shorten_quoted(const std::string& s) {
  if (s.size() <= kMaxQuoted) return s;
  std::size_t cut = kMaxQuoted;
  while (cut > 0 && (static_cast<unsigned char>(s[cut]) & 0xC0) == 0x80) --cut;
  return s.substr(0, cut) + "... (" + std::to_string(s.size()) + " bytes)";
}

// "<file>: <where>: <value>: <constraint>", the one shape of every input error.
inline InputError input_error(const std::string& file, const std::string& where,
                              const std::string& value, const std::string& constraint) {
  std::string msg = file;
  if (!where.empty()) msg += ": " + shorten_quoted(where);
  if (!value.empty()) msg += ": " + shorten_quoted(value);
  msg += ": " + constraint;
  return InputError(msg);
}

}  // namespace shpb
