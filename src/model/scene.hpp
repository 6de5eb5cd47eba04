#pragma once
// The scene: one JSON file describing a bar set-up (docs/scene-format.md), read into plain structs
// with defaults. Validation happens once, in read_scene(); nothing downstream re-checks.
#include <array>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/enum_names.hpp"
#include "core/signal_spec.hpp"
#include "model/material.hpp"

namespace shpb {

struct GaugeSpec {
  std::string name;
  double position_m = 0;  // from the bar's left end
  // As given (`distance_to_specimen`): to the specimen face the pulse reaches; position_m is
  // resolved from it once the specimen is known.
  std::optional<double> distance_to_specimen_m;
  bool operator==(const GaugeSpec&) const = default;
};

struct BarSpec {
  std::string name;
  MaterialSpec material;
  double length_m = 0;
  double area_m2 = 0;       // from `area`, or π d²/4 from `diameter`
  double diameter_m = 0;    // given, or the equivalent circular diameter of `area`
  bool area_given = false;  // the scene gives `area` (named in messages), not `diameter`
  double velocity_m_s = 0;  // initial rigid velocity, + to the right
  int elements = 0;         // 0: chosen automatically (see model/mesh.hpp)
  double gap_m = 0;         // initial gap to the next bar on the right
  std::vector<GaugeSpec> gauges;
  bool inertia = false;      // radial inertia of a flowing specimen (material-law bars only)
  bool has_material = true;  // false: the specimen of a scene only processed (no `material`)

