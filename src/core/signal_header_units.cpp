// The units a signal file's header names (core/signal_header_units.hpp).
#include "core/signal_header_units.hpp"

#include <cmath>
#include <stdexcept>

#include "core/error.hpp"
#include "core/units.hpp"

namespace shpb {

std::optional<double> time_unit(std::string name) {
  if (name == "second" || name == "seconds" || name == "sec") name = "s";
  try {
    return parse_quantity("1 " + name, Dimension::kTime);
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

namespace {

// A value column's unit: a voltage ("V", "mV", "Volt") or a strain ("ε", "µε", "µm/m",
// "microstrain", "%"), with its size in volts or in strain.
struct ValueUnit {
  bool volts = false;
  double size = 1;
};
std::optional<ValueUnit> value_unit(std::string name) {
  if (name == "Volt" || name == "Volts" || name == "volt" || name == "volts") name = "V";
  if (name == "\xCE\xB5") return ValueUnit{false, 1};  // ε
  if (name == "%") return ValueUnit{false, 0.01};      // a strain in percent
  if (name == "u\xCE\xB5" || name == "ue" || name == "ustrain" || name == "microstrain")
    return ValueUnit{false, 1e-6};
  try {
    if (name.find('/') != std::string::npos)  // m/m, mm/m, µm/m
      return ValueUnit{false, parse_quantity("1 " + name, Dimension::kDimensionless)};
    return ValueUnit{true, parse_quantity("1 " + name, Dimension::kVoltage)};
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

ValueUnit read_as(SignalUnit u) {
  switch (u) {
    case SignalUnit::kVolt:
      return {true, 1};
    case SignalUnit::kMillivolt:
      return {true, 1e-3};
    case SignalUnit::kMicrostrain:
      return {false, 1e-6};
    case SignalUnit::kStrain:
      break;
  }
  return {false, 1};
}

}  // namespace

bool unit_row(const TextRow& row) {
  std::size_t units = 0;
  for (std::string_view f : row.fields) {
    if (f.empty()) continue;
    if (f.size() >= 2 && (f.front() == '(' || f.front() == '[') &&
        (f.back() == ')' || f.back() == ']'))
      f = f.substr(1, f.size() - 2);
    if (f.find_first_of("([/_ ") != std::string_view::npos && !value_unit(std::string(f)))
      return false;  // a name with a unit ("Time (ms)", "t_s"), not a unit
    if (!header_unit(f, time_unit, kTimeUnitCuts) && !header_unit(f, value_unit, kValueUnitCuts))
      return false;
    ++units;
  }
  return units > 0;
}

void check_value_unit(const DelimitedText& text, const TextRow& header, std::size_t column,
                      SignalUnit unit) {
  if (column >= header.fields.size()) return;
  const auto named = header_unit(header.fields[column], value_unit, kValueUnitCuts);
  const ValueUnit read = read_as(unit);
  if (!named || (named->second.volts == read.volts &&
                 std::abs(named->second.size / read.size - 1) <= kSameUnit))
    return;
  std::string hint = "convert the column to V, mV, strain or microstrain";
  for (const auto& [name, u] : kSignalUnitNames)
    if (read_as(u).volts == named->second.volts &&
        std::abs(named->second.size / read_as(u).size - 1) <= kSameUnit)
      hint = "set \"unit\": \"" + std::string(name) + "\"";
  throw input_error(text.file.string(), text_place(header.line, column),
                    "\"" + std::string(header.fields[column]) + "\"",
                    "the header gives the values in " + named->first +
                        ", but the channel reads them in " +
                        std::string(enum_name(kSignalUnitNames, unit)) +
                        " (measurement.channels[].unit): " + hint + " or correct the header");
}

}  // namespace shpb
