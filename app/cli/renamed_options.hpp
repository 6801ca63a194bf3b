#pragma once
// The command line is SI throughout, with the unit in each option's name (--y-m, --yaw-rad,
// --load-N, --speed-m-per-s, …; README.md "Commands"). The options that carried a quantity under a
// name without its unit are refused with one error that says what changed and how to convert:
//   railcontact: error: wheelset --y is no longer accepted: the command line is SI throughout, with
//   the unit in the option's name: give --y-m in metres (--y was in millimetres: --y 3 is --y-m 0.003)
// One table in renamed_options.cpp lists them, per command; refuse_renamed_options() registers each
// old name on its command as a hidden option that fails the parse as soon as it is met (so also when
// old and new spellings are mixed). A new option is named with its unit from the start and needs no
// row. CLI11 (2.1) matches long options exactly, so a prefix such as --y is never taken for --y-m.
#include <CLI/CLI.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace railcontact::cli {

struct RenamedOption {
  std::string_view command;   // the command's path: "wheelset", "flextable build", "study patches"
  std::string_view old_name;  // "--y"
  std::string_view new_name;  // "--y-m"
  std::string_view old_unit;  // the unit of the old option's values: "millimetres"
  std::string_view new_unit;  // the SI unit of the new option: "metres"
  double old_per_new = 1.0;   // an old value is this many times the new one (1000 for mm to m)
  std::string_view example;   // an old value, shown converted when the one given is not a number
};

// Registers the old names of the table on their commands under `app` (call it once the
// commands are added). Throws std::logic_error for a row whose command or new option does not exist.
void refuse_renamed_options(CLI::App& app);

}  // namespace railcontact::cli