  double impedance_kg_s() const {
    return material.density_kg_m3 * material.wave_speed_m_s() * area_m2;
  }
  bool operator==(const BarSpec&) const = default;
};

enum class ContactMethod { kPenalty, kBipenalty, kLocalizedBipenalty, kBonded };
enum class Stepping { kAsynchronous, kGlobal };
inline constexpr EnumName<ContactMethod> kContactMethodNames[] = {
    {"penalty", ContactMethod::kPenalty},
    {"bipenalty", ContactMethod::kBipenalty},
    {"localized-bipenalty", ContactMethod::kLocalizedBipenalty},
    {"bonded", ContactMethod::kBonded}};
inline constexpr EnumName<Stepping> kSteppingNames[] = {{"asynchronous", Stepping::kAsynchronous},
                                                        {"global", Stepping::kGlobal}};
// simulation.kinematics: the names of SimulationSpec::finite_strain.
inline constexpr EnumName<bool> kKinematicsNames[] = {{"finite", true}, {"small", false}};

// Penalty parameters of one interface. Unset values are derived from the neighbouring elements
// (docs/methods.md §2): ε_s as a multiple of the stiffer neighbour's EA/h, R as a fraction of
// R_crit = (2c/h)² of each neighbour.
struct PenaltyParams {
  std::optional<double> stiffness_factor;  // ε_s / (EA/h)
  std::optional<double> stiffness_N_m;     // ε_s given directly
  // A compliant contact given by the e-folding rise time τ of the force when two long bars meet:
  // F(t) = F_∞(1 − e^{−t/τ}) with 1/τ = ε_s (1/Z_l + 1/Z_r), so ε_s = Z_l Z_r / ((Z_l + Z_r) τ).
  // Models an imperfect impact face (flatness, tilt) that makes a measured front rise slower than
  // Pochhammer–Chree dispersion alone. At most one of stiffness_factor, stiffness, rise_time.
  std::optional<double> rise_time_s;
  std::optional<double> mass_ratio;  // R / R_crit (bipenalty methods)
  // Set in code only (study stability probes, never read from JSON): plain and node-to-node
  // bipenalty links act in tension too, so the contact never opens and its linear stability
  // limit can be measured.
  bool tied = false;
  bool operator==(const PenaltyParams&) const = default;
};

struct InterfaceOverride {
  std::size_t left_bar = 0;  // the interface between bars[left_bar] and bars[left_bar + 1]
  std::optional<ContactMethod> method;
  PenaltyParams penalty;
  std::optional<double> friction;  // Coulomb μ of the faces (docs/methods.md §8)
  bool operator==(const InterfaceOverride&) const = default;
};

struct ContactSpec {
  ContactMethod method = ContactMethod::kLocalizedBipenalty;
  PenaltyParams penalty;
  std::vector<InterfaceOverride> interfaces;
  double friction = 0;  // Coulomb μ on every interface unless overridden
  bool operator==(const ContactSpec&) const = default;
};

// Method and penalty parameters of the interface between bars[k] and bars[k + 1]: the scene-wide
// values with that interface's override applied (a stiffness given in the override, in any of its
// three forms, replaces the scene-wide one).
ContactMethod interface_method(const ContactSpec& contact, std::size_t k);
PenaltyParams interface_penalty(const ContactSpec& contact, std::size_t k);
double interface_friction(const ContactSpec& contact, std::size_t k);
// Bar i of a chain of `bars` is squeezed between two others (a specimen or a pulse shaper): face
// friction and radial inertia act on it (docs/methods.md §8.2).
inline bool squeezed_bar(std::size_t i, std::size_t bars) { return i > 0 && i + 1 < bars; }

struct SimulationSpec {
  std::optional<double> duration_s;  // default: the transmitted pulse has passed the last gauge
  double sample_rate_Hz = 10e6;
  Stepping stepping = Stepping::kAsynchronous;
  std::optional<double> courant;  // default chosen by the solver (close to 1, docs/methods.md §1)
  // "kinematics": "finite" (default) or "small": finite strain for material-law bars
  // (solver/bar.hpp); elastic bars are small strain either way.
  bool finite_strain = true;
  // Largest compressive engineering strain a material-law bar may reach with finite strain: its
  // stable step is planned for elements that short (model/discretization.hpp).
  std::optional<double> max_strain;
  // The gauge error the user accepts (a fraction; "1 %" in the scene, `--tolerance`): the bars
  // without an `elements` of their own are meshed as coarsely as the error model predicts meets
  // it (model/mesh_choice.hpp). Unset in the scene and on the command line: kDefaultTolerance
  // (model/scene_validation.hpp resolve_scene), with tolerance_is_default set.
  std::optional<double> tolerance;
  bool tolerance_is_default = false;
  // Why resolve_scene() kept the automatic meshes instead of the default tolerance (empty where
  // it applied, or where a tolerance was given or not asked for): `shpb validate` says it.
  std::string tolerance_withheld;
  // Wall time of the error model's mesh choice for this run (resolve_scene), 0 without one: a run
  // pays it before its solve (summary.json mesh_choice_time_s, run_time_s).
  double mesh_choice_time_s = 0;
  bool operator==(const SimulationSpec&) const = default;
};

// The gauge error a run accepts when neither the scene nor --tolerance gives one: the cheapest
// meshes the error model predicts meet it (docs/methods.md §1.1 "The default"). At 3.5 % the
// classic experiment is meshed at 1/4 of the automatic meshes' node updates and is measured at
// 2.53 % against its converged reference where the automatic meshes were at 2.79 %.
inline constexpr double kDefaultTolerance = 0.035;

// Whether a run records its gauges through the record's Gaussian before sampling them (a
// digitiser's anti-alias filter, core/record_filter.hpp) rather than as point samples: with a
// tolerance, which is measured through that Gaussian (docs/methods.md §1.1), so a sharp front's
// aliasing is not counted against it.
inline bool gauges_filtered(const SimulationSpec& s) { return s.tolerance.has_value(); }

// ---- measured signals -------------------------------------------------------------------------

// Wheatstone bridge: ε = k·V / (GF · gain · V_ex) with k = 4/arms (quarter 4, half 2, full 1).
struct BridgeSpec {
  int arms = 1;
  double gauge_factor = 2.0;
  double excitation_V = 10.0;
  double gain = 1.0;
  bool operator==(const BridgeSpec&) const = default;
};

struct ChannelSpec {
  std::string gauge;           // gauge name in the scene; two channels of one gauge are averaged
  std::filesystem::path file;  // empty: the measurement's file
  ColumnRef column;
  SignalUnit unit = SignalUnit::kStrain;
  std::optional<BridgeSpec> bridge;  // required for volts, or
  std::optional<double> scale;       // strain per volt (a calibration factor) instead
  bool invert = false;
  // The digitizer's (or amplifier's) full scale [low, high] in the column's unit, if stated: a
  // sample there is a clip, and a record inside it is not clipped (docs/methods.md §9).
  std::optional<std::array<double, 2>> range;
  // From a calibration of its gauge (model/calibration.hpp), never from the channel's own keys:
  // the recorded strain over the true strain, and the time by which the record lags the reference
  // channel. The signal is divided by the gain and moved earlier by the delay when it is read.
  double calibrated_gain = 1.0;
  double calibrated_delay_s = 0.0;
  bool operator==(const ChannelSpec&) const = default;
};

// measurement.dispersion.correction: the names of DispersionSpec::correction.
inline constexpr EnumName<bool> kCorrectionNames[] = {{"pochhammer-chree", true}, {"none", false}};

struct DispersionSpec {
  bool correction = true;              // "pochhammer-chree" | "none"
  bool amplitude_factors = false;      // Tyas–Pope m1, m2
  std::optional<double> cutoff_Hz;     // default: f·a/c0 = 0.2619 (d/Λ = 0.6), smooth roll-off
  std::optional<double> cutoff_fa_c0;  // or the cut-off as f·a/c0 (dimensionless)
  bool operator==(const DispersionSpec&) const = default;
};

struct TimeWindow {
  double start_s = 0;
  double end_s = 0;
  bool operator==(const TimeWindow&) const = default;
};
struct PulseWindows {  // manual windows on the signals' own clock override detection
  std::optional<TimeWindow> incident, reflected, transmitted;
  bool operator==(const PulseWindows&) const = default;
};

// measurement.align: how the reflected and transmitted pulses are put on the incident pulse's clock
// at the specimen faces (docs/methods.md §6): by the gauge distances over c0, or each at its
// detected onset.
enum class Alignment { kGeometry, kOnsets };
inline constexpr EnumName<Alignment> kAlignmentNames[] = {{"geometry", Alignment::kGeometry},
                                                          {"onsets", Alignment::kOnsets}};

// measurement.primary: the reduction `curve.csv`, `summary.json` and the report lead with: the
// 3-wave average, or the 1-wave stress (transmitted face) against the reflected-pulse strain.
enum class PrimaryReduction { kThreeWave, kOneWave };
inline constexpr EnumName<PrimaryReduction> kPrimaryNames[] = {
    {"3-wave", PrimaryReduction::kThreeWave}, {"1-wave", PrimaryReduction::kOneWave}};

// measurement.rate_window: the range over which the quoted mean strain rate is taken, in the
// primary reduction's engineering strain or in time at the faces (curve.csv's time_s).
struct RateWindow {
  bool by_strain = true;
  double from = 0, to = 0;
  bool operator==(const RateWindow&) const = default;
};

// Corrections `process` applies to the 3-wave curve (analysis/specimen_corrections.hpp).
struct CorrectionsSpec {
  std::optional<double> friction;  // Coulomb μ of the specimen faces
  bool inertia = false;
  bool operator==(const CorrectionsSpec&) const = default;
};

// measurement.uncertainty (docs/scene-format.md): standard uncertainties of what a lab knows it
// does not know, propagated by `process` by Monte Carlo (analysis/uncertainty.hpp).
struct StandardUncertainty {
  double value = 0;  // SI, or a fraction of the nominal value when `relative` ("%")
  bool relative = false;
  std::string path;  // where the scene gives it (named in messages and in the contributions)
  bool operator==(const StandardUncertainty&) const = default;
};
struct BarUncertainty {
  std::size_t bar = 0;  // index into Scene::bars
  std::optional<StandardUncertainty> youngs_modulus, density, wave_speed, poisson_ratio, diameter,
      length;
  bool operator==(const BarUncertainty&) const = default;
};
struct UncertaintySpec {
  // Of every bridge channel, each drawn on its own (every channel has its own gauge and bridge),
  // or once for every channel when named in `shared` (one gauge lot, one supply, one amplifier).
  std::optional<StandardUncertainty> gauge_factor, excitation, gain;
  std::vector<std::string> shared;                    // of "gauge_factor", "excitation", "gain"
  std::optional<StandardUncertainty> gauge_position;  // of each processed gauge along its bar
  std::optional<StandardUncertainty> trigger_delay;   // transmitted channel against incident
  std::optional<StandardUncertainty> window_start;    // reflected/transmitted starts, samples
  std::optional<StandardUncertainty> dispersion_cutoff;
  std::optional<StandardUncertainty> friction;  // μ of measurement.corrections.friction
  std::vector<BarUncertainty> bars;
  // Each gauge record's own noise, white with the σ of its rest (estimate_baseline), drawn anew
  // for every draw (docs/methods.md §10); false: the draws reduce the record's samples as read.
  bool record_noise = true;
  bool operator==(const UncertaintySpec&) const = default;
};

struct MeasurementSpec {
  std::filesystem::path file;  // resolved relative to the scene
  SignalFormat format = SignalFormat::kAuto;
  ColumnRef time_column;                  // empty name and index: the format's own time base
  double time_unit_s = 1.0;               // seconds per unit of the time column
  TimeResampling time_resample;           // measurement.time.resample
  std::optional<SampleClock> time_clock;  // measurement.time.interval (or rate) and start
  std::vector<ChannelSpec> channels;
  DispersionSpec dispersion;
  PulseWindows windows;
  std::optional<double> striker_velocity_m_s;  // if known; else inferred
  CorrectionsSpec corrections;
  std::string time_unit = "s";  // as written (named in errors)
  std::optional<double>
      load_drop;         // curve end at this stress drop (fraction); 0: off; unset: default
  std::string sheet;     // .xlsx/.xls files: the sheet by name (empty: the first)
  bool tension = false;  // "test": "tension" (split Hopkinson tension bar)
  // The lab's calibrated reflected time of the incident bar: a pulse's round trip from the incident
  // gauge to the bar's specimen end and back, timed on the real bar (docs/scene-format.md).
  std::optional<double> reflected_time_s;
  Alignment align = Alignment::kGeometry;
  PrimaryReduction primary = PrimaryReduction::kThreeWave;
  std::optional<RateWindow> rate_window;
  std::optional<UncertaintySpec> uncertainty;
  bool operator==(const MeasurementSpec&) const = default;
};

// The scene's `plan` block (docs/scene-format.md#plan): what `shpb plan` may change in a set-up and
// within which bounds. Read and checked with the rest of the scene by every command that reads it
// (a scene is one file: a misspelt bound is refused by simulate as by plan); used by plan alone.

// A quantity the plan may vary within [lo, hi]; lo == hi fixes it.
struct PlanRange {
  double lo = 0, hi = 0;
  bool free() const { return hi > lo; }
  bool operator==(const PlanRange&) const = default;
};

// A pulse-shaper material the plan may use: as written (for the planned scene) and as read.
struct ShaperMaterial {
  std::string text;  // the scene's name or a path relative to the scene
  BarSpec bar;       // a shaper bar of this material (length and diameter set by the plan)
  bool operator==(const ShaperMaterial&) const = default;
};

struct PlanSpec {
  PlanRange striker_length;    // fixed at the scene's striker length unless given
  PlanRange striker_velocity;  // required
  std::optional<PlanRange> specimen_length;
  // A pulse shaper between the striker and the incident bar: the scene's own (bars[1] when the
  // incident bar is bars[2]), or one the plan may add.
  std::vector<ShaperMaterial> shaper_materials;  // empty: no shaper block
  PlanRange shaper_diameter, shaper_thickness;
  bool scene_has_shaper = false;
  bool operator==(const PlanSpec&) const = default;
};

struct Scene {
  std::string name;
  std::filesystem::path file;           // where it was read from (for messages and relative paths)
  std::vector<BarSpec> bars;            // left to right
  std::optional<std::size_t> specimen;  // index into bars
  ContactSpec contact;
  SimulationSpec simulation;
  std::optional<MeasurementSpec> measurement;
  std::vector<std::filesystem::path> material_files;  // the material files it read, once each
  // The calibration whose values replaced the nominal ones (top-level "calibration"), or empty.
  std::filesystem::path calibration_file;
  std::optional<PlanSpec> plan;  // the `plan` block, if the scene has one
  // The JSON text it was read from: what a scene written back starts from (model/scene_writer.hpp).
  std::string source_text;

  // Index of the first bar with a gauge left of the specimen / right of it, if any.
  std::optional<std::size_t> incident_bar() const;
  std::optional<std::size_t> transmitter_bar() const;
  bool operator==(const Scene&) const = default;
};

// Reads and validates a scene; throws InputError("<file>: <json path>: <value>: <constraint>").
Scene read_scene(const std::filesystem::path& file);
// The same from JSON text in memory (the Python module's Scene.from_dict): `file` names it in
// messages and anchors its relative paths, as if the text had been read from there.
Scene read_scene_text(const std::string& text, const std::filesystem::path& file);

// Why bar i may not have radial inertia on (`inertia`: true), empty when it may: the closed form of
// a Kolsky specimen that flows (a material law), squeezed between two others (the specimen or a
// pulse shaper). The scene reader's rule and the Python module's edit.
std::string radial_inertia_problem(const Scene& scene, std::size_t i);

std::string_view to_string(ContactMethod m);
std::string_view to_string(Stepping s);
std::string_view to_string(MaterialModel m);
// Parse enums; return std::nullopt for unknown text (callers report the error with context).
std::optional<ContactMethod> contact_method_from_string(std::string_view s);
std::optional<Stepping> stepping_from_string(std::string_view s);

}  // namespace shpb
