// The options renamed to SI with the unit in the name, and their refusal (renamed_options.hpp).
#include "cli/renamed_options.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace railcontact::cli {
namespace {

constexpr std::string_view kMetres = "metres", kMillimetres = "millimetres", kRadians = "radians",
                           kMilliradians = "milliradians", kNewtons = "newtons", kKilonewtons = "kilonewtons",
                           kMetresPerSecond = "metres per second", kRadiansPerSecond = "radians per second";

// One row per option that carried a quantity without its unit in the name. A new option needs no
// row: it is named with its unit (--wheel-angular-velocity-rad-per-s).
constexpr std::array kRenamedOptions{
    // wheelset
    RenamedOption{"wheelset", "--y", "--y-m", kMillimetres, kMetres, 1e3, "3"},
    RenamedOption{"wheelset", "--yaw", "--yaw-rad", kMilliradians, kRadians, 1e3, "2"},
    RenamedOption{"wheelset", "--roll", "--roll-rad", kMilliradians, kRadians, 1e3, "1"},
    RenamedOption{"wheelset", "--speed", "--speed-m-per-s", kMetresPerSecond, kMetresPerSecond, 1.0, "20"},
    RenamedOption{"wheelset", "--lateral-velocity", "--lateral-velocity-m-per-s", kMetresPerSecond, kMetresPerSecond,
                  1.0, "0.1"},
    RenamedOption{"wheelset", "--yaw-rate", "--yaw-rate-rad-per-s", kRadiansPerSecond, kRadiansPerSecond, 1.0, "0.1"},
    RenamedOption{"wheelset", "--load", "--load-N", kKilonewtons, kNewtons, 1e-3, "98.1"},
    RenamedOption{"wheelset", "--element-size", "--element-size-m", kMillimetres, kMetres, 1e3, "0.2"},
    RenamedOption{"wheelset", "--sweep-y", "--sweep-y-m", kMillimetres, kMetres, 1e3, "0:-7:0.1"},
    // wheelset-table build
    RenamedOption{"wheelset-table build", "--y", "--y-m", kMillimetres, kMetres, 1e3, "-7:7:0.1"},
    RenamedOption{"wheelset-table build", "--yaw", "--yaw-rad", kMilliradians, kRadians, 1e3, "-5:5:1"},
    RenamedOption{"wheelset-table build", "--load", "--load-N", kKilonewtons, kNewtons, 1e-3, "80,100,120"},
    RenamedOption{"wheelset-table build", "--element-size", "--element-size-m", kMillimetres, kMetres, 1e3, "0.2"},
    // geometry
    RenamedOption{"geometry", "--gauge", "--gauge-m", kMillimetres, kMetres, 1e3, "1435"},
    RenamedOption{"geometry", "--flange-back", "--flange-back-m", kMillimetres, kMetres, 1e3, "1360"},
    RenamedOption{"geometry", "--rolling-radius", "--rolling-radius-m", kMillimetres, kMetres, 1e3, "460"},
    RenamedOption{"geometry", "--y-from", "--y-from-m", kMillimetres, kMetres, 1e3, "-6"},
    RenamedOption{"geometry", "--y-to", "--y-to-m", kMillimetres, kMetres, 1e3, "6"},
    RenamedOption{"geometry", "--y-step", "--y-step-m", kMillimetres, kMetres, 1e3, "0.1"},
    RenamedOption{"geometry", "--amplitude", "--amplitude-m", kMillimetres, kMetres, 1e3, "3"},
    // patch
    RenamedOption{"patch", "--y", "--y-m", kMetres, kMetres, 1.0, "-0.003"},
    RenamedOption{"patch", "--load", "--load-N", kNewtons, kNewtons, 1.0, "98100"},
    // flextable build, check
    RenamedOption{"flextable build", "--y-from", "--y-from-m", kMetres, kMetres, 1.0, "-0.0045"},
    RenamedOption{"flextable build", "--y-to", "--y-to-m", kMetres, kMetres, 1.0, "0.0045"},
    RenamedOption{"flextable build", "--y-step", "--y-step-m", kMetres, kMetres, 1.0, "0.00025"},
    RenamedOption{"flextable build", "--load", "--load-N", kNewtons, kNewtons, 1.0, "98100"},
    RenamedOption{"flextable check", "--y", "--y-m", kMetres, kMetres, 1.0, "0.001"},
    RenamedOption{"flextable check", "--load", "--load-N", kNewtons, kNewtons, 1.0, "98100"},
    // study
    RenamedOption{"study bound", "--y-step", "--y-step-m", kMetres, kMetres, 1.0, "0.0005"},
    RenamedOption{"study patches", "--y-from", "--y-from-m", kMetres, kMetres, 1.0, "-0.0045"},
    RenamedOption{"study patches", "--y-to", "--y-to-m", kMetres, kMetres, 1.0, "0.0045"},
    RenamedOption{"study patches", "--y-step", "--y-step-m", kMetres, kMetres, 1.0, "0.00025"},
    RenamedOption{"study patches", "--load", "--load-N", kNewtons, kNewtons, 1.0, "98100"},
    RenamedOption{"study paper", "--y-step", "--y-step-m", kMetres, kMetres, 1.0, "0.00025"},
};

// `text` with every number (between ':' or ',') divided by `old_per_new`; empty if a part is not a
// finite number.
std::string converted(std::string_view text, double old_per_new) {
  std::string out;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t end = std::min(text.find_first_of(":,", begin), text.size());
    const std::string part(text.substr(begin, end - begin));
    char* stop = nullptr;
    errno = 0;
    const double value = std::strtod(part.c_str(), &stop);
    if (part.empty() || stop != part.c_str() + part.size() || errno != 0 || !std::isfinite(value)) return {};
    out += fmt::format("{:.12g}", value / old_per_new);
    if (end == text.size()) break;
    out += text[end];
    begin = end + 1;
  }
  return out;
}

