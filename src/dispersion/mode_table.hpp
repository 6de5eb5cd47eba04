#pragma once
// The table `shpb dispersion` prints (docs/commands.md, docs/methods.md §5): the first
// Pochhammer–Chree mode of a solid round bar at a list of a/Λ, one row at a time.
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace shpb {

// The largest evenly spaced table: a million rows (about 60 MB of CSV) is far past any plot or
// interpolation a bar needs, and bounds a mistyped count before it is allocated.
inline constexpr int kMaxTablePoints = 1000000;
// The evenly spaced table when no list is given: a/Λ 0 … 1.6 in steps of 0.005.
inline constexpr double kDefaultMaxAOverLambda = 1.6;
inline constexpr int kDefaultTablePoints = 321;

struct ModeTableOptions {
  double poisson = 0.29;
  std::vector<double> a_over_lambda;  // explicit list, or
  // an evenly spaced table of `points` from 0 (1.6 and 321 when not given; not with a list)
  std::optional<double> max_a_over_lambda;
  std::optional<int> points;
  std::optional<double> radius_m;  // both, or neither: the frequency_Hz column
  std::optional<double> c0_m_s;
  // Ceres' Solver::Options::IsValid: false with the one-line reason in `error`.
  bool IsValid(std::string* error) const;
};

// a_over_lambda,c_over_c0,cg_over_c0,f_a_over_c0[,frequency_Hz].
std::vector<std::string> mode_table_header(const ModeTableOptions& options);
// Calls `row` for every a/Λ in order. NumericalError for a non-finite value.
void mode_table(const ModeTableOptions& options,
                const std::function<void(const std::vector<double>&)>& row);

}  // namespace shpb
