#include "study/study_args.hpp"

#include "analysis/uncertainty.hpp"
#include "core/error.hpp"
#include "core/options_check.hpp"

namespace shpb {

bool StudyArgs::IsValid(std::string* error) const {
  const int modes = (plan ? 1 : 0) + (run ? 1 : 0) + (merge ? 1 : 0);
  // The Monte Carlo option given first, if any (named by the errors below).
  const char* monte_carlo_option = first_given({{!distributions.empty(), "--distributions"},
                                                {draws.has_value(), "--draws"},
                                                {seed.has_value(), "--seed"}});
  // The sweep and its run options given first, if any: a plan holds them.
  const char* planned_option = first_given({{sweep.has_value(), "--sweep"},
                                            {overrides.contact.has_value(), "--contact"},
                                            {overrides.stepping.has_value(), "--stepping"},
                                            {overrides.courant.has_value(), "--courant"},
                                            {overrides.tolerance.has_value(), "--tolerance"},
                                            {refine != 1, "--refine"}});
  std::optional<InputError> e;
  if (modes > 1)
    e = input_error("study", "", "", "--plan, --run and --merge are separate steps: give one");
  else if ((run || merge) && planned_option)
    e = not_with_step(planned_option, "--run or --merge",
                      "the plan holds the sweep and its options (plan again to change them)");
  else if (refine < 1 || refine > kMaxRefine)
    e = input_error("--refine", "", std::to_string(refine),
                    "expected 1 to " + std::to_string(kMaxRefine));
  else if (draws && (*draws < kMinDraws || *draws > kMaxStudyDraws))
    e = input_error(
        "--draws", "", std::to_string(*draws),
        "expected " + std::to_string(kMinDraws) + " to " + std::to_string(kMaxStudyDraws));
  else if (refine != 1 && chosen_sweep() != Sweep::kStability)
    e = input_error("--refine", "", std::to_string(refine), "only with --sweep stability");
  else if ((run || merge) && monte_carlo_option)
    e = not_with_step(monte_carlo_option, "--run or --merge", "the plan holds the draws");
  else if (chosen_sweep() != Sweep::kMonteCarlo && monte_carlo_option)
    e = input_error(monte_carlo_option, "", "", "only with --sweep monte-carlo");
  else if (chosen_sweep() == Sweep::kMonteCarlo && !run && !merge && distributions.empty())
    e = input_error("--distributions", "", "",
                    "a file of the values to draw is required with --sweep monte-carlo "
                    "(docs/scene-format.md, \"Monte Carlo distributions\")");
  else if (!shard.empty() && !run)
    e = input_error("--shard", "", "\"" + shard + "\"", "only with --run DIR");
  else if ((run || plan) && !output.empty())
    e = input_error("-o", "", "\"" + output.string() + "\"",
                    "not with --plan or --run: they write into DIR (the plan, DIR/parts)");
  else if ((run || merge) && !scene.empty())
    e = input_error(scene.string(), "", "",
                    "--run and --merge take the scene from DIR/plan.json: give no scene");
  else if (!run && !merge && scene.empty())
    e = input_error("study", "", "", "a scene file is required");
  else if (!run && !merge && !plan && output.empty())
    e = input_error("-o", "", "", "an output folder is required");
  if (e) *error = e->what();
  return !e;
}

}  // namespace shpb
