#pragma once
// The units a signal file's header names for its columns ("Time (ms)", "CH1 [mV]", a unit row's
// "(ms)"), read as a scene's quantities are and checked against the units the scene reads the
// columns in (core/signal_csv.cpp).
#include <cctype>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#include "core/signal_spec.hpp"
#include "core/signal_text.hpp"

namespace shpb {

// The unit a header field names, as scopes and spreadsheets write it: "Time (ms)", "Zeit [us]",
// "CH1 (mV)", a unit row's "(ms)", "second", "Volt" or "µm/m", or after the last of `cuts`
// ("Time/s", "time_s"); nothing for a name without one ("Time", "Sample"). `value` reads a unit's
// name (µ written u) as the kind of unit sought, or gives nothing; the unit is returned as written
// with that value.
template <class Read, class Value = typename std::invoke_result_t<Read, std::string>::value_type>
std::optional<std::pair<std::string, Value>> header_unit(std::string_view field, Read value,
                                                         std::string_view cuts) {
  const auto read = [&](std::string_view unit) -> std::optional<std::pair<std::string, Value>> {
    while (!unit.empty() && unit.front() == ' ') unit.remove_prefix(1);
    while (!unit.empty() && unit.back() == ' ') unit.remove_suffix(1);
    std::string name(unit);
    // A unit starts with a letter, µ (UTF-8 C2 B5, Greek μ CE BC, Latin-1 B5) or is "%": not a
    // number.
    const auto first = static_cast<unsigned char>(name.empty() ? '0' : name.front());
    if (!std::isalpha(first) && first != 0xC2 && first != 0xCE && first != 0xB5 && name != "%")
      return std::nullopt;
    for (const std::string_view micro : {"\xC2\xB5", "\xCE\xBC", "\xB5"})
      if (name.rfind(micro, 0) == 0) name = "u" + name.substr(micro.size());
    if (const auto v = value(name)) return std::make_pair(std::string(unit), *v);
    return std::nullopt;
  };
  if (const auto open = field.find_last_of("(["); open != std::string_view::npos) {
    const auto close = field.find_first_of(")]", open);
    return read(field.substr(open + 1, close == std::string_view::npos ? close : close - open - 1));
  }
  if (const auto whole = read(field)) return whole;  // a unit row's cell
  if (const auto cut = field.find_last_of(cuts); cut != std::string_view::npos)
    return read(field.substr(cut + 1));
  return std::nullopt;
}

// Where a name ends and its unit begins: "Time/s", "time_s", "t s" for the time; only "CH1/mV"
// for a value, whose names (a gauge's "inc_V") may end in a unit's letters.
inline constexpr std::string_view kTimeUnitCuts = "/_ ", kValueUnitCuts = "/";

// A time unit's name in seconds, read as a scene's quantities are (core/units.hpp).
std::optional<double> time_unit(std::string name);

// Two units are the same when their sizes agree to round-off.
inline constexpr double kSameUnit = 1e-9;

// A row of units only, under the row of names (PicoScope "(ms),(mV)", Keysight "second,Volt"):
// every filled field, without its brackets, a time or value unit.
bool unit_row(const TextRow& row);

// A header that names a value column's unit must name the one the channel reads it in: a column
// in mV read as V is 1000 times the strain, µm/m read as strain a million times.
void check_value_unit(const DelimitedText& text, const TextRow& header, std::size_t column,
                      SignalUnit unit);

}  // namespace shpb
