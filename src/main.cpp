// shpb — a virtual Split-Hopkinson pressure bar laboratory. This file is only the command line:
// CLI11 subcommands (docs/commands.md), each registered and run by its own file in app/.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "core/closest_match.hpp"
#include "core/error.hpp"
#include "core/output_folder.hpp"
#include "version.hpp"

using namespace shpb;

namespace {

// The command's exit code, with what escapes it mapped to the codes of docs/commands.md.
int run_command(const Command& command) {
  try {
    throw_if_interrupted();  // a signal while the options were parsed
    return command.run();
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const NumericalError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 3;
  } catch (const WriteError& e) {
    std::fprintf(stderr, "error: %s\n", final_names(e.what()).c_str());
    return 3;
  } catch (const std::bad_alloc&) {
    // The estimate (validate) was passed but the machine could not give the memory: a failed
    // run, not an internal error.
    std::fprintf(stderr,
                 "error: out of memory: the run needs more memory than this machine could give; "
                 "`shpb validate` prints the estimate (coarser mesh, shorter duration or lower "
                 "sample rate reduce it)\n");
    return 3;
  } catch (const Interrupted&) {
    std::fprintf(stderr, "error: interrupted; previous results left intact\n");
    return 130;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: internal: %s\n", e.what());
    return 4;
  }
}

// The long options of `command` ("--name"), the closest-match candidates for a misspelt one: a
// one-letter typo is not worth a guess, and --help is never the option meant.
std::vector<std::string> long_options(const CLI::App& command) {
  std::vector<std::string> options;
  for (const CLI::Option* o : command.get_options())
    for (const std::string& name : o->get_lnames())
      if (name != "help") options.push_back("--" + name);
  return options;
}

// An unknown option of `where` ("shpb" or "shpb simulate"), named with the closest of
// `candidates` (core/closest_match.hpp), or the list to choose from.
std::string unknown_option(const std::string& extra, const std::string& where,
                           const std::vector<std::string>& candidates) {
  const std::string word = extra.substr(0, extra.find('=')), see = " (see " + where + " --help)";
  if (word.size() < 2 || word[1] != '-') return word + ": unknown option of " + where + see;
  return word + ": unknown option of " + where + "; " + suggestion_text(word, candidates) + see;
}

// A misspelt command or option named with the closest one (core/closest_match.hpp), as a misspelt
// scene key is; anything else in CLI11's words.
std::string usage_error(CLI::App& app, const CLI::ParseError& e, int argc, char** argv) {
  std::vector<std::string> names;
  for (const CLI::App* c : app.get_subcommands([](const CLI::App*) { return true; }))
    names.push_back(c->get_name());
  // An option before any command (shpb's own, --help and --version, end the parse when they are
  // given): a misspelt one of shpb's, or a command written as an option; whether a command
  // follows or not.
  if (argc > 1 && argv[1][0] == '-') {
    std::vector<std::string> candidates = long_options(app);
    candidates.insert(candidates.end(), names.begin(), names.end());
    return unknown_option(argv[1], "shpb", candidates);
  }
  if (app.get_subcommands().empty() && argc > 1)
    return std::string(argv[1]) + ": unknown command; " + suggestion_text(argv[1], names) +
           " (see shpb --help)";
  for (const std::string& extra : app.remaining(true)) {
    if (extra.size() < 2 || extra[0] != '-' || app.get_subcommands().empty()) continue;
    const CLI::App& command = *app.get_subcommands().front();
    return unknown_option(extra, "shpb " + command.get_name(), long_options(command));
  }
  // A value our checks refused (app/cli_options.cpp: --threads, --seed) in the library's words,
  // as the Python module gives them; anything else in CLI11's, with where to look.
  if (dynamic_cast<const CLI::ValidationError*>(&e)) return e.what();
  return std::string(e.what()) + " (see shpb --help)";
}

// SIGINT and SIGTERM are taken before anything of shpb runs: .preinit_array runs before every
// library's initialiser and the parsing of the options, so a signal at any instant ends a command
// with exit 130, nothing written (docs/commands.md, Exit codes); the one place for all commands.
// Only the system's loading of the executable and its libraries comes earlier (3.5 ms here).
void take_interrupts(int, char**, char**) { install_interrupt_handlers(); }
[[gnu::section(".preinit_array"),
  gnu::used]] void (*const take_interrupts_first)(int, char**, char**) = take_interrupts;

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "shpb — virtual Split-Hopkinson pressure bar laboratory: simulate a Kolsky bar test from one "
      "JSON scene, record strain gauges, correct Pochhammer–Chree dispersion and reduce gauge "
      "signals (simulated or measured) to specimen stress–strain curves."};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("shpb ") + kVersion);
  const std::vector<Command> commands = add_commands(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "error: %s\n", usage_error(app, e, argc, argv).c_str());
    return 2;
  }
  for (const Command& c : commands)
    if (*c.app) return run_command(c);
  return 2;
}
