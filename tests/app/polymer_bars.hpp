#pragma once
// A polymer-bar set-up shared by the tests of process and plan.
#include <nlohmann/json.hpp>

namespace shpb_test {

// PMMA bars of 20 mm (E(t) = 3 GPa + 1.5 GPa e^{-t/1 ms} + 1.2 GPa e^{-t/20 us}) on a soft
// specimen (50 MPa, 15 x 5 mm), as a lab tests a foam or rubber; the striker at 2 m/s; a record of
// 1.8 ms.
inline nlohmann::json polymer_bar_scene() {
  const nlohmann::json pmma = {{"model", "viscoelastic"},
                               {"density", "1190 kg/m3"},
                               {"poisson_ratio", 0.35},
                               {"long_term_modulus", "3 GPa"},
                               {"arms",
                                {{{"modulus", "1.5 GPa"}, {"relaxation_time", "1 ms"}},
                                 {{"modulus", "1.2 GPa"}, {"relaxation_time", "20 us"}}}}};
  return {{"bars",
           {{{"name", "striker"},
             {"material", "pmma"},
             {"length", "0.15 m"},
             {"diameter", "20 mm"},
             {"velocity", "2 m/s"}},
            {{"name", "incident"},
             {"material", "pmma"},
             {"length", "2 m"},
             {"diameter", "20 mm"},
             {"gauges", {{{"name", "incident"}, {"distance_to_specimen", "1 m"}}}}},
            {{"name", "specimen"},
             {"material",
              {{"model", "elastic"},
               {"density", "1100 kg/m3"},
               {"youngs_modulus", "50 MPa"},
               {"poisson_ratio", 0.45}}},
             {"length", "5 mm"},
             {"diameter", "15 mm"}},
            {{"name", "transmitter"},
             {"material", "pmma"},
             {"length", "1 m"},
             {"diameter", "20 mm"},
             {"gauges", {{{"name", "transmitted"}, {"distance_to_specimen", "0.1 m"}}}}}}},
          {"specimen", "specimen"},
          {"materials", {{"pmma", pmma}}},
          {"simulation", {{"duration", "1.8 ms"}}}};
}

}  // namespace shpb_test
