#pragma once
// Physical quantities given as numbers (SI) or strings with a unit: "20 mm", "200 GPa",
// "7.85 g/cm3", "600 us" (µ and u both mean micro), "15 m/s", "10 MHz" (docs/scene-format.md).
#include <string>
#include <string_view>

namespace shpb {

enum class Dimension {
  kDimensionless,
  kLength,        // m
  kArea,          // m^2
  kTime,          // s
  kFrequency,     // Hz = 1/s
  kMass,          // kg
  kDensity,       // kg/m^3
  kPressure,      // Pa
  kVelocity,      // m/s
  kForce,         // N
  kEnergy,        // J
  kVoltage,       // V
  kTemperature,   // K (°C accepted and converted)
  kSpecificHeat,  // J/(kg K)
  kStrainRate,    // 1/s
  kStiffness,     // N/m
};

std::string_view to_string(Dimension d);
std::string_view si_unit(Dimension d);
// What a value of `d` looks like, as parse_quantity's messages say it: "a time such as \"600 us\"
// (a bare number is taken in s)".
std::string quantity_text(Dimension d);

// Parses "<number> <unit>" (or a bare number, taken as SI) into SI. Throws std::invalid_argument
// with a message saying what was expected ("a length such as \"20 mm\"") on a bad number, an
// unknown unit, or a unit of another dimension. The caller adds file and JSON path. A plain
// number may be given in percent: "1 %" is 0.01.
double parse_quantity(std::string_view text, Dimension expected);

}  // namespace shpb
