#include "app/cli_options.hpp"

#include <algorithm>
#include <charconv>
#include <climits>

#include "core/csv_writer.hpp"
#include "core/enum_names.hpp"
#include "core/error.hpp"
#include "core/number_format.hpp"
#include "core/options_check.hpp"
#include "model/discretization.hpp"

namespace shpb {

std::vector<Command> add_commands(CLI::App& app) {
  return {add_simulate_command(app),   add_process_command(app), add_compare_command(app),
          add_dispersion_command(app), add_study_command(app),   add_validate_command(app),
          add_report_command(app),     add_fit_command(app),     add_calibrate_command(app),
          add_plan_command(app)};
}

std::string alternatives(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& n : names) text += (text.empty() ? "" : " | ") + n;
  return text;
}

namespace {

// A whole number of type T from 0 to `max`, written without sign, fraction or exponent;
// `description` is what --help shows after the option's type.
template <class T>
CLI::Validator whole_number_check(T max, const std::string& description, const std::string& name,
                                  const std::string& expected) {
  return CLI::Validator(
      [max, expected](std::string& text) -> std::string {
        T value{};
        const char* end = text.data() + text.size();
        const auto [at, ec] = std::from_chars(text.data(), end, value);
        if (text.empty() || text.front() == '-' || ec != std::errc() || at != end || value > max)
          return text + ": " + expected;
        return {};
      },
      description, name);
}

}  // namespace

CLI::Option* add_seed_option(CLI::App* cmd, std::uint64_t& seed, const std::string& help) {
  static const CLI::Validator check = whole_number_check<std::uint64_t>(
      UINT64_MAX, "", "seed", "expected a whole number from 0 to " + std::to_string(UINT64_MAX));
  return cmd->add_option("--seed", seed, help)->check(check);
}

CLI::Option* add_threads_option(CLI::App* cmd, int& threads, const std::string& help) {
  static const CLI::Validator check =
      whole_number_check<int>(INT_MAX, "NONNEGATIVE", "threads", kThreadsExpected);
  return cmd->add_option("--threads", threads, help)->check(check);
}

const CLI::Validator& unsigned_text_check() {
  static const CLI::Validator check = whole_number_check<std::uint64_t>(
      UINT64_MAX, "", "unsigned", "expected a whole number such as 1000");
  return check;
}

void check_choice(const std::string& option, const std::string& text,
                  const std::vector<std::string>& names) {
  if (std::find(names.begin(), names.end(), text) != names.end()) return;
  std::string expected = "expected ";
  for (std::size_t i = 0; i < names.size(); ++i)
    expected += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  throw input_error(option, "", "\"" + text + "\"", expected);
}

namespace {

// --contact's choices: the scene's methods but `bonded`, a scene key only.
std::vector<std::string> contact_choices() {
  std::vector<std::string> methods = enum_names(kContactMethodNames);
  std::erase(methods, std::string(to_string(ContactMethod::kBonded)));
  return methods;
}

}  // namespace

void add_run_options(CLI::App* cmd, RunOverrides& o, RunOptionText& text) {
  // The choices are checked with the other values (resolve_run_options): one message, the
  // command's and the Python module's.
  cmd->add_option("--contact", text.contact,
                  "Contact method at every interface: " + alternatives(contact_choices()) +
                      " (default: the scene's, else " +
                      std::string(to_string(ContactSpec{}.method)) + ")");
  cmd->add_option("--stepping", text.stepping,
                  alternatives(enum_names(kSteppingNames)) +
                      ": every bar its own time step, or all bars at the smallest step (default: "
                      "the scene's, else " +
                      std::string(to_string(SimulationSpec{}.stepping)) + ")");
  // Read as the scene's simulation.courant is (a number or "50 %"); its range, (0, 1], is
  // checked with the scene (model/scene_validation.hpp).
  cmd->add_option("--courant", text.courant,
                  "Courant number of every bar, c·Δt/h, in (0, 1] (default: the scene's, else " +
                      format_double(kDefaultCourant) + ")");
  // Its range, (0 %, 100 %) as in the scene: tolerance_option.
  cmd->add_option("--tolerance", text.tolerance,
                  "Gauge error accepted, e.g. \"1 %\": every bar without its own elements meshed "
                  "as coarsely as the error model predicts meets it (default: the scene's "
                  "simulation.tolerance, else " +
                      format_number(100 * kDefaultTolerance) +
                      " %; study: else the automatic meshes)");
  add_threads_option(cmd, o.threads, "Worker threads (0 = all cores)");
  cmd->add_flag("--quiet,-q", o.quiet, "No progress output on stderr");
}

void resolve_run_options(RunOverrides& o, const RunOptionText& text) {
  if (!text.contact.empty()) {
    check_choice("--contact", text.contact, contact_choices());
    o.contact = contact_method_from_string(text.contact);
  }
  if (!text.stepping.empty()) {
    check_choice("--stepping", text.stepping, enum_names(kSteppingNames));
    o.stepping = stepping_from_string(text.stepping);
  }
  if (!text.courant.empty())
    o.courant = quantity_option("--courant", text.courant, Dimension::kDimensionless);
  if (!text.tolerance.empty()) o.tolerance = tolerance_option("--tolerance", text.tolerance);
}

double tolerance_option(const std::string& option, const std::string& text) {
  double t = 0;
  try {
    t = parse_quantity(text, Dimension::kDimensionless);
  } catch (const std::invalid_argument&) {
    throw input_error(option, "", "\"" + text + "\"", "expected a gauge error such as \"1 %\"");
  }
  if (const std::string what = tolerance_option_problem(option, t); !what.empty())
    throw InputError(what);
  return t;
}

double quantity_option(const std::string& option, const std::string& text, Dimension d) {
  try {
    return parse_quantity(text, d);
  } catch (const std::invalid_argument& e) {
    throw input_error(option, "", "\"" + text + "\"", e.what());
  }
}

}  // namespace shpb
