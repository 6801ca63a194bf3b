#pragma once
// The CLI's commands: each registers its options on a CLI11 sub-command and sets the action
// that main() runs after parsing. The commands only translate options into library calls.
#include <CLI/CLI.hpp>
#include <functional>

namespace railcontact::cli {

using Action = std::function<int()>;

void add_coefficients_command(CLI::App& app, Action& action);
void add_study_command(CLI::App& app, Action& action);
void add_run_command(CLI::App& app, Action& action);
void add_patch_command(CLI::App& app, Action& action);
void add_flextable_command(CLI::App& app, Action& action);

}  // namespace railcontact::cli
