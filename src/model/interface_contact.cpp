// Per-interface contact settings: the scene-wide contact block with one interface's override
// applied (docs/scene-format.md "contact"). Shared by validate and simulate so both resolve alike.
#include "model/scene.hpp"

namespace shpb {

ContactMethod interface_method(const ContactSpec& contact, std::size_t k) {
  for (const InterfaceOverride& o : contact.interfaces)
    if (o.left_bar == k && o.method) return *o.method;
  return contact.method;
}

PenaltyParams interface_penalty(const ContactSpec& contact, std::size_t k) {
  PenaltyParams p = contact.penalty;
  for (const InterfaceOverride& o : contact.interfaces) {
    if (o.left_bar != k) continue;
    const PenaltyParams& q = o.penalty;
    if (q.stiffness_factor || q.stiffness_N_m || q.rise_time_s) {
      p.stiffness_factor = q.stiffness_factor;
      p.stiffness_N_m = q.stiffness_N_m;
      p.rise_time_s = q.rise_time_s;
    }
    if (q.mass_ratio) p.mass_ratio = q.mass_ratio;
  }
  return p;
}

double interface_friction(const ContactSpec& contact, std::size_t k) {
  for (const InterfaceOverride& o : contact.interfaces)
    if (o.left_bar == k && o.friction) return *o.friction;
  return contact.friction;
}

}  // namespace shpb
