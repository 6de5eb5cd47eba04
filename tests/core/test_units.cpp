#include <catch2/catch.hpp>
#include <stdexcept>
#include <string>

#include "core/units.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_core_test_units {

using namespace shpb;

namespace {
// Conversion factors are products of exact decimal constants; allow a few ulps of round-off.
constexpr double kRelativeTolerance = 1e-14;

double q(const std::string& text, Dimension d) { return parse_quantity(text, d); }

bool rejects(const std::string& text, Dimension d, const std::string& part_of_message) {
  try {
    parse_quantity(text, d);
  } catch (const std::invalid_argument& e) {
    return std::string(e.what()).find(part_of_message) != std::string::npos;
  }
  return false;
}
}  // namespace

TEST_CASE("Bare numbers and numbers without a unit are taken as SI", "[core][units]") {
  CHECK(q("0.005", Dimension::kLength) == 0.005);
  CHECK(q("  2e11 ", Dimension::kPressure) == 2e11);
  CHECK(q("+15", Dimension::kVelocity) == 15);
  CHECK(q("-3.5", Dimension::kVelocity) == -3.5);
  CHECK(q("0.29", Dimension::kDimensionless) == 0.29);
}

TEST_CASE("Every unit of every dimension converts to SI", "[core][units]") {
  struct Case {
    const char* text;
    Dimension dimension;
    double si;
  };
  const Case cases[] = {
      {"20 mm", Dimension::kLength, 0.02},
      {"2 m", Dimension::kLength, 2},
      {"1.5 cm", Dimension::kLength, 0.015},
      {"3 dm", Dimension::kLength, 0.3},
      {"0.75 in", Dimension::kLength, 0.01905},  // inch = 25.4 mm exactly
      {"250 um", Dimension::kLength, 250e-6},
      {"285 mm2", Dimension::kArea, 285e-6},
      {"2.85 cm^2", Dimension::kArea, 2.85e-4},
      {"1 m\xC2\xB2", Dimension::kArea, 1},
      {"600 us", Dimension::kTime, 600e-6},
      {"600 \xC2\xB5s", Dimension::kTime, 600e-6},  // µ MICRO SIGN
      {"600 \xCE\xBCs", Dimension::kTime, 600e-6},  // μ GREEK MU
      {"2 ms", Dimension::kTime, 2e-3},
      {"50 ns", Dimension::kTime, 50e-9},
      {"3 ps", Dimension::kTime, 3e-12},
      {"10 MHz", Dimension::kFrequency, 10e6},
      {"200 kHz", Dimension::kFrequency, 200e3},
      {"1 GHz", Dimension::kFrequency, 1e9},
      {"1.2 kg", Dimension::kMass, 1.2},
      {"500 g", Dimension::kMass, 0.5},
      {"7.85 g/cm3", Dimension::kDensity, 7850},
      {"8080 kg/m3", Dimension::kDensity, 8080},
      {"8080 kg/m^3", Dimension::kDensity, 8080},
      {"8080 kg m^-3", Dimension::kDensity, 8080},
      {"8080 kg\xC2\xB7m-3", Dimension::kDensity, 8080},
      {"8.08 g/cm\xC2\xB3", Dimension::kDensity, 8080},
      {"200 GPa", Dimension::kPressure, 200e9},
      {"324 MPa", Dimension::kPressure, 324e6},
      {"101.325 kPa", Dimension::kPressure, 101325},
      {"2 bar", Dimension::kPressure, 2e5},
      {"15 psi", Dimension::kPressure, 15 * 6894.757293168361},
      {"1 ksi", Dimension::kPressure, 6894757.293168361},
      {"1 TPa", Dimension::kPressure, 1e12},
      {"1 N/mm2", Dimension::kPressure, 1e6},
      {"15 m/s", Dimension::kVelocity, 15},
      {"5 mm/us", Dimension::kVelocity, 5000},
      {"10 kN", Dimension::kForce, 1e4},
      {"1 kg m/s2", Dimension::kForce, 1},
      {"5 J", Dimension::kEnergy, 5},
      {"3 mJ", Dimension::kEnergy, 3e-3},
      {"2 N*m", Dimension::kEnergy, 2},
      {"8 V", Dimension::kVoltage, 8},
      {"300 mV", Dimension::kVoltage, 0.3},
      {"293 K", Dimension::kTemperature, 293},
      {"900 J/(kg K)", Dimension::kSpecificHeat, 900},
      {"900 J/kg/K", Dimension::kSpecificHeat, 900},
      {"900 J/kg K", Dimension::kSpecificHeat, 900},  // '/' divides by the whole rest
      {"0.9 J/(g K)", Dimension::kSpecificHeat, 900},
      {"1000 1/s", Dimension::kStrainRate, 1000},
      {"1000 s^-1", Dimension::kStrainRate, 1000},
      {"1000 /s", Dimension::kStrainRate, 1000},
      {"2 /ms", Dimension::kStrainRate, 2000},
      {"1e9 N/m", Dimension::kStiffness, 1e9},
      {"1 kN/mm", Dimension::kStiffness, 1e6},
  };
  for (const auto& c : cases) {
    INFO(c.text);
    CHECK(q(c.text, c.dimension) == Approx(c.si).epsilon(kRelativeTolerance));
  }
}

