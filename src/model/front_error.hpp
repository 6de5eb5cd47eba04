#pragma once
// The frequency integrals of the gauge-error model's bars' share (docs/methods.md §1.1): what a
// front that has crossed bars over distances x_i loses to their meshes, as one gauge reads it.
// They are pure functions of numbers — the record's sample interval and the pulse's rise time,
// and for every bar on the path its distance, element length, wave speed, step and Courant number
// — and a search, or a run of the same set-up again, asks for the same ones many times: the
// integral is remembered by all of those numbers (the cost of the choice, §1.1).
#include <memory>
#include <vector>

namespace shpb {

// What the integrals weigh each frequency by depends on the record (Δs) and the pulse's rise (τ)
// only, not on the mesh.
struct FrequencyWeights {
  double sample_s = -1, rise_s = -1;
  double dw = 0;
  std::vector<double> weight;  // (trapezoid end) e^{−ω²Δs²}/(1 + ω²τ²) at ω_j = j dω, j = 1…N
  std::vector<double> w2;    // ω_j²
  std::vector<double> tail;  // Σ_{m ≥ j} weight_m/ω_m²: the integrand where nothing is carried
  // The aliasing integral's points ω and its running sums (the sum up to, not including, point n).
  double alias_dw = 0;
  std::vector<double> alias_w, alias_sum;

  FrequencyWeights(double sample, double rise);
};

// The weights of (Δs, τ), computed once for the pairs asked for recently (shared by every thread).
std::shared_ptr<const FrequencyWeights> frequency_weights(double sample_s, double rise_s);

// A front's path to one gauge: with the weights, all that front_error_s() reads.
struct FrontPath {
  // 1: the record's aliasing of the front counted (a point-sampled record); 0: not.
  double aliasing = 0;
  double gauge_w = 0;  // the gauge's place between the element centres around it (of the pitch)
  struct Bar {
    double x;  // the distance the front travels in the bar (0 on the gauge's own bar: not crossed)
    double courant, element_length_m, wave_speed_m_s, time_step_s;
    bool gauge;  // the gauge's own bar
  };
  std::vector<Bar> bars;  // in chain order: those crossed (x > 0), and the gauge's own
};

// (1/π) ∫ e^{−ω²Δs²}/(1 + ω²τ²) |F H − 1|²/ω² dω + the aliasing (the model's I / A²) for the
// front's path `p`, `f` the weights of its record. `give_up`: once the integral below the cut-off
// passes it (checked every 32 points), return what it has summed with *gave_up set (the caller's
// bound then shows the mesh misses its target). Remembered by every number it reads from the
// second time a path is asked for (a few thousand paths at most, shared by every thread): the very
// double integrating it again gives.
double front_error_s(const FrontPath& p, const FrequencyWeights& f, double give_up, bool* gave_up);

// A lower bound on front_error_s: the frequencies above the path's lowest cut-off, which no mesh
// carries (|F H − 1| = 1), and the aliasing, without the integral below the cut-off.
double front_error_floor_s(const FrontPath& p, const FrequencyWeights& f);

// Forgets the remembered integrals and weights (the next choice is made afresh).
void forget_front_errors();

}  // namespace shpb
