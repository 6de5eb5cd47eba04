#include "study/sweep.hpp"

#include <algorithm>
#include <cmath>

#include "core/csv_writer.hpp"
#include "model/discretization.hpp"
#include "solver/contact.hpp"

namespace shpb {

namespace {
const std::vector<ContactMethod> kAllMethods = {ContactMethod::kPenalty, ContactMethod::kBipenalty,
                                                ContactMethod::kLocalizedBipenalty};
const std::vector<Stepping> kAllSteppings = {Stepping::kAsynchronous, Stepping::kGlobal};
}  // namespace

std::string format_factor(double factor) {
  if (factor < 1) return "1/" + format_double(1 / factor);
  return format_double(factor);
}

std::vector<ParetoCase> pareto_cases(const std::vector<ContactMethod>& methods,
                                     const std::vector<Stepping>& steppings,
                                     const std::vector<double>& resolutions) {
  std::vector<ParetoCase> cases;
  for (ContactMethod m : methods.empty() ? kAllMethods : methods) {
    for (Stepping s : steppings.empty() ? kAllSteppings : steppings)
      for (double r : resolutions) cases.push_back({m, s, r});
    const bool asynchronous =
        steppings.empty() ||
        std::find(steppings.begin(), steppings.end(), Stepping::kAsynchronous) != steppings.end();
    if (m == ContactMethod::kLocalizedBipenalty && asynchronous)
      for (double r : resolutions) cases.push_back({m, Stepping::kAsynchronous, r, true});
  }
  return cases;
}

std::string method_name(const ParetoCase& c) {
  return c.finite_links ? "localized-bipenalty-finite" : std::string(to_string(c.method));
}

Scene scene_at_resolution(const Scene& scene, double factor) {
  Scene out = scene;
  const ChainDiscretization d = discretize(scene);
  for (std::size_t i = 0; i < out.bars.size(); ++i)
    out.bars[i].elements = std::max(1, static_cast<int>(std::lround(factor * d.bars[i].elements)));
  return out;
}

Scene scene_for(const Scene& scene, const ParetoCase& c) {
  Scene out = scene_at_resolution(scene, c.resolution);
  out.contact.method = c.method;
  for (InterfaceOverride& o : out.contact.interfaces) o.method.reset();
  // A bonded interface (glued: it carries tension) is part of the experiment, not a contact to
  // compare methods on: it stays bonded.
  for (std::size_t k = 0; k + 1 < scene.bars.size(); ++k) {
    if (interface_method(scene.contact, k) != ContactMethod::kBonded) continue;
    auto o = std::find_if(out.contact.interfaces.begin(), out.contact.interfaces.end(),
                          [k](const InterfaceOverride& i) { return i.left_bar == k; });
    if (o == out.contact.interfaces.end())
      o = out.contact.interfaces.insert(out.contact.interfaces.end(), InterfaceOverride{k});
    o->method = ContactMethod::kBonded;
  }
  out.simulation.stepping = c.stepping;
  // The study measures its runs by its own norms (point samples, and those seen through the
  // record's Gaussian): its runs record point samples whatever the scene's tolerance (which chose
  // the meshes and Courant number of resolution 1 already).
  out.simulation.tolerance.reset();
  if (c.finite_links) {
    out.contact.penalty.stiffness_factor = kDefaultStiffnessFactor;
    out.contact.penalty.mass_ratio = kDefaultMassRatio;
  }
  return out;
}

namespace {
std::vector<double> refined(const std::vector<double>& axis, int refine, bool log) {
  std::vector<double> out;
  for (std::size_t i = 0; i + 1 < axis.size(); ++i)
    for (int k = 0; k < refine; ++k) {
      const double f = static_cast<double>(k) / refine;
      out.push_back(k == 0 ? axis[i]
                    : log  ? axis[i] * std::pow(axis[i + 1] / axis[i], f)
                           : axis[i] + (axis[i + 1] - axis[i]) * f);
    }
  out.push_back(axis.back());
  return out;
}
}  // namespace

std::vector<StabilityPoint> stability_grid(const std::vector<ContactMethod>& methods, int refine) {
  const std::vector<double> stiffness = refined(kStiffnessFactors, refine, true),
                            courant = refined(kCourantNumbers, refine, false);
  std::vector<StabilityPoint> grid;
  for (ContactMethod m : methods.empty() ? kAllMethods : methods) {
    const std::vector<double> ratios =
        m == ContactMethod::kPenalty ? std::vector<double>{0.0} : kMassRatios;
    const std::vector<double> steps =
        m == ContactMethod::kLocalizedBipenalty ? kStepRatios : std::vector<double>{1.0};
    for (double q : steps) {
      if (m == ContactMethod::kLocalizedBipenalty)  // the rigid-link limit (stiffness 0)
        for (double c : courant) grid.push_back({m, 0, 0, c, false, q});
      for (double r : ratios)
        for (double s : stiffness)
          for (double c : courant) grid.push_back({m, s, r, c, false, q});
    }
  }
  return grid;
}

}  // namespace shpb
