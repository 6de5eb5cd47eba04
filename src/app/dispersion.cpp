// `shpb dispersion`: the first Pochhammer–Chree mode as CSV (docs/commands.md, docs/methods.md §5).
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "app/cli_options.hpp"
#include "app/commands.hpp"
#include "core/checked_write.hpp"
#include "core/csv_writer.hpp"
#include "core/error.hpp"
#include "core/output_folder.hpp"
#include "dispersion/mode_table.hpp"

namespace shpb {

int run_dispersion(const DispersionArgs& args) {
  const ModeTableOptions options{args.poisson, args.a_over_lambda, args.max_a_over_lambda,
                                 args.points,  args.radius_m,      args.c0_m_s};
  require_valid(options);
  const std::vector<std::string> header = mode_table_header(options);
  // A file through CsvWriter, or stdout (never reopened: that would truncate a redirect).
  // The file is written atomically: FILE keeps its previous content until the table is complete.
  // It replaces only a table of this command: a first line that starts with the columns every
  // table has (those without frequency_Hz).
  if (args.output && *args.output != "-") {  // "-": stdout, as the shell convention has it
    std::string columns;
    for (const std::string& name : mode_table_header(ModeTableOptions{}))
      columns += (columns.empty() ? "" : ",") + name;
    OutputFile file(*args.output, columns);
    CsvWriter csv(file.path(), header);
    mode_table(options, [&](const std::vector<double>& row) { csv.row(row); });
    csv.close();
    file.commit();
    return 0;
  }
  for (std::size_t i = 0; i < header.size(); ++i)
    std::printf("%s%s", i ? "," : "", header[i].c_str());
  std::printf("\n");
  mode_table(options, [](const std::vector<double>& row) {
    for (std::size_t i = 0; i < row.size(); ++i)
      std::printf("%s%s", i ? "," : "", format_double(row[i]).c_str());
    std::printf("\n");
  });
  if (std::fflush(stdout) != 0) throw_write_error("stdout", errno);
  return 0;
}

Command add_dispersion_command(CLI::App& app) {
  struct Options {
    DispersionArgs args;
    std::string radius, c0;
  };
  auto o = std::make_shared<Options>();
  DispersionArgs& disp = o->args;
  auto* cmd = app.add_subcommand(
      "dispersion",
      "Print or write the first-mode Pochhammer–Chree curve of a solid round bar: "
      "a_over_lambda,c_over_c0,cg_over_c0,f_a_over_c0[,frequency_Hz]");
  cmd->add_option("--poisson", disp.poisson, "Poisson ratio of the bar, in [0, 0.49]")
      ->required();  // its range checked by run_dispersion (dispersion/pochhammer_chree.hpp)
  // Each value of the list a number: an empty list ("") was read as 0, a row nobody
  // asked for; the range is checked with the table (dispersion/mode_table.hpp).
  static const CLI::Validator number(
      [](std::string& text) -> std::string {
        double v = 0;
        const char* end = text.data() + text.size();
        const auto [at, ec] = std::from_chars(text.data(), end, v);
        if (text.empty() || ec != std::errc() || at != end)
          return "\"" + text + "\": expected a list of numbers such as 0.1,0.5";
        return {};
      },
      "NUMBER", "number");
  cmd->add_option("--a-over-lambda", disp.a_over_lambda,
                  "Explicit list of radius/wavelength values")
      ->delimiter(',')
      ->check(number);
  cmd->add_option("--max-a-over-lambda", disp.max_a_over_lambda,
                  "Largest a/Λ of an evenly spaced table (default 1.6)");
  // Their ranges: ModeTableOptions::IsValid, the Python module's check too.
  cmd->add_option("--points", disp.points, "Number of table points (default 321)");
  cmd->add_option("--radius", o->radius, "Bar radius, e.g. \"9.525 mm\" (adds frequency_Hz)");
  cmd->add_option("--c0", o->c0, "Bar wave speed sqrt(E/ρ), e.g. \"4975 m/s\"");
  cmd->add_option("-o,--output", disp.output, "CSV file to write (default, or -: stdout)");
  return {cmd, [o] {
            if (!o->radius.empty())
              o->args.radius_m = quantity_option("--radius", o->radius, Dimension::kLength);
            if (!o->c0.empty())
              o->args.c0_m_s = quantity_option("--c0", o->c0, Dimension::kVelocity);
            return run_dispersion(o->args);
          }};
}

}  // namespace shpb
