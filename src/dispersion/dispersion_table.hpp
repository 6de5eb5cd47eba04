#pragma once
// The first Pochhammer–Chree mode of one Poisson ratio, solved once on a fine a/Λ grid and
// interpolated by normalised frequency f·a/c0 (the quantity an FFT bin gives directly).
#include <memory>
#include <mutex>
#include <vector>

namespace shpb {

class DispersionTable {
 public:
  // Solves the mode at `points` evenly spaced a/Λ in [0, max_a_over_lambda] by marching in k.
  explicit DispersionTable(double poisson, double max_a_over_lambda = kMaxAOverLambda,
                           int points = kPoints);
  // The same grid, solved only as far as a correction needs: to the first point at or above the
  // normalised frequency `fa_over_c0` and past the pole of m1 (or to the grid's end).
  static DispersionTable up_to(double poisson, double fa_over_c0);

  static constexpr double kMaxAOverLambda = 2.0;
  static constexpr int kPoints = 4001;  // Δ(a/Λ) = 5e-4

  double poisson() const { return poisson_; }
  // Largest tabulated f·a/c0; beyond it the caller must not ask (the correction cuts off below).
  double max_normalized_frequency() const { return fa_.back(); }
  // f·a/c0 of the pole of m1 (surface strain of the mode vanishes), 0 if beyond the table.
  double m1_pole_normalized_frequency() const { return m1_pole_fa_; }

  // Phase velocity c/c0, amplitude factors m1 and m1·m2 at normalised frequency f·a/c0
  // (linear interpolation; the grid makes the error < 1e-7 in c/c0).
  double phase_velocity(double fa_over_c0) const;
  double m1(double fa_over_c0) const;
  double m1_m2(double fa_over_c0) const;

 private:
  DispersionTable(double poisson, double max_a_over_lambda, int points, double stop_fa_over_c0);
  double interpolate(const std::vector<double>& y, double fa_over_c0) const;

  double poisson_;
  std::vector<double> fa_;  // f·a/c0, increasing (group velocity > 0)
  std::vector<double> c_;   // c/c0
  std::vector<double> m1_;  // Tyas–Pope m1 (infinite at the pole: clamped, never used there)
  std::vector<double> m1m2_;
  double m1_pole_fa_ = 0;
};

// The tables of repeated corrections (the draws of a Monte Carlo propagation, on several threads):
// each Poisson ratio solved once, with headroom above the cut-off asked (a drawn cut-off a little
// higher reuses it). A table's values do not depend on where it stops, so a reduction with a
// cached table equals one with its own.
class DispersionTableCache {
 public:
  const DispersionTable& up_to(double poisson, double fa_over_c0);

 private:
  std::mutex mutex_;
  std::vector<std::unique_ptr<DispersionTable>> tables_;
};

}  // namespace shpb
