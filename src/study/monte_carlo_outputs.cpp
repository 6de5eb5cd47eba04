// The files of a Monte Carlo study (study/monte_carlo_outputs.hpp).
#include "study/monte_carlo_outputs.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "analysis/monte_carlo.hpp"
#include "analysis/uncertainty.hpp"
#include "core/checked_write.hpp"
#include "core/csv_writer.hpp"
#include "core/error.hpp"
#include "core/json_numbers.hpp"
#include "output_schema.hpp"
#include "version.hpp"

namespace shpb {
namespace {

using Json = nlohmann::ordered_json;

std::string column_name(const Distribution& d) {
  std::string unit(si_unit(d.dimension));
  std::replace(unit.begin(), unit.end(), '/', '_');
  return unit.empty() ? d.key : d.key + "_" + unit;
}

// The quantities of summary.json: each gauge's peak |strain|, then the reduction's figures (those
// of the nominal run); values[q][d] for draw d (NaN where a draw gives none).
struct Quantities {
  std::vector<std::string> names, units;
  std::vector<double> nominal;
  std::vector<std::vector<double>> values;
};

double peak_strain(const TimeSeries& g, std::size_t column) {
  double peak = 0;
  for (double v : g.values[column]) peak = std::max(peak, std::abs(v));
  return peak;
}

Quantities quantities(const std::vector<MonteCarloJobResult>& results) {
  Quantities q;
  const MonteCarloJobResult& n = results[0];
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t g = 0; g < n.gauges.columns.size(); ++g) {
    q.names.push_back(n.gauges.columns[g] + "_peak_strain");
    q.units.push_back("");
    q.nominal.push_back(peak_strain(n.gauges, g));
    std::vector<double> v(results.size() - 1, nan);
    for (std::size_t d = 1; d < results.size(); ++d)
      if (results[d].ok) v[d - 1] = peak_strain(results[d].gauges, g);
    q.values.push_back(v);
  }
  if (!n.reduced) return q;
  for (const auto& [name, value] : n.figures) {
    q.names.push_back(name);
    q.units.push_back(name.ends_with("_Pa")    ? "Pa"
                      : name.ends_with("_1_s") ? "1/s"
                      : name.ends_with("_m_s") ? "m/s"
                                               : "");
    q.nominal.push_back(value);
    std::vector<double> v(results.size() - 1, nan);
    for (std::size_t d = 1; d < results.size(); ++d)
      if (results[d].reduced)
        for (const auto& [dn, dv] : results[d].figures)
          if (dn == name) v[d - 1] = dv;
    q.values.push_back(v);
  }
  return q;
}

void write_draws(const std::vector<Distribution>& distributions,
                 const std::vector<MonteCarloJob>& jobs,
                 const std::vector<MonteCarloJobResult>& results,
                 const std::filesystem::path& file) {
  namespace k = schema::draws;  // the column names (src/core/output_schema.json)
  std::vector<std::string> header = {k::draw};
  for (const Distribution& d : distributions) header.push_back(column_name(d));
  header.insert(header.end(), {k::simulated, k::reduced, k::failure});
  CsvWriter csv(file, header);
  for (std::size_t r = 1; r < jobs.size(); ++r) {
    std::vector<std::string> cells = {std::to_string(r)};
    for (double v : jobs[r].values) cells.push_back(format_double(v));
    const MonteCarloJobResult& x = results[r];
    cells.push_back(x.ok ? "1" : "0");
    cells.push_back(x.reduced ? "1" : "0");
    cells.push_back(x.ok ? x.reduction_failure : x.failure);
    csv.row(cells);
  }
  csv.close();
}

// The gauges' bands at the nominal run's times (up to the shortest run's record).
void write_gauge_bands(const std::vector<MonteCarloJobResult>& results,
                       const std::vector<std::size_t>& good, const std::filesystem::path& file) {
  const TimeSeries& n = results[0].gauges;
  std::size_t rows = n.samples();
  for (std::size_t d : good) rows = std::min(rows, results[d].gauges.samples());
  std::vector<std::string> header = {schema::gauge_bands::time_s};
  std::vector<std::vector<double>> columns;
  for (std::size_t g = 0; g < n.columns.size(); ++g) {
    std::vector<const std::vector<double>*> draws;
    for (std::size_t d : good) draws.push_back(&results[d].gauges.values[g]);
    std::vector<double> band[3];
    quantile_bands(draws, rows, band);
    const std::string& c = n.columns[g];
    header.insert(header.end(), {c, c + "_p2.5", c + "_p50", c + "_p97.5"});
    columns.push_back(n.values[g]);
    for (auto& b : band) columns.push_back(std::move(b));
  }
  CsvWriter csv(file, header);
  for (std::size_t i = 0; i < rows; ++i) {
    std::vector<std::string> cells = {format_double(n.time_s[i])};
    for (const auto& c : columns) cells.push_back(format_double(c[i]));
    csv.row(cells);
  }
  csv.close();
}

// The processed curve's bands at the nominal curve's strains (process's band columns).
void write_curve_bands(const std::vector<MonteCarloJobResult>& results,
                       const std::vector<std::size_t>& reduced, const std::filesystem::path& file) {
  const MonteCarloJobResult& n = results[0];
  const std::size_t rows = n.strain.size();
  std::vector<CurveAtStrains> at;
  for (std::size_t d : reduced)
    at.push_back(curve_at_strains(results[d].strain, results[d].stress3, results[d].stress1,
                                  results[d].rate, results[d].strain.size(), n.strain, rows));
  UncertaintyResult u;
  auto band = [&](std::vector<double> CurveAtStrains::*field, std::vector<double>(&to)[3]) {
    std::vector<const std::vector<double>*> draws;
    for (const auto& a : at) draws.push_back(&(a.*field));
    quantile_bands(draws, rows, to);
  };
  band(&CurveAtStrains::stress3, u.stress_3wave);
  band(&CurveAtStrains::stress1, u.stress_1wave);
  band(&CurveAtStrains::rate, u.strain_rate);
  const auto bands = uncertainty_band_columns(u);
  namespace k = schema::curve_bands;  // the nominal columns, then the bands (as curve.csv's)
  std::vector<std::string> header = {k::strain, k::stress_3wave_Pa, k::stress_1wave_Pa,
                                     k::strain_rate_1_s};
  for (const auto& [name, column] : bands) header.push_back(name);
  CsvWriter csv(file, header);
  for (std::size_t i = 0; i < rows; ++i) {
    std::vector<std::string> cells = {format_double(n.strain[i]), format_double(n.stress3[i]),
                                      format_double(n.stress1[i]), format_double(n.rate[i])};
    for (const auto& [name, column] : bands) cells.push_back(format_field((*column)[i]));
    csv.row(cells);
  }
  csv.close();
}

}  // namespace

