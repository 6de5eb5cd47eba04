#pragma once
// Command-line pieces several commands register (CLI11): the run options and quantities with
// units.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "core/units.hpp"

namespace shpb {

// "a | b | c" of an option's choices.
std::string alternatives(const std::vector<std::string>& names);

// The text of --contact/--stepping/--tolerance as given, resolved after parsing.
struct RunOptionText {
  std::string contact, stepping, courant, tolerance;
};

// --contact/--stepping/--courant/--tolerance/--threads/--quiet for simulate, compare, study and
// validate. The choices are the enums' own name tables (core/enum_names.hpp); `bonded` is a scene
// key only.
void add_run_options(CLI::App* cmd, RunOverrides& o, RunOptionText& text);
// Into `o`; InputError for a choice not offered, a tolerance that is not a gauge error, a Courant
// number that is not a number (the Python module's options too).
void resolve_run_options(RunOverrides& o, const RunOptionText& text);

// The numeric options several commands share, each checked in one place (CLI11 validators, run on
// the text as given: exit 2 with "error: --seed: -1: expected ..."):
// --seed, a whole number 0 … 2^64 − 1 (no sign, no fraction, no wrap-around of "-1");
CLI::Option* add_seed_option(CLI::App* cmd, std::uint64_t& seed, const std::string& help);
// --threads, a whole number ≥ 0 (0: all cores), in the library's words (kThreadsExpected).
// The ranges of the other numeric options are the library's (each command's IsValid, run before
// any work): one check, the command's message and the Python module's.
CLI::Option* add_threads_option(CLI::App* cmd, int& threads, const std::string& help);

// The text of a count read into an unsigned type (--draws): a whole number without sign, which
// CLI11 would otherwise wrap ("-1" read as 2^64 − 1); its range is the library's.
const CLI::Validator& unsigned_text_check();

// A choice option's text (--contact, --stepping, --sweep): InputError naming the option unless it
// is one of `names` ("--sweep: \"foo\": expected pareto, stability or monte-carlo").
void check_choice(const std::string& option, const std::string& text,
                  const std::vector<std::string>& names);

// A gauge-error option ("1 %") as a fraction in (0, 1); InputError naming the option.
double tolerance_option(const std::string& option, const std::string& text);
// A quantity option ("22 m/s") in SI; InputError naming the option.
double quantity_option(const std::string& option, const std::string& text, Dimension d);

}  // namespace shpb
