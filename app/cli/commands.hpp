#pragma once
// The CLI's commands: each registers its options on a CLI11 sub-command and sets the action
// that main() runs after parsing. The commands only translate options into library calls.
#include <CLI/CLI.hpp>
#include <functional>

#include "railcontact/error.hpp"

namespace railcontact::cli {

// The exit code of each error kind (docs/ARCHITECTURE.md "Errors"): 0 success; 2 invalid input
// (also a command line CLI11 cannot parse); 3 a file that cannot be read or written; 4 no contact;
// 5 several contact patches where one is needed; 6 a solver that did not converge; 70 an internal
// error (a bug; also an unexpected exception); 71 out of memory.
constexpr int exit_code(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::invalid_input: return 2;
    case ErrorKind::io: return 3;
    case ErrorKind::no_contact: return 4;
    case ErrorKind::several_patches: return 5;
    case ErrorKind::not_converged: return 6;
    case ErrorKind::internal: return 70;
  }
  return 70;
}
inline constexpr int kExitOutOfMemory = 71;

using Action = std::function<int()>;

void add_coefficients_command(CLI::App& app, Action& action);
void add_study_command(CLI::App& app, Action& action);
void add_run_command(CLI::App& app, Action& action);
void add_patch_command(CLI::App& app, Action& action);
void add_flextable_command(CLI::App& app, Action& action);
void add_wheelset_command(CLI::App& app, Action& action);
void add_wheelset_table_command(CLI::App& app, Action& action);
void add_geometry_command(CLI::App& app, Action& action);
void add_sweep_command(CLI::App& app, Action& action);  // also `merge`

}  // namespace railcontact::cli
