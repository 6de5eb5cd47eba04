#pragma once
// Bessel factors of the Pochhammer–Chree mode for a radial wavenumber s whose square may be
// negative (then s = i q and J_n(i q r) becomes a modified Bessel function I_n). Only the
// combinations J0(s), s·J1(s) and J1(s)/s appear in the frequency equation and the amplitude
// factors; all three are real for either sign of s². When s is imaginary they are returned scaled
// by exp(−q) so that large a/Λ does not overflow (every term of the equations carries exactly one
// such factor per wavenumber, so the scale cancels).

namespace shpb {

struct BesselFactors {
  double j0 = 1;           // J0(s)        or I0(q)·e^{−q}
  double s_j1 = 0;         // s·J1(s)      or −q·I1(q)·e^{−q}
  double j1_over_s = 0.5;  // J1(s)/s    or I1(q)/q·e^{−q}
};

// Factors at argument s·r for s² = s_squared (r = 1: the caller scales s by the radius).
BesselFactors bessel_factors(double s_squared);

}  // namespace shpb
