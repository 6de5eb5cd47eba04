#pragma once
// A steel striker on a steel bar with one gauge (docs/methods.md §4), meshed by hand at 1 mm (the
// automatic meshes): a run's cost and its outputs' sizes are those of this mesh, not of the one a
// tolerance would choose (coarse enough to finish 5 s of it in half a second). `duration` sets
// them: field.csv grows by about 12 MB per ms at 1 MHz; 5 s is ~2.5e10 node updates, seconds of
// solving even optimised.
#include <string>

namespace shpb_robust {

inline std::string striker_on_bar_scene(const std::string& duration,
                                        const std::string& sample_rate = "1 MHz") {
  return R"({
  "name": "striker on bar",
  "bars": [
    {"name": "striker", "material": "steel", "length": "200 mm", "diameter": "12 mm",
     "velocity": "10 m/s", "elements": 200},
    {"name": "bar", "material": "steel", "length": "1 m", "diameter": "12 mm", "elements": 1000,
     "gauges": [{"name": "gauge", "position": "500 mm"}]}
  ],
  "materials": {"steel": {"model": "elastic", "density": "7850 kg/m3",
                          "youngs_modulus": "200 GPa", "poisson_ratio": 0.29}},
  "simulation": {"duration": ")" +
         duration + R"(", "sample_rate": ")" + sample_rate + R"("}
})";
}

}  // namespace shpb_robust
