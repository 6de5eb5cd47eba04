#include "dispersion/mode_table.hpp"

#include <cmath>

#include "core/csv_writer.hpp"
#include "core/error.hpp"
#include "core/interrupt.hpp"
#include "dispersion/pochhammer_chree.hpp"
#include "output_schema.hpp"

namespace shpb {
namespace {

// The largest a/Λ tabulated: far beyond the bars' frequencies (a/Λ of a few tenths).
constexpr double kMaxAOverLambda = 1000;

std::vector<double> table_points(const ModeTableOptions& o) {
  std::vector<double> xs = o.a_over_lambda;
  const int n = o.points.value_or(kDefaultTablePoints);
  if (xs.empty())
    for (int i = 0; i < n; ++i)
      xs.push_back(o.max_a_over_lambda.value_or(kDefaultMaxAOverLambda) * i / (n - 1));
  return xs;
}

}  // namespace

bool ModeTableOptions::IsValid(std::string* error) const {
  std::optional<InputError> e;
  if (!poisson_ratio_supported(poisson))
    e = input_error("--poisson", "", format_double(poisson),
                    "must be in [" + format_double(kMinPoissonRatio) + ", " +
                        format_double(kMaxPoissonRatio) + "]");
  // A list is the table: an evenly spaced table's size given with it was ignored.
  else if (!a_over_lambda.empty() && points)
    e = input_error("--points", "", std::to_string(*points),
                    "not with --a-over-lambda (the list gives the table's a/Λ)");
  else if (!a_over_lambda.empty() && max_a_over_lambda)
    e = input_error("--max-a-over-lambda", "", format_double(*max_a_over_lambda),
                    "not with --a-over-lambda (the list gives the table's a/Λ)");
  else if (points && (*points < 2 || *points > kMaxTablePoints))
    e = input_error("--points", "", std::to_string(*points),
                    "must be in [2, " + std::to_string(kMaxTablePoints) + "]");
  // The largest a/Λ under its own name: an infinite one made the table's points NaN, refused
  // as --a-over-lambda (a value nobody gave).
  else if (max_a_over_lambda && !(*max_a_over_lambda > 0 && *max_a_over_lambda <= kMaxAOverLambda))
    e = input_error("--max-a-over-lambda", "", format_double(*max_a_over_lambda),
                    "must be in (0, " + format_double(kMaxAOverLambda) + "]");
  for (double x : e ? std::vector<double>{} : table_points(*this))
    if (!e && (!(x >= 0) || x > kMaxAOverLambda))
      e = input_error("--a-over-lambda", "", format_double(x),
                      "must be in [0, " + format_double(kMaxAOverLambda) + "]");
  if (!e && radius_m.has_value() != c0_m_s.has_value())
    e = input_error(radius_m ? "--c0" : "--radius", "", "missing",
                    "--radius and --c0 go together (frequency_Hz needs both)");
  else if (!e && radius_m &&
           !(std::isfinite(*radius_m) && *radius_m > 0 && std::isfinite(*c0_m_s) && *c0_m_s > 0))
    e = input_error("--radius/--c0", "",
                    format_double(*radius_m) + " m, " + format_double(*c0_m_s) + " m/s",
                    "must be finite and > 0");
  if (e) *error = e->what();
  return !e;
}

std::vector<std::string> mode_table_header(const ModeTableOptions& options) {
  namespace k = schema::dispersion;  // the column names (src/core/output_schema.json)
  std::vector<std::string> header = {k::a_over_lambda, k::c_over_c0, k::cg_over_c0, k::f_a_over_c0};
  if (options.radius_m && options.c0_m_s) header.push_back(k::frequency_Hz);
  return header;
}

void mode_table(const ModeTableOptions& options,
                const std::function<void(const std::vector<double>&)>& row) {
  // Marching guess only for a small increasing step (the narrow bracket then cannot reach
  // another mode; see phase_velocity).
  constexpr double kMarchingStep = 0.01;
  const bool with_frequency = options.radius_m && options.c0_m_s;
  double previous_x = -1, previous_c = 0;
  for (double x : table_points(options)) {
    throw_if_interrupted();
    const bool near = x > previous_x && x - previous_x <= kMarchingStep && previous_x >= 0;
    const double c = phase_velocity(options.poisson, x, near ? previous_c : 0.0);
    previous_x = x;
    previous_c = c;
    const double cg = group_velocity(options.poisson, x, c);
    std::vector<double> r = {x, c, cg, x * c};
    if (with_frequency) r.push_back(x * c * *options.c0_m_s / *options.radius_m);
    for (double v : r)
      if (!std::isfinite(v))
        throw NumericalError("dispersion: non-finite value at a/lambda = " + format_double(x));
    row(r);
  }
}

}  // namespace shpb
