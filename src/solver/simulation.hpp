#pragma once
// The simulator's library API: run a scene in memory, then (optionally) write the files of
// docs/outputs.md. `shpb simulate`, `shpb compare`, `shpb study` and the processing tests call
// these two functions; the signatures are kept stable.
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/time_series.hpp"
#include "model/discretization.hpp"
#include "model/scene.hpp"

namespace shpb {

struct SimulationOptions {
  bool full_model = false;               // update every node from the start (no causal economy)
  std::function<void(double)> progress;  // fraction of the duration done, called ~100 times
  std::function<bool()> cancel;          // polled in the main loop; true → throws Interrupted
  bool record_field = true;              // field.csv grid
  int field_times = 200;                 // rows of the x–t grid
  int field_points = 400;                // columns (element centres along the chain)
  bool subcycle = true;                  // a lone fast bar steps in a tight loop (scheduler.hpp)
  bool adaptive_step = true;  // finite-strain bars step from their shortest element (step_control)
  bool skip_at_rest = true;   // a lone bar at rest skips its no-op instants (scheduler.hpp rule 10)
  // An asynchronous run that loses its energy is run again with end segments at a law specimen's
  // faces, else at global steps (simulate()); off where the methods themselves are measured.
  bool stabilize = true;
  // Told what a repeat does and why before it runs (its progress starts again from 0).
  std::function<void(const std::string&)> repeating;
};

// Stress along the chain on a coarse x–t grid (the wave diagram): stress_Pa[t * x_m.size() + x].
struct FieldGrid {
  std::vector<double> time_s;
  std::vector<double> x_m;  // chain coordinate of element centres (striker's left end = 0)
  std::vector<double> stress_Pa;
};

struct BarStatistics {
  std::string name;
  int elements = 0;
  int simulated_elements = 0;  // fewer if the causal economy cut the bar's far end
  double time_step_s = 0;
  long steps = 0;
  double courant = 0;
  long long node_updates = 0;
  long long node_updates_full_model = 0;
  double final_velocity_m_s = 0;  // momentum / mass at the end of the run
};

struct InterfaceStatistics {
  std::string name;  // "<left>-<right>"
  std::string method;
  long activations = 0;  // contact closings
  long releases = 0;     // contact openings
  // After the unloading, the first release after the loading peak (docs/methods.md §3.7): its
  // instant [s] (NaN if the interface never opened after its peak), the closings after it, the
  // meetings among them (closings after the faces were open longer than meeting_separation_s,
  // the shorter neighbour's elastic transit L/c₀) and the largest contact force after it over the
  // loading peak peak_force_N (NaN if never unloaded).
  double unloading_s = 0;
  long closings_after_unloading = 0;
  long meetings_after_unloading = 0;
  double meeting_separation_s = 0;
  double peak_force_N = 0;
  double force_after_unloading_share = 0;
  // An end segment at this tie (solver/end_segment.hpp): the bar whose end elements step on the
  // other bar's clock, and how many; empty and 0 without one.
  std::string segment_bar;
  int segment_elements = 0;
  // The run's time it started at: 0 from the start, else when a law specimen's face was unloaded.
  double segment_from_s = 0;
};

struct SimulationResult {
  ChainDiscretization discretization;
  TimeSeries gauges;      // one strain column per gauge (tension positive), named by the gauge
  TimeSeries interfaces;  // "<left>-<right>_force_N" (compression positive), "<left>-<right>_gap_m"
  // strain, strain_rate_1_s, stress_Pa, front_stress_Pa, back_stress_Pa (engineering: force over
  // the initial area), true_strain (−ln(1 − strain)), true_stress_Pa (force over current area)
  TimeSeries specimen;
  TimeSeries energy;  // kinetic_J, strain_J, contact_J, dissipated_J, total_J
  FieldGrid field;
  std::vector<BarStatistics> bars;
  std::vector<InterfaceStatistics> interface_statistics;
  long long node_updates = 0;
  long long node_updates_full_model = 0;
  double wall_time_s = 0;   // the solve alone
  double call_time_s = 0;   // the whole simulate() call: set-up, solve, records, statistics
  double energy_error = 0;  // max |total − initial| / initial
  double max_penetration_m = 0;
  double max_penetration_elements = 0;  // over the smaller neighbouring element of its interface
  bool stable = true;
  std::string failure;                 // where and when, if not stable
  bool beyond_planned_strain = false;  // failed: an element shorter than its step was planned for
  std::vector<std::string> warnings;   // physically implausible but computed (plausibility checks)
};

// Runs the scene (already validated by read_scene). Never throws on instability: the result
// says stable = false and holds what was computed up to then. Throws Interrupted if cancelled.
SimulationResult simulate(const Scene& scene, const SimulationOptions& options = {});

// Writes gauges.csv, interfaces.csv, specimen.csv (if the scene has a specimen), energy.csv,
// field.csv (long format: time_s,x_m,stress_Pa) and summary.json into `dir`.
void write_simulation_outputs(const SimulationResult& result, const Scene& scene,
                              const std::filesystem::path& dir);
// summary.json's content.
nlohmann::ordered_json simulation_summary(const SimulationResult& result, const Scene& scene);

}  // namespace shpb
