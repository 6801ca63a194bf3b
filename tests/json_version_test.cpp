// Every JSON the command-line tool writes, on stdout (--json) or as a file (--out DIR, the
// flexibility table), carries the library's version at its top level under "railcontact_version"
// (issue #13): the string `railcontact --version` prints and rc_version_string() returns.
// The test also reads the tool's --help: a command whose help mentions JSON but that is not run
// here fails it, so a new JSON output cannot forget the version unnoticed.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "railcontact/railcontact.h"

namespace {

using railcontact::test::CommandResult;
using railcontact::test::run_cli;
using railcontact::test::ScratchDirectory;

// No figures (a missing script is a warning): the test checks the JSON only.
const std::string kNoFigures = "RAILCONTACT_SCRIPTS=/nonexistent-railcontact-scripts ";

nlohmann::json parse_file(const std::filesystem::path& path) {
  std::ifstream file(path);
  EXPECT_TRUE(file.good()) << path;
  return nlohmann::json::parse(file);
}

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return text;
}

// The names listed under "Subcommands:" in a CLI11 help text.
std::vector<std::string> subcommands_in_help(const std::string& help) {
  std::vector<std::string> names;
  std::istringstream in(help);
  bool listing = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("Subcommands:", 0) == 0) {
      listing = true;
      continue;
    }
    if (!listing) continue;
    if (line.empty()) break;
    std::istringstream words(line);
    std::string name;
    if (words >> name) names.push_back(name);
  }
  return names;
}

// Every leaf command ("run", "flextable build", ...) whose --help mentions JSON.
void commands_mentioning_json(const std::string& prefix, std::set<std::string>& found) {
  const CommandResult help = run_cli(prefix + (prefix.empty() ? "" : " ") + "--help");
  ASSERT_EQ(help.exit_code, 0) << prefix << ": " << help.err;
  const std::vector<std::string> subcommands = subcommands_in_help(help.out);
  if (subcommands.empty()) {
    if (lowercase(help.out).find("json") != std::string::npos) found.insert(prefix);
    return;
  }
  for (const std::string& name : subcommands) commands_mentioning_json(prefix.empty() ? name : prefix + " " + name, found);
}

TEST(JsonVersion, EveryJsonOutputOfTheToolCarriesTheLibraryVersion) {
  const std::string version = rc_version_string();
  ASSERT_FALSE(version.empty());
  const CommandResult version_flag = run_cli("--version");
  ASSERT_EQ(version_flag.exit_code, 0) << version_flag.err;
  EXPECT_EQ(version_flag.out, "railcontact " + version + "\n");

  const ScratchDirectory dir("json_version");
  std::set<std::string> covered;  // the commands run below
  int checked = 0;
  auto expect_version = [&](const nlohmann::json& j, const std::string& what) {
    ASSERT_TRUE(j.is_object()) << what;
    ASSERT_TRUE(j.contains("railcontact_version")) << what << " has no railcontact_version";
    EXPECT_EQ(j["railcontact_version"], version) << what;
    ++checked;
  };
  auto run_json = [&](const std::string& command, const std::string& arguments) {
    covered.insert(command);
    const CommandResult r = run_cli(command + " " + arguments, kNoFigures);
    EXPECT_EQ(r.exit_code, 0) << command << " " << arguments << ": " << r.err;
    if (r.exit_code == 0) expect_version(nlohmann::json::parse(r.out), command + " --json");
  };

  // run: stdout and DIR/result.json.
  {
    std::ofstream(dir / "case.toml") << "[geometry]\ntype = \"ellipse\"\na = 0.006\nb = 0.004\n"
                                        "[material]\nE = 2.1e11\nnu = 0.3\n[load]\nnormal_force = 98100\n"
                                        "[friction]\nmu = 0.3\n[creepage]\nxi = 0.001\neta = 0\nphi = 0\n"
                                        "[mesh]\nelements = 300\n[solvers]\nrun = [\"nh-fastsim\"]\n";
    run_json("run", (dir / "case.toml").string() + " --json --out " + (dir / "run").string());
    expect_version(parse_file(dir / "run" / "result.json"), "run --out DIR/result.json");
  }
  run_json("coefficients", "--a-over-b 1 --nu 0.3 --elements 300 --json");
  // patch: stdout and DIR/patch.json.
  run_json("patch", "--elements 500 --json --out " + (dir / "patch").string());
  expect_version(parse_file(dir / "patch" / "patch.json"), "patch --out DIR/patch.json");
  run_json("wheelset", "--element-size-m 0.001 --json");
  // flextable build writes the table file; flextable check prints its JSON.
  {
    covered.insert("flextable build");
    const std::string table = (dir / "table.json").string();
    const CommandResult b =
        run_cli("flextable build --out " + table + " --y-from-m 0 --y-to-m 0.5e-3 --y-step-m 0.5e-3 --elements 300");
    ASSERT_EQ(b.exit_code, 0) << b.err;
    expect_version(parse_file(table), "flextable build --out FILE");
    run_json("flextable check", "--table " + table + " --elements 300 --json");
  }
  // wheelset-table build writes the table file; wheelset --table prints its JSON.
  {
    covered.insert("wheelset-table build");
    const std::string table = (dir / "wheelset_table.json").string();
    const CommandResult b = run_cli("wheelset-table build --out " + table + " --y-m=0:0.0005:0.0005 --load-N 100000 --element-size-m 0.001");
    ASSERT_EQ(b.exit_code, 0) << b.err;
    expect_version(parse_file(table), "wheelset-table build --out FILE");
    run_json("wheelset", "--table " + table + " --y-m 0.0002 --load-N 100000 --frictionless-balance --json");
  }
  run_json("geometry", "--y-from-m=-0.002 --y-to-m 0.002 --y-step-m 0.0005 --amplitude-m 0.001 --json --out " + (dir / "geometry").string());
  // sweep writes DIR/sweep.json; a shard's journal holds it and merge writes it again.
  {
    covered.insert("sweep");
    covered.insert("merge");
    std::ofstream(dir / "sweep.toml") << "[mesh]\nelement_size_mm = 1.0\n[grid]\ny_mm = [0, 1]\n";
    const CommandResult s = run_cli("sweep " + (dir / "sweep.toml").string() + " --out " + (dir / "sweep").string(), kNoFigures);
    ASSERT_EQ(s.exit_code, 0) << s.err;
    expect_version(parse_file(dir / "sweep" / "sweep.json"), "sweep --out DIR/sweep.json");
    for (const std::string i : {"0", "1"}) {
      const CommandResult shard = run_cli("sweep " + (dir / "sweep.toml").string() + " --shard " + i + "/2 --out " +
                                              (dir / ("shard" + i)).string(), kNoFigures);
      ASSERT_EQ(shard.exit_code, 0) << shard.err;
    }
    const CommandResult m =
        run_cli("merge " + (dir / "shard0").string() + " " + (dir / "shard1").string() + " --out " + (dir / "merged").string(), kNoFigures);
    ASSERT_EQ(m.exit_code, 0) << m.err;
    expect_version(parse_file(dir / "merged" / "sweep.json"), "merge --out DIR/sweep.json");
  }
  EXPECT_EQ(checked, 13);

  // Every command that mentions JSON in its help is one of those run above.
  std::set<std::string> mentioning;
  commands_mentioning_json("", mentioning);
  EXPECT_GE(mentioning.size(), 5u);  // the help was read
  for (const std::string& command : mentioning)
    EXPECT_TRUE(covered.count(command)) << "railcontact " << command
                                        << " mentions JSON in its help but its output is not checked here";
}

}  // namespace
