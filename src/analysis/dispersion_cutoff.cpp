#include "analysis/dispersion_cutoff.hpp"

namespace shpb {

double cutoff_fa_over_c0(const DispersionSpec& ds, const BarWaveguide& w) {
  if (ds.cutoff_fa_c0) return *ds.cutoff_fa_c0;
  return ds.cutoff_Hz ? *ds.cutoff_Hz * w.radius_m / w.c0_m_s : kDefaultCutoffFaOverC0;
}

double dispersion_cutoff_Hz(const DispersionSpec& ds, const BarWaveguide& w) {
  return cutoff_fa_over_c0(ds, w) * w.c0_m_s / w.radius_m;
}

const char* dispersion_cutoff_key(const DispersionSpec& ds) {
  return ds.cutoff_fa_c0 ? "measurement.dispersion.cutoff_fa_c0" : "measurement.dispersion.cutoff";
}

}  // namespace shpb
