#pragma once
// Command-line pieces several commands register (CLI11): the run options and quantities with
// units.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "core/units.hpp"

namespace shpb {

// "a | b | c" of an option's choices.
std::string alternatives(const std::vector<std::string>& names);

// The text of --contact/--stepping/--tolerance as given, resolved after parsing.
struct RunOptionText {
  std::string contact, stepping, tolerance;
};

// --contact/--stepping/--courant/--tolerance/--threads/--quiet for simulate, compare, study and
// validate. The choices are the enums' own name tables (core/enum_names.hpp); `bonded` is a scene
// key only.
void add_run_options(CLI::App* cmd, RunOverrides& o, RunOptionText& text);
// Into `o`; InputError for a tolerance that is not a gauge error.
void resolve_run_options(RunOverrides& o, const RunOptionText& text);

// A gauge-error option ("1 %") as a fraction in (0, 1); InputError naming the option.
double tolerance_option(const std::string& option, const std::string& text);
// A quantity option ("22 m/s") in SI; InputError naming the option.
double quantity_option(const std::string& option, const std::string& text, Dimension d);

}  // namespace shpb
