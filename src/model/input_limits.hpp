#pragma once
// The ranges the scene and material readers accept (docs/scene-format.md), public so that every
// other way of setting the same value (the Python module's scene edits) checks the same bounds.
#include <cstdint>

namespace shpb {

// Elements of one bar: far beyond any useful mesh; guards the node count's overflow.
inline constexpr std::int64_t kMaxElements = 100'000'000;

// Poisson's ratio ν of an isotropic solid, an open interval: its bulk and shear moduli stay
// positive only for −1 < ν < 0.5 (docs/scene-format.md, materials).
inline constexpr double kPoissonRatioAbove = -1.0;
inline constexpr double kPoissonRatioBelow = 0.5;

}  // namespace shpb
