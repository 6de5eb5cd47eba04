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

// `bars` are the scene's bar names left to right; `specimen` its specimen bar (the bars named
// in the block must be the specimen or its neighbours: the bars a reduction uses).
UncertaintySpec read_uncertainty(const JsonValue& value, const std::vector<std::string>& bars,
                                 std::optional<std::size_t> specimen);

}  // namespace shpb
