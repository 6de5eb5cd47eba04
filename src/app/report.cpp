// `shpb report DIR`: figures and a one-page HTML report of an output folder. The plotting lives in
// the Python package tools/shpb_report/ (matplotlib) behind the entry script tools/report.py; this
// file finds the script and a Python that can import matplotlib and numpy, and runs it.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <cstdlib>  // setenv
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "core/error.hpp"
#include "core/external_program.hpp"
#include "core/interrupt.hpp"  // interrupted()

namespace shpb {
namespace {

// The report script's stderr, collected: its `warning: ` lines into `warnings`; after its exit
// code `rc` 2, 3 or 4, its `error: ` line thrown as InputError, WriteError or an internal error
// (what main prints after `error: `, exit 2, 3 or 4).
void collected_lines(const std::string& text, std::vector<std::string>& warnings, int rc) {
  std::string error;
  std::size_t at = 0;
  for (std::size_t end; at < text.size(); at = end + 1) {
    end = std::min(text.find('\n', at), text.size());
    const std::string line = text.substr(at, end - at);
    if (line.starts_with("warning: ")) warnings.push_back(line.substr(9));
    if (line.starts_with("error: ")) error = line.substr(7);
  }
  if (error.empty()) return;
  if (rc == 2) throw InputError(error);
  if (rc == 3) throw WriteError(error);
  if (rc == 4) throw std::logic_error(error);
}

}  // namespace

int run_report(const ReportArgs& args) {
  // Named as every input is (docs/commands.md, Exit codes), not in CLI11's words.
  if (!std::filesystem::is_directory(args.folder))
    throw input_error(args.folder.string(), "",
                      std::filesystem::exists(args.folder) ? "not a folder" : "no such folder",
                      "an output folder of simulate, process, compare, study, fit, calibrate or "
                      "plan was expected");
  const auto script = find_installed("report.py");
  if (!script)
    throw input_error("report", "share/shpb/report.py", "not found",
                      "the report script is installed beside the executable (cmake --install)");
  const auto python = find_python("import matplotlib, numpy");
  if (!python)
    throw input_error("report", "python3", "matplotlib/numpy not importable",
                      "install python3-matplotlib and python3-numpy (bash tools/install-deps.sh)");
  // The script stops if shpb is killed outright; it knows shpb by its pid (tools/report.py).
  ::setenv("SHPB_PARENT_PID", std::to_string(::getpid()).c_str(), 1);
  std::string errors;
  const int rc = run_program({*python, script->string(), args.folder.string()}, false,
                             args.warnings ? &errors : nullptr);
  if (args.warnings) collected_lines(errors, *args.warnings, rc);
  // Killed outright (the out-of-memory killer, kill -9; 128 + its signal), the script left its
  // temporaries in DIR, where they kept shpb from replacing DIR until the next report: the script
  // removes those of processes that are gone (docs/outputs.md, Conventions).
  const bool killed = rc > 128 && rc != 130;
  if (killed)
    run_program({*python, script->string(), "--remove-temporaries", args.folder.string()}, true);
  // 130: the script stopped on SIGINT/SIGTERM and left the previous report; a script that was
  // signalled but had already put its report in place finished (0).
  if (rc == 130 || (rc != 0 && interrupted())) throw Interrupted();
  // 2 bad input, 3 not written, 4 a bug of the script: it printed its own `error:` line.
  if (rc == 0 || rc == 2 || rc == 3 || rc == 4) return rc;
  if (killed) {
    std::fprintf(stderr,
                 "error: %s: the report script was killed by signal %d (out of memory?); the "
                 "report was not finished: run shpb report again\n",
                 args.folder.c_str(), rc - 128);
    return 3;
  }
  std::fprintf(stderr, "error: internal: %s %s exited with status %d\n", python->c_str(),
               script->c_str(), rc);
  return 4;
}

Command add_report_command(CLI::App& app) {
  auto args = std::make_shared<ReportArgs>();
  auto* cmd = app.add_subcommand(
      "report",
      "Turn an output folder of simulate/process/compare/study/fit/calibrate/plan into PNG figures "
      "and one self-contained report.html (needs python3 with matplotlib)");
  cmd->add_option("folder", args->folder, "Output folder")->required();
  return {cmd, [args] { return run_report(*args); }};
}

}  // namespace shpb
