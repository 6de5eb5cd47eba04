#pragma once
// The keys each JSON object of the input files allows (docs/scene-format.md): the scene, its
// materials, measurement, calibration file and plan block, campaign files and Monte Carlo
// distributions files. The readers open each object with its list (an unknown key is refused with
// a "did you mean", core/json_value.hpp), and tests/app/test_docs_complete.cpp checks that
// docs/scene-format.md documents exactly these keys. Order matters only for messages ("expected
// one of: …").
#include <string>
#include <vector>

#include "core/closest_match.hpp"
#include "core/enum_names.hpp"
#include "model/fit_spec.hpp"

namespace shpb::input_keys {

using Keys = std::vector<std::string>;

// The scene file.
inline const Keys kScene = {"name",    "notes",      "bars",        "specimen",    "materials",
                            "contact", "simulation", "measurement", "calibration", "plan"};
inline const Keys kBar = {"name",     "material", "length", "diameter", "area",   "velocity",
                          "elements", "gap",      "gauges", "notes",    "inertia"};
inline const Keys kGauge = {"name", "position", "distance_to_specimen"};
inline const Keys kContact = {"method",     "stiffness_factor", "stiffness", "rise_time",
                              "mass_ratio", "interfaces",       "friction"};
inline const Keys kInterface = {"between",   "method",     "stiffness_factor", "stiffness",
                                "rise_time", "mass_ratio", "friction"};
inline const Keys kSimulation = {"duration",   "sample_rate", "stepping", "courant",
                                 "kinematics", "max_strain",  "tolerance"};

// A material (scene `materials`, a bar's inline `material`, a material file): the keys of every
// model, then each model's own.
inline const Keys kMaterial = {"model",  "name",  "density",    "poisson_ratio",
                               "source", "notes", "uncertainty"};
inline const Keys kElastic = {"youngs_modulus"};
inline const Keys kBilinear = {"youngs_modulus", "yield_stress", "tangent_modulus"};
inline const Keys kJohnsonCook = {"youngs_modulus",
                                  "A",
                                  "B",
                                  "n",
                                  "C",
                                  "reference_strain_rate",
                                  "m",
                                  "room_temperature",
                                  "melting_temperature",
                                  "temperature",
                                  "specific_heat",
                                  "taylor_quinney",
                                  "adiabatic",
                                  "strain_rate_filter"};
inline const Keys kViscoelastic = {"long_term_modulus", "arms"};
inline const Keys kMaxwellArm = {"modulus", "relaxation_time"};  // viscoelastic `arms[]`
// A material's `uncertainty.<law parameter>`: a fit's interval of it (fit.json).
inline const Keys kFitInterval = {"interval_95", "method", "weakly_identified"};

// The scene's `measurement`.
inline const Keys kMeasurement = {
    "file",        "format",           "time",           "channels",  "dispersion",
    "windows",     "striker_velocity", "notes",          "load_drop", "sheet",
    "test",        "corrections",      "reflected_time", "align",     "primary",
    "rate_window", "uncertainty"};
inline const Keys kMeasurementTime = {"column", "unit", "resample", "interval", "rate", "start"};
inline const Keys kChannel = {"gauge",  "file",  "column", "unit",
                              "bridge", "scale", "invert", "range"};
inline const Keys kBridge = {"arms", "gauge_factor", "excitation", "gain"};
inline const Keys kDispersion = {"correction", "amplitude_factors", "cutoff", "cutoff_fa_c0"};
inline const Keys kWindows = {"incident", "reflected", "transmitted"};
inline const Keys kRateWindow = {"strain", "time"};
inline const Keys kCorrections = {"friction", "inertia"};
inline const Keys kUncertainty = {
    "gauge_factor",      "excitation", "gain", "gauge_position", "trigger_delay", "window_start",
    "dispersion_cutoff", "friction",   "bars", "shared",         "record_noise",  "notes"};
// `uncertainty.bars.<name>`: an incident or transmitter bar, or the specimen.
inline const Keys kUncertaintyBar = {"youngs_modulus", "density", "wave_speed", "poisson_ratio",
                                     "diameter"};
inline const Keys kUncertaintySpecimen = {"diameter", "length"};

// The scene's `plan` block.
inline const Keys kPlan = {"striker", "shaper", "specimen", "notes"};
inline const Keys kPlanStriker = {"length", "velocity"};
inline const Keys kPlanShaper = {"material", "diameter", "thickness"};
inline const Keys kPlanSpecimen = {"length"};

// Every object of a material (scene `materials`, a bar's inline `material`, a material file, a
// campaign's `material`), where it is: a key refused in one object is looked for in the others, so
// that the refusal says where it belongs (core/json_value.hpp, UnknownKeyError).
inline const std::vector<KeyPlace> kMaterialPlaces = {
    {"a material", &kMaterial},
    {"an elastic material", &kElastic},
    {"a bilinear material", &kBilinear},
    {"a johnson-cook material", &kJohnsonCook},
    {"a viscoelastic material", &kViscoelastic},
    {"a viscoelastic material's arms[]", &kMaxwellArm},
    {"a material's uncertainty.<parameter>", &kFitInterval}};

// The places of one file's objects: `own`, then the material's objects after the first `before`.
inline std::vector<KeyPlace> places_with_material(std::vector<KeyPlace> own, std::size_t before) {
  own.insert(own.begin() + static_cast<std::ptrdiff_t>(before), kMaterialPlaces.begin(),
             kMaterialPlaces.end());
  return own;
}

// Every object of a scene file, where it is (as kMaterialPlaces).
inline const std::vector<KeyPlace> kScenePlaces =
    places_with_material({{"the top level", &kScene},
                          {"bars[]", &kBar},
                          {"bars[].gauges[]", &kGauge},
                          {"contact", &kContact},
                          {"contact.interfaces[]", &kInterface},
                          {"simulation", &kSimulation},
                          {"measurement", &kMeasurement},
                          {"measurement.time", &kMeasurementTime},
                          {"measurement.channels[]", &kChannel},
                          {"measurement.channels[].bridge", &kBridge},
                          {"measurement.dispersion", &kDispersion},
                          {"measurement.windows", &kWindows},
                          {"measurement.rate_window", &kRateWindow},
                          {"measurement.corrections", &kCorrections},
                          {"measurement.uncertainty", &kUncertainty},
                          {"measurement.uncertainty.bars.<bar>", &kUncertaintyBar},
                          {"measurement.uncertainty.bars.<specimen>", &kUncertaintySpecimen},
                          {"plan", &kPlan},
                          {"plan.striker", &kPlanStriker},
                          {"plan.shaper", &kPlanShaper},
                          {"plan.specimen", &kPlanSpecimen}},
                         3);

// A calibration file (`shpb calibrate`'s calibration.json).
inline const Keys kCalibration = {"format", "reference_gauge", "absolute_gain",
                                  "bars",   "gauges",          "provenance"};
inline const Keys kCalibrationBar = {"bar", "wave_speed_m_s", "poisson_ratio", "density_kg_m3",
                                     "youngs_modulus_Pa"};
inline const Keys kCalibrationGauge = {"gauge", "bar", "position_m", "gain", "delay_s"};
inline const Keys kCalibratedValue = {"value", "sd"};
// Its objects, as kScenePlaces.
inline const std::vector<KeyPlace> kCalibrationPlaces = {{"the top level", &kCalibration},
                                                         {"bars[]", &kCalibrationBar},
                                                         {"gauges[]", &kCalibrationGauge},
                                                         {"bars[].<value>", &kCalibratedValue},
                                                         {"gauges[].<value>", &kCalibratedValue}};

// A campaign file: its tests, and the fit's keys (model/fit_spec.hpp), so one file serves `process`
// and `fit`; both read all of them.
inline const Keys kCampaignFit = {"material", "free", "nuisance", "stages", "loss"};
inline const Keys kCampaign = [] {
  Keys keys = {"name", "notes", "tests"};
  keys.insert(keys.end(), kCampaignFit.begin(), kCampaignFit.end());
  return keys;
}();
inline const Keys kCampaignTest = {"scene", "name", "weight"};
// The fit's `nuisance` (kNuisanceNames).
inline const Keys kNuisance = enum_names(kNuisanceNames);
// Its objects, as kScenePlaces: an inline `material` is a material.
inline const std::vector<KeyPlace> kCampaignPlaces = places_with_material(
    {{"the top level", &kCampaign}, {"tests[]", &kCampaignTest}, {"nuisance", &kNuisance}}, 3);

// A Monte Carlo distributions file (`study --sweep monte-carlo`).
inline const Keys kDistributions = {"values", "notes"};
inline const Keys kDistribution = {"normal", "uniform"};
// Its objects, as kScenePlaces.
inline const std::vector<KeyPlace> kDistributionsPlaces = {
    {"the top level", &kDistributions}, {"values.<scene value>", &kDistribution}};

}  // namespace shpb::input_keys
