#pragma once
// Reads measurement.uncertainty (docs/scene-format.md): standard uncertainties with a unit of the
// quantity, or "%" of its nominal value.
#include <optional>
#include <string>
#include <vector>

#include "core/json_value.hpp"
#include "model/scene.hpp"

namespace shpb {

// A standard uncertainty: "x %" of the nominal value (below 100 %), or an absolute value of
// dimension `d` (a bare number for a plain number: "%" always means relative). `relative_ok`
// false: the nominal value is zero (a delay, a window shift), so only an absolute value means
// something. InputError naming the value otherwise.
StandardUncertainty read_standard_uncertainty(const JsonValue& v, Dimension d,
                                              bool relative_ok = true);

// A normal distribution of a quantity that must keep its sign (a modulus, a density, a length, a
// gauge factor: > 0) is ill-posed when a draw crosses zero with a probability that matters: its
// standard deviation must be below |value| / kSignKeepingSigmas. At 6 standard deviations a draw
// is ≤ 0 with probability Φ(−6) = 1e-9, so below 1e-6 over 1000 draws (`process`'s default; a
// study's is 200). The one rule for measurement.uncertainty and a study's distributions.
inline constexpr double kSignKeepingSigmas = 6.0;
// Empty if a normal distribution of mean `value` (≠ 0) and standard deviation `sigma` keeps the
// sign of `value`, else what is expected (naming both in dimension `d`).
std::string sign_keeping_problem(double value, double sigma, Dimension d);

// `bars` are the scene's bar names left to right; `specimen` its specimen bar (the bars named
// in the block must be the specimen or its neighbours: the bars a reduction uses).
UncertaintySpec read_uncertainty(const JsonValue& value, const std::vector<std::string>& bars,
                                 std::optional<std::size_t> specimen);

}  // namespace shpb