TEST_CASE("Temperatures accept kelvin and degrees Celsius", "[core][units]") {
  CHECK(q("20 degC", Dimension::kTemperature) == Approx(293.15).epsilon(kRelativeTolerance));
  CHECK(q("0 \xC2\xB0"
          "C",
          Dimension::kTemperature) == Approx(273.15).epsilon(kRelativeTolerance));
  CHECK(q("-273.15 degC", Dimension::kTemperature) == Approx(0).margin(1e-12));
  CHECK(q("293 K", Dimension::kTemperature) == 293);
  CHECK(rejects("20 degC", Dimension::kLength, "is a temperature"));
  CHECK(rejects("900 J/(kg degC)", Dimension::kSpecificHeat, "only valid on its own"));
}

TEST_CASE("A unit of the wrong dimension is rejected and named", "[core][units]") {
  CHECK(rejects("20 kg", Dimension::kLength, "\"kg\" is a mass; expected a length"));
  CHECK(rejects("200 GPa", Dimension::kDensity, "is a stress; expected a density"));
  CHECK(rejects("15 m", Dimension::kVelocity, "expected a velocity such as \"15 m/s\""));
  CHECK(rejects("10 MHz", Dimension::kTime, "is a frequency"));
  CHECK(rejects("3 kg/m2", Dimension::kDensity, "a quantity in m^-2 kg"));
  CHECK(rejects("1 V", Dimension::kPressure, "is a voltage"));
}

TEST_CASE("Unknown units, bad numbers and malformed expressions are rejected", "[core][units]") {
  CHECK(rejects("20 furlongs", Dimension::kLength, "unknown unit \"furlongs\""));
  CHECK(rejects("20 Mm/", Dimension::kVelocity, "a unit is missing"));
  CHECK(rejects("20 mm^", Dimension::kLength, "integer exponent"));
  CHECK(rejects("20 m^0", Dimension::kLength, "non-zero"));
  CHECK(rejects("1 J/(kg K", Dimension::kSpecificHeat, "closing parenthesis"));
  CHECK(rejects("1 kK", Dimension::kTemperature, "unknown unit"));  // K takes no prefix
  CHECK(rejects("1 kin", Dimension::kLength, "unknown unit"));      // nor does the inch
  CHECK(rejects("mm", Dimension::kLength, "no number"));
  CHECK(rejects("", Dimension::kLength, "no number"));
  CHECK(rejects("nan", Dimension::kLength, "no number"));
  CHECK(rejects("inf m", Dimension::kLength, "no number"));
  CHECK(rejects("1e999 m", Dimension::kLength, "out of range"));
  CHECK(rejects("1e300 Tm", Dimension::kLength, "out of range"));
  CHECK(rejects("1,5 mm", Dimension::kLength, "decimal point, not a comma"));
  CHECK(rejects("20 m m", Dimension::kLength, "an area"));  // space multiplies: m² is no length
  // A second number, not the unit "1" of "1/s" (read before as 16 x 1^6 mm and 2 x 1 m).
  CHECK(rejects("16 16 mm", Dimension::kLength, "a second number?"));
  CHECK(rejects("2 1 m", Dimension::kLength, "a second number?"));
  CHECK(rejects("5 1", Dimension::kLength, "a second number?"));
  CHECK(q("1000 1 / s", Dimension::kStrainRate) == 1000);
}

TEST_CASE("Every dimension has a name and an SI unit for messages", "[core][units]") {
  CHECK(to_string(Dimension::kLength) == "a length");
  CHECK(si_unit(Dimension::kLength) == "m");
  CHECK(si_unit(Dimension::kPressure) == "Pa");
  CHECK(si_unit(Dimension::kDimensionless).empty());
}

}  // namespace tests_core_test_units
