// The command line is SI throughout, with the unit in each option's name (README.md "Commands"):
// every quantity option of every command names its unit in its name and in its help line, and the
// old spellings without the unit are refused with one error that converts the value given.
#include <gtest/gtest.h>

#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.hpp"

namespace railcontact {
namespace {

using test::CommandResult;
using test::run_cli;

// The unit suffixes of option names and the unit each help line must state.
struct Unit {
  std::string suffix, symbol;
};
const std::vector<Unit>& units() {
  static const std::vector<Unit> u{{"-m-per-s", "m/s"}, {"-rad-per-s", "rad/s"}, {"-m", "m"},
                                   {"-rad", "rad"},     {"-N", "N"},            {"-Pa", "Pa"}};
  return u;
}

// Numbers without a unit: friction, creepage, Poisson's ratio, ratios of lengths, collocation offsets.
const std::set<std::string> kDimensionless{"--mu", "--extra-creepage", "--nu", "--a-over-b", "--alpha", "--alpha-spin",
                                           "--refine-lateral-force-fraction"};

struct HelpOption {
  std::string name, type, description;
};

// The lines of a section ("Options:", "Subcommands:") of CLI11's help: an entry starts at two
// spaces; its description follows on the same line or, for a long name, on the next one.
std::vector<HelpOption> help_section(const std::string& help, const std::string& section) {
  std::vector<HelpOption> entries;
  std::istringstream in(help);
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    if (line == section) {
      inside = true;
      continue;
    }
    if (!inside) continue;
    if (line.empty()) break;
    if (line.rfind("  ", 0) != 0) break;
    if (line.size() > 4 && line[2] != ' ') {  // a new entry: NAME [TYPE[=DEFAULT] ...] DESCRIPTION
      std::istringstream words(line.substr(2));
      HelpOption o;
      words >> o.name;
      if (const std::size_t comma = o.name.rfind(','); comma != std::string::npos) o.name = o.name.substr(comma + 1);
      std::string rest;
      std::getline(words, rest);
      const std::size_t start = rest.find_first_not_of(' ');
      rest = start == std::string::npos ? "" : rest.substr(start);
      // The type is the first word in capitals (FLOAT, INT, TEXT), before the description's gap.
      if (const std::size_t gap = rest.find("  "); gap != std::string::npos && std::isupper(rest[0])) {
        o.type = rest.substr(0, gap);
        rest = rest.substr(gap);
      } else if (!rest.empty() && std::isupper(rest[0]) && rest.find(' ') == std::string::npos) {
        o.type = rest;  // the description is on the next line
        rest.clear();
      }
      o.description = rest;
      entries.push_back(o);
    } else if (!entries.empty()) {
      entries.back().description += " " + line;
    }
  }
  return entries;
}

// Every command path: "wheelset", "flextable build", "study patches", …
std::vector<std::string> command_paths(const std::string& prefix = "") {
  const CommandResult r = run_cli(prefix + (prefix.empty() ? "" : " ") + "--help");
  EXPECT_EQ(r.exit_code, 0) << prefix << ": " << r.err;
  std::vector<std::string> paths;
  for (const HelpOption& sub : help_section(r.out, "Subcommands:")) {
    const std::string path = prefix.empty() ? sub.name : prefix + " " + sub.name;
    paths.push_back(path);
    for (const std::string& deeper : command_paths(path)) paths.push_back(deeper);
  }
  return paths;
}

const Unit* unit_of(const std::string& name) {
  for (const Unit& u : units())
    if (name.size() > u.suffix.size() && name.compare(name.size() - u.suffix.size(), u.suffix.size(), u.suffix) == 0)
      return &u;
  return nullptr;
}

// A help line states its unit: "(m, + to the left)", "(N; default …)", "FROM:TO:STEP in m".
bool states_unit(const std::string& description, const std::string& symbol) {
  const std::regex word("(^|[\\s(])" + std::regex_replace(symbol, std::regex("/"), "\\/") + "([\\s,;)]|$)");
  return std::regex_search(description, word);
}

TEST(CliUnits, EveryQuantityOptionOfEveryCommandNamesItsUnitInItsNameAndHelp) {
  const std::vector<std::string> paths = command_paths();
  ASSERT_GE(paths.size(), 15u);  // run, patch, wheelset, flextable build/check, study …, sweep, merge, …
  int quantity_options = 0;
  for (const std::string& path : paths) {
    const CommandResult r = run_cli(path + " --help");
    ASSERT_EQ(r.exit_code, 0) << path << ": " << r.err;
    for (const HelpOption& o : help_section(r.out, "Options:")) {
      SCOPED_TRACE(path + " " + o.name + " " + o.type + ": " + o.description);
      const Unit* unit = unit_of(o.name);
      // A real number, or a FROM:TO:STEP range of them, is a quantity unless it is dimensionless.
      const bool quantity = (o.type.find("FLOAT") != std::string::npos ||
                             o.description.find("FROM:TO:STEP") != std::string::npos) &&
                            !kDimensionless.contains(o.name);
      if (quantity) {
        ++quantity_options;
        EXPECT_NE(unit, nullptr) << "a quantity option needs its SI unit in its name (-m, -rad, -N, -Pa, -m-per-s, "
                                    "-rad-per-s), or a place in kDimensionless";
      }
      if (unit != nullptr) EXPECT_TRUE(states_unit(o.description, unit->symbol)) << "the help must state " << unit->symbol;
    }
  }
  EXPECT_GE(quantity_options, 30);
  // The top-level help says it once.
  const CommandResult top = run_cli("--help");
  EXPECT_NE(top.out.find("the command line is SI throughout"), std::string::npos) << top.out;
  EXPECT_NE(top.out.find("the unit is in each option's name"), std::string::npos) << top.out;
  EXPECT_NE(top.out.find("JSON is SI"), std::string::npos) << top.out;
}

// The test's own parser finds a unit-less FLOAT option: the check above can fail.
TEST(CliUnits, TheHelpCheckFindsAnOptionWithoutItsUnit) {
  const std::vector<HelpOption> options =
      help_section("Options:\n  --foo FLOAT                 a length\n  --bar-m FLOAT=0.5           a length (m)\n"
                   "  --lateral-velocity-m-per-s FLOAT\n                              lateral velocity (m/s)\n\n",
                   "Options:");
  ASSERT_EQ(options.size(), 3u);
  EXPECT_EQ(options[0].name, "--foo");
  EXPECT_EQ(options[0].type, "FLOAT");
  EXPECT_EQ(unit_of(options[0].name), nullptr);
  ASSERT_NE(unit_of(options[1].name), nullptr);
  EXPECT_TRUE(states_unit(options[1].description, "m"));
  EXPECT_FALSE(states_unit("a length (mm)", "m"));
  const Unit* velocity = unit_of(options[2].name);
  ASSERT_NE(velocity, nullptr);
  EXPECT_EQ(velocity->symbol, "m/s");
  EXPECT_TRUE(states_unit(options[2].description, "m/s"));
}

// An old spelling, alone, mixed with new ones, with or without a value: one error with exit code 2
// that names the command, the old option and the new one, and converts the value given.
TEST(CliUnits, OldSpellingsAreRefusedWithTheNewOptionAndTheValueConverted) {
  const std::string no_table = " --out /nonexistent-railcontact/t.json";
  const std::vector<std::pair<std::string, std::string>> cases{
      {"wheelset --y 3", "wheelset --y is no longer accepted: the command line is SI throughout, with the unit in the "
                         "option's name: give --y-m in metres (--y was in millimetres: --y 3 is --y-m 0.003)"},
      {"wheelset --y-m 0.003 --load 98", "--load was in kilonewtons: --load 98 is --load-N 98000)"},
      {"wheelset --yaw=2.5 --y-m 0.001", "give --yaw-rad in radians (--yaw was in milliradians: --yaw 2.5 is --yaw-rad 0.0025)"},
      {"wheelset --roll -1", "--roll -1 is --roll-rad -0.001"},
      {"wheelset --speed 30", "give --speed-m-per-s in metres per second (--speed was in metres per second too: "
                              "--speed 30 is --speed-m-per-s 30)"},
      {"wheelset --lateral-velocity 0.1", "--lateral-velocity 0.1 is --lateral-velocity-m-per-s 0.1"},
      {"wheelset --yaw-rate 0.2", "--yaw-rate 0.2 is --yaw-rate-rad-per-s 0.2"},
      {"wheelset --element-size 0.5", "--element-size 0.5 is --element-size-m 0.0005"},
      {"wheelset --sweep-y 0:-7:0.1", "--sweep-y 0:-7:0.1 is --sweep-y-m 0:-0.007:0.0001"},
      {"wheelset --y", "--y 3 is --y-m 0.003"},            // no value: the example
      {"wheelset --y abc", "--y 3 is --y-m 0.003"},        // not a number: the example
      {"wheelset-table build --load 80,100" + no_table, "wheelset-table build --load is no longer accepted"},
      {"wheelset-table build --load 80,100" + no_table, "--load 80,100 is --load-N 80000,100000"},
      {"wheelset-table build --yaw -5:5:1" + no_table, "--yaw -5:5:1 is --yaw-rad -0.005:0.005:0.001"},
      {"wheelset-table build --element-size 0.2" + no_table, "--element-size 0.2 is --element-size-m 0.0002"},
      {"geometry --amplitude 3", "geometry --amplitude is no longer accepted"},
      {"geometry --rolling-radius 460", "--rolling-radius 460 is --rolling-radius-m 0.46"},
      {"geometry --y-from-m -0.006 --y-to 6", "geometry --y-to is no longer accepted"},
      {"patch --y -0.003", "patch --y is no longer accepted"},
      {"patch --load 80000", "--load was in newtons too: --load 80000 is --load-N 80000"},
      {"flextable build --y-step 0.0005", "flextable build --y-step is no longer accepted"},  // before --out is missed
      {"flextable check --y 0.001 --table t.json", "flextable check --y is no longer accepted"},
      {"study patches --load 98100 --out /nonexistent-railcontact/s", "study patches --load is no longer accepted"},
      {"study bound --y-step 0.001 --out /nonexistent-railcontact/s", "study bound --y-step is no longer accepted"},
      {"study paper --y-step 0.001 --out /nonexistent-railcontact/s", "study paper --y-step is no longer accepted"},
  };
  for (const auto& [arguments, message] : cases) {
    SCOPED_TRACE("railcontact " + arguments);
    const CommandResult r = run_cli(arguments);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    test::expect_one_error_line(r, message);
  }
  // A prefix of a new option is not taken for it (CLI11 matches long options exactly), nor is
  // another case of its unit.
  for (const std::string option : {"--yaw-rate-rad", "--lateral-velocity-m", "--load-n"}) {
    const CommandResult prefix = run_cli("wheelset " + option + " 1");
    EXPECT_EQ(prefix.exit_code, 2) << option;
    test::expect_one_error_line(prefix, "The following argument was not expected: " + option);
  }
  // No old spelling is shown in a help.
  for (const std::string& path : command_paths())
    for (const HelpOption& o : help_section(run_cli(path + " --help").out, "Options:"))
      for (const char* old : {"--y", "--yaw", "--roll", "--speed", "--load", "--gauge", "--y-from", "--y-step", "--amplitude"})
        EXPECT_NE(o.name, old) << path;
}

}  // namespace
}  // namespace railcontact