// The error of an old option given with `values`, converted when they are numbers (also
// FROM:TO:STEP or a comma list), else the row's example converted.
std::string renamed_option_message(const RenamedOption& row, const std::vector<std::string>& values) {
  // The values given, converted; the row's example when they are none or not numbers.
  std::string old_values, new_values;
  for (const std::string& value : values) {
    const std::string value_si = converted(value, row.old_per_new);
    if (value_si.empty()) {
      old_values.clear();
      break;
    }
    old_values += (old_values.empty() ? "" : " ") + value;
    new_values += (new_values.empty() ? "" : " ") + value_si;
  }
  if (old_values.empty()) {
    old_values = row.example;
    new_values = converted(row.example, row.old_per_new);
  }
  const bool same_unit = row.old_unit == row.new_unit;
  return fmt::format("{} {} is no longer accepted: the command line is SI throughout, with the unit in the option's "
                     "name: give {} in {} ({} was in {}{}: {} {} is {} {})",
                     row.command, row.old_name, row.new_name, row.new_unit, row.old_name, row.old_unit,
                     same_unit ? " too" : "", row.old_name, old_values, row.new_name, new_values);
}

}  // namespace

void refuse_renamed_options(CLI::App& app) {
  for (const RenamedOption& row : kRenamedOptions) {
    CLI::App* command = &app;
    std::string_view path = row.command;
    while (!path.empty()) {
      const std::size_t space = std::min(path.find(' '), path.size());
      try {
        command = command->get_subcommand(std::string(path.substr(0, space)));
      } catch (const CLI::OptionNotFound&) {
        throw std::logic_error(fmt::format("renamed option {}: no command '{}'", row.old_name, row.command));
      }
      path.remove_prefix(std::min(space + 1, path.size()));
    }
    if (command->get_option_no_throw(std::string(row.new_name)) == nullptr)
      throw std::logic_error(fmt::format("renamed option {}: {} has no option {}", row.old_name, row.command, row.new_name));
    // Hidden (no help line), at most one value, refused as soon as it is parsed: before any
    // other check of the command line, whatever else is given with it.
    command
        ->add_option(
            std::string(row.old_name),
            [&row](const CLI::results_t& values) -> bool {
              std::vector<std::string> given;
              for (const std::string& v : values)
                if (!v.empty()) given.push_back(v);
              throw CLI::ValidationError(renamed_option_message(row, given));
            },
            "")
        ->expected(0, 1)
        ->trigger_on_parse()
        ->group("");
  }
}

}  // namespace railcontact::cli
