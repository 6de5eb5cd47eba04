// `shpb dispersion`: the first Pochhammer–Chree mode as CSV (docs/commands.md, docs/methods.md §5).
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "app/commands.hpp"
#include "core/checked_write.hpp"
#include "core/csv_writer.hpp"
#include "core/error.hpp"
#include "core/output_folder.hpp"
#include "dispersion/pochhammer_chree.hpp"

namespace shpb {

int run_dispersion(const DispersionArgs& args) {
  if (!poisson_ratio_supported(args.poisson))
    throw input_error("--poisson", "", format_double(args.poisson),
                      "must be in [" + format_double(kMinPoissonRatio) + ", " +
                          format_double(kMaxPoissonRatio) + "]");
  std::vector<double> xs = args.a_over_lambda;
  if (xs.empty()) {
    if (args.points < 2)
      throw input_error("--points", "", std::to_string(args.points), "must be >= 2");
    for (int i = 0; i < args.points; ++i)
      xs.push_back(args.max_a_over_lambda * i / (args.points - 1));
  }
  for (double x : xs)
    if (!(x >= 0) || x > 1000)
      throw input_error("--a-over-lambda", "", format_double(x), "must be in [0, 1000]");
  const bool with_frequency = args.radius_m && args.c0_m_s;
  if (args.radius_m.has_value() != args.c0_m_s.has_value())
    throw input_error(args.radius_m ? "--c0" : "--radius", "", "missing",
                      "--radius and --c0 go together (frequency_Hz needs both)");
  if (with_frequency && (!(*args.radius_m > 0) || !(*args.c0_m_s > 0)))
    throw input_error("--radius/--c0", "", "", "must be > 0");

  std::vector<std::string> header = {"a_over_lambda", "c_over_c0", "cg_over_c0", "f_a_over_c0"};
  if (with_frequency) header.push_back("frequency_Hz");
  // A file through CsvWriter, or stdout (never reopened: that would truncate a redirect).
  // The file is written atomically: FILE keeps its previous content until the table is complete.
  std::unique_ptr<OutputFile> file;
  std::unique_ptr<CsvWriter> csv;
  if (args.output) {
    file = std::make_unique<OutputFile>(*args.output);
    csv = std::make_unique<CsvWriter>(file->path(), header);
  } else {
    for (std::size_t i = 0; i < header.size(); ++i)
      std::printf("%s%s", i ? "," : "", header[i].c_str());
    std::printf("\n");
  }
  auto write = [&](const std::vector<double>& row) {
    for (double v : row)
      if (!std::isfinite(v))
        throw NumericalError("dispersion: non-finite value at a/lambda = " + format_double(row[0]));
    if (csv) return csv->row(row);
    for (std::size_t i = 0; i < row.size(); ++i)
      std::printf("%s%s", i ? "," : "", format_double(row[i]).c_str());
    std::printf("\n");
  };
  // Marching guess only for a small increasing step (the narrow bracket then cannot reach
  // another mode; see phase_velocity).
  constexpr double kMarchingStep = 0.01;
  double previous_x = -1, previous_c = 0;
  for (double x : xs) {
    throw_if_interrupted();
    const bool near = x > previous_x && x - previous_x <= kMarchingStep && previous_x >= 0;
    const double c = phase_velocity(args.poisson, x, near ? previous_c : 0.0);
    previous_x = x;
    previous_c = c;
    const double cg = group_velocity(args.poisson, x, c);
    std::vector<double> row = {x, c, cg, x * c};
    if (with_frequency) row.push_back(x * c * *args.c0_m_s / *args.radius_m);
    write(row);
  }
  if (csv) {
    csv->close();
    file->commit();
  } else if (std::fflush(stdout) != 0) {
    throw_write_error("stdout", errno);
  }
  return 0;
}

}  // namespace shpb
