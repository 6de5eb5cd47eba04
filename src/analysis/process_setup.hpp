#pragma once
#include <nlohmann/json.hpp>

#include "model/scene.hpp"

namespace shpb {

// What `process` will read and use, read and resolved by process's own functions: every channel
// (file, column, unit, strain per unit), the common time base, the gauges' roles and distances,
// the windows, the dispersion correction, the expected pulse timing, and the warnings process
// would give on reading. A problem is the InputError process would throw (exit 2). Needs
// scene.measurement.
nlohmann::json process_setup(const Scene& scene);

}  // namespace shpb
