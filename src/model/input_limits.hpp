#pragma once
// The ranges the scene and material readers accept (docs/scene-format.md), public so that every
// other way of setting the same value (the Python module's scene edits) checks the same bounds.
#include <cstdint>
#include <string>

namespace shpb {

// Elements of one bar: far beyond any useful mesh; guards the node count's overflow.
inline constexpr std::int64_t kMaxElements = 100'000'000;

// Poisson's ratio ν of an isotropic solid, an open interval: its bulk and shear moduli stay
// positive only for −1 < ν < 0.5 (docs/scene-format.md, materials).
inline constexpr double kPoissonRatioAbove = -1.0;
inline constexpr double kPoissonRatioBelow = 0.5;

// A bar's `gap` is to the next bar on its right: the last bar has none.
inline constexpr const char* kLastBarGap =
    "the gap is to the next bar on the right; the last bar has none";

// Rules between values, for the key named last: "" where they hold, else what is expected.
// A gauge lies on its bar, within [0, length] of its left end (model/scene_reader.cpp).
std::string gauge_position_problem(double position_m, double bar_length_m);
// Johnson-Cook's homologous temperature (T - T_room) / (T_melt - T_room) needs T_melt > T_room;
// the test's temperature lies below melting (model/material_reader.cpp).
std::string melting_temperature_problem(double melting_K, double room_K);
std::string test_temperature_problem(double test_K, double melting_K);
// A bilinear law's hardening slope after yield lies below its elastic modulus.
std::string tangent_modulus_problem(double tangent_Pa, double youngs_modulus_Pa);

}  // namespace shpb