std::vector<std::string> write_monte_carlo(
    const Scene& scene, const std::vector<Distribution>& distributions, std::uint64_t seed,
    const std::vector<MonteCarloJob>& jobs, const std::vector<MonteCarloJobResult>& results,
    int threads, double wall_s, const std::filesystem::path& dir) {
  const MonteCarloJobResult& nominal = results.at(0);
  if (!nominal.ok)
    throw NumericalError("study monte-carlo: the nominal scene does not run: " + nominal.failure);
  std::vector<std::size_t> good, reduced;
  std::vector<std::string> failures;
  std::size_t failed = 0;
  std::string first_failure, first_unreduced;  // the first cause of each kind, in draw order
  for (std::size_t d = 1; d < results.size(); ++d) {
    if (results[d].ok) good.push_back(d);
    if (results[d].ok && results[d].reduced && nominal.reduced) reduced.push_back(d);
    const std::string& why = results[d].ok ? results[d].reduction_failure : results[d].failure;
    if (!results[d].ok) ++failed;
    std::string& first = results[d].ok ? first_unreduced : first_failure;
    if (first.empty()) first = why;
    if (!why.empty() && failures.size() < 3 &&
        std::find(failures.begin(), failures.end(), why) == failures.end())
      failures.push_back(why);
  }
  const std::string draws = std::to_string(results.size() - 1);
  // Fewer than two good draws have no spread: the study failed (exit 3), nothing written.
  if (good.size() < 2)
    throw NumericalError("study monte-carlo: " + std::to_string(failed) + " of " + draws +
                         " draws failed" +
                         (first_failure.empty() ? std::string() : ": " + first_failure));
  // Some failed: the bands are over the others, said on stderr as in summary.json.
  std::vector<std::string> warnings;
  if (failed > 0)
    warnings.push_back("study monte-carlo: " + std::to_string(failed) + " of " + draws +
                       " draws failed (summary.json failed_draws), the bands are over the " +
                       std::to_string(good.size()) + " others; the first: " + first_failure);
  if (const std::size_t unreduced = good.size() - reduced.size(); nominal.reduced && unreduced > 0)
    warnings.push_back("study monte-carlo: " + std::to_string(unreduced) + " of " + draws +
                       " draws ran but were not reduced (summary.json unreduced_draws)" +
                       (reduced.size() < 2 ? ", so no curve_bands.csv" : "") +
                       "; the first: " + first_unreduced);
  write_draws(distributions, jobs, results, dir / schema::draws::kFile);
  write_gauge_bands(results, good, dir / schema::gauge_bands::kFile);
  if (reduced.size() >= 2) write_curve_bands(results, reduced, dir / schema::curve_bands::kFile);

  // Each quantity over the draws, with each drawn value's share of its variance.
  const std::size_t k = distributions.size();
  std::vector<double> inputs((results.size() - 1) * k);
  for (std::size_t d = 1; d < jobs.size(); ++d)
    for (std::size_t i = 0; i < k; ++i) inputs[(d - 1) * k + i] = jobs[d].values[i];
  std::vector<std::size_t> from;
  for (std::size_t d : good) from.push_back(d - 1);
  const Quantities q = quantities(results);
  Json figures = Json::object();
  for (std::size_t f = 0; f < q.names.size(); ++f) {
    // A quantity too few draws give is left out (analysis/monte_carlo.hpp, states_interval).
    const auto stated =
        figure_statistics(q.names[f], q.units[f], q.nominal[f], q.values[f], from, inputs, k);
    if (!stated) continue;
    const FigureUncertainty& u = *stated;
    Json shares = Json::array();
    for (const auto& [i, share] : u.shares)
      shares.push_back({{"value", distributions[i].key}, {"share", share}});
    figures[u.name] = {{"nominal", number(u.nominal)},
                       {"median", u.median},
                       {"standard_deviation", u.standard_uncertainty},
                       {"interval_95", {u.low95, u.high95}},
                       {"unit", u.unit},
                       {"draws", u.draws},
                       {"contributions", shares}};
  }
  Json dist = Json::array();
  for (const Distribution& d : distributions) dist.push_back(distribution_json(d));
  Json j;
  j["version"] = kVersion;
  j["scene"] = scene.name;
  j["sweep"] = "monte-carlo";
  j["method"] =
      "Monte Carlo (GUM Supplement 1, JCGM 101:2008): each draw sets the scene's values from "
      "their distributions, is simulated and reduced as process --signals reduces a simulated "
      "test; bands: 2.5/50/97.5 % quantiles over the draws at each time (gauge_bands.csv) and at "
      "each strain of the nominal curve (curve_bands.csv); quantities: standard deviation and "
      "2.5/97.5 % quantiles over the draws; contributions: each drawn value's share of the "
      "variance (squared correlation), largest first";
  j["draws"] = results.size() - 1;
  j["seed"] = seed;
  j["failed_draws"] = failed;
  j["unreduced_draws"] = good.size() - reduced.size();
  j["failures"] = failures;
  j["distributions"] = dist;
  j["curve_bands"] = reduced.size() >= 2;
  if (!nominal.reduced && scene.specimen)
    j["curve_bands_missing_because"] = nominal.reduction_failure;
  j["quantities"] = figures;
  j["threads"] = threads;
  j["wall_time_s"] = wall_s;
  j["warnings"] = warnings;  // what the command prints, as every summary.json holds them
  write_text_file(dir / "summary.json", j.dump(2) + "\n");
  return warnings;
}

}  // namespace shpb
