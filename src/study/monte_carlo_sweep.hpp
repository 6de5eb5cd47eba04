#pragma once
// `shpb study --sweep monte-carlo --distributions FILE`: what a planned test will show given what
// is uncertain about it (docs/commands.md, docs/methods.md §10). FILE gives distributions of scene
// values (striker velocity, law parameters, friction, specimen size, bar constants); the plan
// draws every run's values once (seeded), so a run is a scene with its values set, simulated and
// reduced as `process --signals` reduces a simulated test. The merge gives the 2.5 / 50 / 97.5 %
// bands of every gauge and of the processed curve and each quantity's spread (the band and
// statistics rules of analysis/monte_carlo.hpp).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "core/json_value.hpp"
#include "core/time_series.hpp"
#include "core/units.hpp"
#include "model/scene.hpp"

namespace shpb {

// 200 draws: a band edge (2.5 or 97.5 %) is then an order statistic whose probability level has
// a standard error √(p(1−p)/N) = 1.1 %, about a quarter of a normal band's half-width from one
// seed to the next; JCGM 101 §7.2 asks N ≫ 1/(1−p) = 20. 200 classic simulations take ~10 s.
inline constexpr std::size_t kDefaultMonteCarloDraws = 200;

enum class DistributionKind { kNormal, kUniform };

// One scene value drawn: normal (mean, standard deviation) or uniform on [low, high]; SI.
struct Distribution {
  std::string key;   // "<bar>.<quantity>" or "contact.friction" (docs/scene-format.md)
  std::string path;  // JSON path in the distributions file (messages)
  DistributionKind kind = DistributionKind::kNormal;
  double nominal = 0;                       // the scene's value
  double mean = 0, standard_deviation = 0;  // normal
  double low = 0, high = 0;                 // uniform
  Dimension dimension = Dimension::kDimensionless;
};

// The values FILE lets vary on `scene`, in the file's order; InputError naming the file, the JSON
// path, the value and what is expected (exit 2).
std::vector<Distribution> read_distributions(const std::filesystem::path& file, const Scene& scene);

// One run: the nominal scene (values empty) or draw `draw` with one value per distribution.
struct MonteCarloJob {
  bool nominal = false;
  std::vector<double> values;
};
// The nominal run, then `draws` draws from `seed` (each distribution drawn in turn, draw after
// draw, in one sequence: the plan does not depend on how it is run).
std::vector<MonteCarloJob> monte_carlo_jobs(const std::vector<Distribution>& distributions,
                                            std::size_t draws, std::uint64_t seed);

// What a run leaves for the merge: its gauges, and its reduced curve (primary strain, 3-wave and
// 1-wave stress, primary strain rate, up to the end of loading) with its headline figures.
struct MonteCarloJobResult {
  bool ok = false;
  std::string failure;  // why the run gives nothing (a drawn value out of range, unstable, …)
  double wall_time_s = 0;
  TimeSeries gauges;
  bool reduced = false;
  std::string reduction_failure;
  std::vector<double> strain, stress3, stress1, rate;
  std::vector<std::pair<std::string, double>> figures;
};

MonteCarloJobResult run_monte_carlo_job(const Scene& scene,
                                        const std::vector<Distribution>& distributions,
                                        const MonteCarloJob& job,
                                        const std::function<bool()>& cancel = {});

nlohmann::ordered_json distribution_json(const Distribution& d);
// A distribution as distribution_json wrote it (a study plan); InputError naming its JSON path.
Distribution distribution_from(const JsonValue& v);
nlohmann::ordered_json job_result_json(const MonteCarloJobResult& r);
MonteCarloJobResult job_result_from(const nlohmann::json& j);

}  // namespace shpb
