#pragma once
// The whole reduction of one test (docs/outputs.md `process`): incident pulse found on the incident
// gauge, the three pulses moved to the specimen faces (Pochhammer–Chree or pure delay), cut to a
// common window, reduced (reduction.hpp) and summarised. Library function, reused by `compare`.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "analysis/gauge_signals.hpp"
#include "analysis/kolsky_setup.hpp"
#include "analysis/reduction.hpp"
#include "analysis/specimen_corrections.hpp"
#include "dispersion/propagation.hpp"
#include "model/scene.hpp"

namespace shpb {

// The curve ends at the strain maximum or, earlier, where the 1-wave stress falls below half the
// peak it had reached and stays there (fracture, or the end of the pulse), docs/methods.md §6.
inline constexpr double kDefaultLoadDrop = 0.5;

// A load drop that ends the curve with less than 95 % of the record's strain maximum reached is
// said: the strain gained after the drop at the end of an ordinary pulse (its unloading ramp,
// while the reflected pulse dies out) is a few percent of the total.
inline constexpr double kLoadDropStrainShortfall = 0.05;

struct ProcessingOptions {
  DispersionSpec dispersion;            // correction on/off, amplitude factors, cut-off
  PulseWindows windows;                 // manual windows (gauge clocks) override detection
  std::string scene_file;               // named in error messages
  double load_drop = kDefaultLoadDrop;  // the curve ends where σ falls by this fraction; 0: off
  // A tension test (split Hopkinson tension bar): the signals are given negated, so the
  // reduction's "compression positive" reads "tension positive"; named in warnings.
  bool tension = false;
  Alignment align = Alignment::kGeometry;                   // measurement.align
  PrimaryReduction primary = PrimaryReduction::kThreeWave;  // measurement.primary
  std::optional<RateWindow> rate_window;                    // measurement.rate_window
  // Further time shifts of the reflected and transmitted pulses at the faces (a Monte Carlo
  // draw's trigger delay and window starts, analysis/uncertainty.hpp); 0 for a plain reduction.
  double reflected_shift_s = 0, transmitted_shift_s = 0;
  // Whether the specimen is in equilibrium for its peak (reduction_checks.hpp, settle_peak_stress):
  // unset, as the test's own equilibrium decides; a Monte Carlo draw takes its nominal's choice, so
  // that every draw reads its peak by the nominal's rule (a draw whose equilibrium fraction
  // crosses the rule's bound was read at the unloading edge's transient: the classic test, 5 of
  // 200 draws at about 2 x the peak, u 15 % for a 95 % interval of ±5 %).
  std::optional<bool> peak_in_equilibrium;
  // The specimen corrections (docs/methods.md §8), applied to the curve before its peaks are read,
  // and the specimen they need (analysis/test_processing.hpp sets both from the scene).
  SpecimenCorrections corrections;
  SpecimenProperties specimen;
  // Shared by repeated reductions (null: each reduction solves its own tables and plans).
  DispersionTableCache* tables = nullptr;
  FftPlans* plans = nullptr;
};

struct WindowReport {
  std::string gauge;
  double start_s = 0, end_s = 0;  // on the gauge's own clock
  bool detected = false;          // false: from the scene's `windows`
};

// Equilibrium over the loaded time (mean force ≥ 20 % of its peak), times on the faces' clock.
struct Equilibrium {
  std::optional<std::pair<double, double>> loaded_s;   // first and last loaded sample
  double fraction = 0;                                 // of the loaded samples with R ≤ 5 %
  std::optional<std::pair<double, double>> longest_s;  // longest run with R ≤ 5 %
  std::optional<double> holds_from_s;  // start of the run that lasts until unloading
  // The first loaded sample with R ≤ 5 %: the ring-up has passed — the front face's transient,
  // the reflected front against the incident one (tensile in a compression test), and its
  // overshoot — and the face forces first agree (docs/methods.md §6).
  std::optional<double> first_s;
  // Largest 3-wave stress over the loaded samples with R ≤ 5 %: where the two face forces agree,
  // the specimen's stress; null when no loaded sample is in equilibrium.
  std::optional<double> peak_3wave_Pa;
};

struct ProcessingResult {
  std::vector<double> time_s;  // at the specimen faces, on the signals' clock
  std::vector<double> incident, reflected, transmitted;  // strains at the faces, tension positive
  Curve curve;
  WindowReport incident_window, reflected_window, transmitted_window;
  double face_start_s = 0, face_end_s = 0;
  double shift_incident_s = 0, shift_reflected_s = 0, shift_transmitted_s = 0;
  std::optional<double> reflected_onset_offset_s;    // detected − expected (alignment check)
  std::optional<double> transmitted_onset_offset_s;  // detected − expected (alignment check)
  double transmitted_rise_s = 0;                     // onset to half peak of the transmitted front
  double reflected_rise_s = 0;                       // … and of the reflected front
  double incident_rise_s = 0;                        // … and of the incident front
  bool alignment_suspect = false;  // an onset is off: a gauge position or wave speed is wrong
  // The reflected onset is off by more than a mistiming of the incident side would leave the
  // transmitted onset on time: the reflected pulse's own shape (its foot), not a mistiming.
  bool reflected_offset_is_shape = false;
  bool reflected_at_onset = false, transmitted_at_onset = false;  // align "onsets" applied
  // How long the incident pulse still passes its gauge after the reflected pulse arrives there
  // (0: they are apart); one gauge records their sum.
  double incident_overlap_s = 0;
  // The incident pulse's length on its gauge when its reflection arrives before it has passed
  // (the detected window ends there at the latest: from then on the gauge records their sum),
  // from where the reflected pulse ends: one pulse length after its arrival; 0 when apart.
  double incident_length_s = 0;
  // When the transmitter's far end reflects the transmitted pulse back to its gauge inside the
  // window the curve uses: that instant on the faces' clock.
  std::optional<double> transmitted_echo_s;
  // Largest change of the 3-wave stress over the loading, as a fraction of the 1-wave peak, that
  // moving the reflected pulse by its onset offset makes (docs/methods.md §6); null without one.
  std::optional<double> reflected_offset_stress_error;
  double area_ratio = 0;                     // incident bar over specimen cross-section
  std::vector<std::string> inverted_gauges;  // first pulse of the other polarity than the test's
  double incident_plateau_strain = 0;        // compressive strain magnitude at the face
  double inferred_striker_velocity_m_s = 0;
  double plateau_strain_rate_1_s = 0;       // level of the top part of the rate (plateau_level)
  bool strain_rate_has_plateau = false;     // the rate stays at that level long enough to quote it
  double strain_rate_plateau_fraction = 0;  // longest run within ±10 % / samples with rate > 0
  double mean_strain_rate_1_s = 0;          // over the loading, where the rate is positive
  std::optional<double> window_strain_rate_1_s;  // mean over options.rate_window
  std::size_t loading_end = 0;  // curve samples [0, loading_end) are the loading; the rest is cut
  std::string loading_end_how;
  double record_max_strain = 0;    // of the primary strain over the whole face window
  bool loading_cut_short = false;  // a load drop ended the curve short of record_max_strain
  // The primary reduction's figures over the loading (strain rate, peak stress, strain) ...
  PrimaryReduction primary = PrimaryReduction::kThreeWave;
  double peak_stress_Pa = 0;
  double max_strain = 0;
  // ... and both reductions' (3-wave: 3-wave stress and strain; 1-wave: 1-wave stress and
  // reflected-pulse strain).
  double peak_stress_3wave_Pa = 0, max_strain_3wave = 0;
  double peak_stress_1wave_Pa = 0, max_strain_1wave = 0;
  // The peak stresses are read from the line fitted over the half period the bars resolve
  // (processing.cpp, summarize_loading), not from a sample, which a record's noise lifts. The
  // 3-wave stress's largest sample over the whole loading, its ring-up and unloading fronts
  // included (peak_stress_3wave_Pa is read in equilibrium once the specimen reaches it).
  double peak_stress_3wave_over_loading_Pa = 0;
  // The specimen is in equilibrium for its peak (settle_peak_stress): the headline peak is the
  // 1-wave one, peak_stress_3wave_Pa read over the samples in equilibrium.
  bool peak_in_equilibrium = false;
  Equilibrium equilibrium;
  std::optional<double> time_to_equilibrium_s;  // holds_from_s − start of the face window
  CorrectionReport corrections_removed;         // what options.corrections took out
  double cutoff_Hz = 0;                         // 0 without dispersion correction
  std::vector<std::string> warnings;
};

// The headline peak stress (ProcessingResult::peak_stress_Pa) and the reduction it comes from:
// the 1-wave reduction's (the transmitted face's stress P2/A_s, largest over the loading) when it
// is primary or when the specimen is in equilibrium for its peak. There the two faces' stresses
// agree, and the back face's peak is read over every sample of the loading, where the 3-wave
// stress's is read over the samples with R ≤ 5 %: a set that a lab's errors shrink, whose largest
// stress is then biased low and spread into a long lower tail by the Monte Carlo draws
// (docs/methods.md §10). Otherwise the 3-wave reduction's over the whole loading, its line fit's
// as the 1-wave peak's (said).
struct HeadlinePeak {
  double stress_Pa = 0;
  PrimaryReduction reduction = PrimaryReduction::kThreeWave;
};
inline HeadlinePeak headline_peak_stress(const ProcessingResult& r) {
  if (r.primary == PrimaryReduction::kOneWave || r.peak_in_equilibrium)
    return {r.peak_stress_1wave_Pa, PrimaryReduction::kOneWave};
  return {r.peak_stress_3wave_Pa, PrimaryReduction::kThreeWave};
}

// The largest strain of `strain` (on the faces' clock `t`) before the specimen first comes into
// equilibrium (Equilibrium::first_s): the ring-up's. A stress read at a strain it reaches is the
// face forces' transient, not the specimen's, and a flow stress at a strain no greater is not
// quoted (summary.json's uncertainty figures, campaign.csv); without equilibrium, 0 (the warning
// of settle_peak_stress says so instead).
double ring_up_strain(const std::vector<double>& t, const std::vector<double>& strain,
                      const std::optional<double>& first_s);

// Equilibrium holds where R ≤ 5 % (a common criterion, e.g. Gray 2000) while the mean force is
// above 20 % of its peak; it is reached where it then holds until unloading.
inline constexpr double kEquilibriumThreshold = 0.05;

ProcessingResult process_signals(const GaugeSignals& signals, const KolskySetup& setup,
                                 const ProcessingOptions& options);

}  // namespace shpb
