// A bonded interface (`contact.method: "bonded"`): the faces are glued, as a specimen is glued or
// threaded into the bars of a split Hopkinson tension bar, so the interface carries tension as
// well as compression and never opens. It is the node-to-node bipenalty link of
// contact_bipenalty.cpp made bilateral (InterfaceModel::tied, set for this method in
// make_interface_model): stiff (ε_s = 1e4 EA/h by default) and mass-penalised so that it keeps
// the bars' stable step (docs/methods.md §2). Between bars on different time steps
// (asynchronous stepping) the tied link is unstable — measured: energy ×1000 within 600 µs on a
// steel–specimen–steel chain — so a scene with a bonded interface steps globally (discretize()).
#include "solver/contact.hpp"

namespace shpb {

ContactResult solve_bonded(const InterfaceModel& model, InterfaceState& state, const EndState& left,
                           const EndState& right) {
  return solve_bipenalty(model, state, left, right);  // tied: active in tension too
}

}  // namespace shpb
