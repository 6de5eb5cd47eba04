#pragma once
// Recorders: gauges, specimen truth, interface force/gap, energy and the x–t field, each sampled
// from its bar's (or interface's) own instants and interpolated linearly in time onto the output
// grid (docs/outputs.md). Bars call on_bar_instant between force assembly and advance (the
// full-step velocity is known there); interfaces call on_interface_solve after each solve.
// With a tolerance (model/scene.hpp gauges_filtered) the gauges are recorded at
// kGaugeOversampling × the sample rate and seen through the record's Gaussian before they are
// sampled (core/record_filter.hpp), as a digitiser's anti-alias filter does.
#include <span>
#include <string>
#include <vector>

#include "model/scene.hpp"
#include "solver/chain.hpp"
#include "solver/simulation.hpp"

namespace shpb {

// Values known at increasing instants τ, linearly interpolated onto τ_k = τ_0 + k·Δ, k < count.
class GridSampler {
 public:
  GridSampler() = default;
  GridSampler(double tau0, double spacing, long count, int width);
  double next_tau() const { return tau0_ + filled_ * spacing_; }
  bool done() const { return filled_ >= count_; }
  // True if the instant τ_next is at or after the next grid time (so τ_n and τ_next bracket it).
  bool wants(double tau_next) const { return !done() && next_tau() <= tau_next; }
  void push(double tau, const double* values);
  long filled() const { return filled_; }
  int width() const { return width_; }
  double at(long k, int c) const { return data_[k * width_ + c]; }
  // Column c at the first n grid points (n ≤ filled()).
  std::vector<double> column(int c, long n) const;
  // The filled grid points row after row: a sampler of width 1's column, without a copy.
  std::span<const double> rows() const {
    return {data_.data(), static_cast<std::size_t>(filled_ * width_)};
  }

 private:
  double tau0_ = 0, spacing_ = 1;
  long count_ = 0, filled_ = 0;
  int width_ = 0;
  bool has_prev_ = false;
  double prev_tau_ = 0;
  std::vector<double> prev_;
  // Row by row, as the solve writes them. Zero-filled: a fill writes whole cache lines, where left
  // uninitialised the solve's first writes each fetched theirs (measured slower:
  // docs/validation.md).
  std::vector<double> data_;
};

class ChainRecorders {
 public:
  ChainRecorders(const Scene& scene, const Chain& chain, const ChainDiscretization& d,
                 const SimulationOptions& options);

  // Bar i is at instant τ_n (forces assembled, contact applied); τ_next = τ_n + Δt_i.
  void on_bar_instant(const Chain& chain, std::size_t i, double tau_n, double tau_next);
  // Interface k was solved at τ; it is solved next at τ_next.
  void on_interface_solve(const Chain& chain, std::size_t k, double tau, double tau_next);

  // Energy grid points complete in every recorder, and the total energy at one of them.
  long energy_complete() const;
  double energy_total(long k) const;
  double energy_strain(long k) const;  // the bars' and end segments' strain energy alone
  double energy_grid_tau(long k) const { return energy_tau0_ + k * energy_spacing_; }

  // Fills the time series of `result` up to (and including) simulation time `until_s`, each
  // ending before its first row with a non-finite value (an unstable run's tail), the field too.
  // Moves the recorded field into `result`: called once, at the end of the run.
  void finish(const Chain& chain, double until_s, SimulationResult& result);

 private:
  struct GaugeProbe {
    std::size_t column;
    int element;    // left element of the interpolation pair
    double weight;  // of element + 1
  };
  struct BarRecorder {
    std::vector<GaugeProbe> gauges;
    GridSampler gauge_sampler;
    bool specimen = false;
    GridSampler specimen_sampler;
    GridSampler energy_sampler;
    std::vector<int> field_elements;
    std::size_t field_offset = 0;  // first column of this bar in the field grid
    long field_next = 0;           // next field time to record
  };
  struct InterfaceRecorder {
    GridSampler sampler;         // force, gap
    GridSampler energy_sampler;  // link energy, contact dissipation, end segment's kinetic, strain
  };

  double sample_spacing_s_ = 0;
  int gauge_oversampling_ = 1;  // gauge grid points per sample
  long samples_ = 0;
  double energy_tau0_ = 0, energy_spacing_ = 0;
  long energy_samples_ = 0;
  std::vector<std::string> gauge_names_;
  std::vector<std::string> interface_names_;
  std::vector<BarRecorder> bars_;
  std::vector<InterfaceRecorder> interfaces_;
  bool record_field_ = false;
  std::vector<double> field_tau_;
  std::vector<double> field_x_;
  std::vector<double> field_stress_;
};

}  // namespace shpb
