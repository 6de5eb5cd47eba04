#pragma once
// Reads the `measurement` block of a scene (docs/scene-format.md): where measured gauge signals are
// and how to turn them into strain. Files are resolved relative to the scene but not opened here,
// so a scene whose data live elsewhere still validates; the signal importers check them when used.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/json_value.hpp"
#include "model/scene.hpp"

namespace shpb {

// `gauges` are the gauge names of the scene (channels must name one of them); `bars` its bar
// names and `specimen` its specimen bar (for measurement.uncertainty).
MeasurementSpec read_measurement(const JsonValue& value, const std::filesystem::path& scene_dir,
                                 const std::vector<std::string>& gauges,
                                 const std::vector<std::string>& bars = {},
                                 std::optional<std::size_t> specimen = {});

}  // namespace shpb
