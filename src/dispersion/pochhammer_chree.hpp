#pragma once
// First longitudinal Pochhammer–Chree mode of a solid circular bar (Bancroft 1941; docs/methods.md
// §5). Everything is dimensionless: radius a = 1, bar speed c0 = sqrt(E/ρ) = 1, so the mode is a
// function of the Poisson ratio ν and x = a/Λ only; c/c0 and f·a/c0 = x·c/c0 follow.

namespace shpb {

// The Poisson ratios shpb solves the mode for (docs/methods.md §5): bar steels, aluminium,
// titanium and PMMA lie well inside; auxetic (ν < 0) bars are not supported.
inline constexpr double kMinPoissonRatio = 0.0, kMaxPoissonRatio = 0.49;
inline bool poisson_ratio_supported(double nu) {
  return nu >= kMinPoissonRatio && nu <= kMaxPoissonRatio;
}

// Bulk wave speeds of an isotropic solid over c0, from ν alone.
struct WaveSpeeds {
  double longitudinal;  // c_L/c0 = sqrt((1−ν)/((1+ν)(1−2ν)))
  double shear;         // c_T/c0 = 1/sqrt(2(1+ν))
  double rayleigh;      // c_R/c0, root of the Rayleigh equation
};
WaveSpeeds wave_speeds(double poisson);

// Bancroft's frequency equation divided by β (real for either sign of α², β², no false root at
// c = c_T), scaled by k⁻⁴ and the exponential scale of any modified Bessel factor; its sign
// changes at the roots. x = a/Λ > 0, c = phase velocity over c0.
double frequency_equation(double poisson, double x, double c);

// Phase velocity c/c0 of the first mode at x = a/Λ ≥ 0: the lowest sign change of the frequency
// equation between 0.9 c_R and c0, refined to ~1e-13. `guess` (the root at a slightly smaller x,
// Δx ≤ 0.01) narrows the bracket when tabulating; without it the full range is scanned.
double phase_velocity(double poisson, double x, double guess = 0);

// Group velocity c_g/c0 = dω/dk at x, from the implicit-function theorem on the frequency equation
// (dω/dk = −G_k/G_ω), independent of any table. `c` is the phase velocity at x.
double group_velocity(double poisson, double x, double c);

// Tyas & Pope (2005) amplitude factors at x with phase velocity c: m1 = mean axial strain over the
// cross-section / surface strain; m1·m2 = mean axial stress / (E · surface strain). m1 has a pole
// where the surface strain of the mode vanishes (a/Λ = 0.37675 for ν = 0.29).
struct AmplitudeFactors {
  double m1 = 1;
  double m1_m2 = 1;
};
AmplitudeFactors amplitude_factors(double poisson, double x, double c);

// Surface strain of the mode over its mean strain, 1/m1 without the pole (zero at the pole).
double surface_over_mean_strain(double poisson, double x, double c);

}  // namespace shpb
