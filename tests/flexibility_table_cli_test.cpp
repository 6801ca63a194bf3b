// `railcontact flextable build|check` and `railcontact run --flextable`, run as a user would: the
// table file, the table-driven nh-fastsim in the JSON, and one clear error line with a non-zero
// exit code for bad input (ellipse cases, other profiles, y out of range, bad files and options).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_run.hpp"
#include "railcontact/flexibility_table.hpp"
#include "railcontact/geometry.hpp"
#include "railcontact/wheel_rail.hpp"

namespace {

using railcontact::test::CommandResult;
using railcontact::test::count_lines;
using railcontact::test::run_cli;

using railcontact::test::ScratchDirectory;  // removed with its files at the end of each test

void write(const std::filesystem::path& path, const std::string& text) {
  std::ofstream file(path);
  file << text;
}

// A wheel-rail case at ~800 elements; the rail file and y as given.
std::string wheel_rail_case(double y_m, const std::string& rail = "") {
  return "[geometry]\ntype = \"wheel-rail\"\ny = " + std::to_string(y_m) + "\n" +
         (rail.empty() ? "" : "rail = \"" + rail + "\"\n") +
         "[material]\nE = 2.1e11\nnu = 0.3\n[load]\nnormal_force = 98100\n[friction]\nmu = 0.3\n"
         "[creepage]\nxi_normalised = 0.5\neta_normalised = 0.5\nphi = \"from-conicity\"\n"
         "[mesh]\nelements = 800\n[solvers]\nrun = [\"nh-fastsim\", \"fastsim\"]\n";
}

// A small table (y = 0, 0.25, 0.5 mm, ~800 elements, K2 of the patch itself) written by the
// library, not the CLI.
std::filesystem::path small_table(const std::filesystem::path& dir) {
  railcontact::FlexibilityTableOptions options;
  options.patch.target_elements = 800;
  options.nh_fastsim.flexibility_coarsening = 1;
  const railcontact::FlexibilityTable table = railcontact::build_flexibility_table(
      railcontact::default_wheel_rail_pair(), {0.0, 0.25e-3, 0.5e-3}, {98100.0}, options);
  const std::filesystem::path path = dir / "table.json";
  railcontact::save_flexibility_table(table, path);
  return path;
}

using railcontact::test::expect_one_error_line;

TEST(FlextableCli, BuildWritesATableThatRunUses) {
  const ScratchDirectory dir("flextable_build");
  const std::string table = (dir / "t.json").string();
  const CommandResult b =
      run_cli("flextable build --out " + table + " --y-from-m 0 --y-to-m 0.5e-3 --y-step-m 0.25e-3 --elements 800");
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_NE(b.out.find("3 solved"), std::string::npos) << b.out;
  EXPECT_NE(b.err.find("node 3/3"), std::string::npos) << b.err;  // progress on stderr
  const railcontact::FlexibilityTable t = railcontact::load_flexibility_table(table);
  EXPECT_EQ(t.y_m().size(), 3u);
  EXPECT_EQ(t.metadata().target_elements, 800);

  write(dir / "case.toml", wheel_rail_case(0.125e-3));
  const CommandResult r = run_cli("run " + (dir / "case.toml").string() + " --flextable " + table + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["results"]["nh-fastsim"]["flexibility_source"], "table");
  EXPECT_EQ(j["results"]["fastsim"]["flexibility_source"], "Eq 9");
  EXPECT_FALSE(j["patch"].contains("creepage_matrix_K2"));  // no K2
  EXPECT_EQ(j["flexibility_table"]["file"], table);
  EXPECT_EQ(j["flexibility_table"]["flexibility"], j["results"]["nh-fastsim"]["flexibility"]);

  const CommandResult text = run_cli("run " + (dir / "case.toml").string() + " --flextable " + table);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("from the flexibility table " + table), std::string::npos) << text.out;
  EXPECT_EQ(text.err.find("older nH-FastSim recipe"), std::string::npos) << text.err;
  // The same table as a format-3 file (no recipe recorded): used, with a note on stderr.
  nlohmann::json old_format = nlohmann::json::parse(std::ifstream(table));
  old_format["format_version"] = 3;
  old_format.erase("nh_fastsim_recipe");
  const std::string old_table = (dir / "old.json").string();
  std::ofstream(old_table) << old_format.dump();
  const CommandResult old_run = run_cli("run " + (dir / "case.toml").string() + " --flextable " + old_table + " --json");
  ASSERT_EQ(old_run.exit_code, 0) << old_run.err;
  EXPECT_NE(old_run.err.find("note: " + old_table + ": the table was built with an older nH-FastSim recipe (1 or 2, "
                             "not recorded; this railcontact: 4)"),
            std::string::npos)
      << old_run.err;
  EXPECT_EQ(nlohmann::json::parse(old_run.out)["results"]["nh-fastsim"]["F1"], j["results"]["nh-fastsim"]["F1"]);
  const CommandResult without = run_cli("run " + (dir / "case.toml").string() + " --json");
  ASSERT_EQ(without.exit_code, 0) << without.err;
  EXPECT_EQ(nlohmann::json::parse(without.out)["results"]["nh-fastsim"]["flexibility_source"],
            "K2 of the patch coarsened by 2");  // ~800 elements: automatic coarsening
}

TEST(FlextableCli, CheckPrintsTheForceDifferencesAndTheirMaximum) {
  const ScratchDirectory dir("flextable_check");
  const std::string table = small_table(dir).string();
  const CommandResult r = run_cli("flextable check --table " + table);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("max |F_table - F_onthefly| / |F_onthefly|"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("xi'=eta'=0.5+spin"), std::string::npos) << r.out;
  const CommandResult j = run_cli("flextable check --table " + table + " --json");
  ASSERT_EQ(j.exit_code, 0) << j.err;
  const nlohmann::json out = nlohmann::json::parse(j.out);
  EXPECT_EQ(out["points"].size(), 2u);  // the two midpoints
  EXPECT_EQ(out["families"].size(), 5u);
  EXPECT_LT(out["max_force_difference"].get<double>(), 0.01);
}

TEST(FlextableCli, BadInputGivesOneClearErrorLine) {
  const ScratchDirectory dir("flextable_bad");
  const std::string table = small_table(dir).string();
  const std::string rail = (dir / "rail.txt").string();
  railcontact::write_text_profile(rail, railcontact::read_profile(railcontact::default_rail_profile_path()));
  write(dir / "other_rail.toml", wheel_rail_case(0.25e-3, rail));
  // The table's recipe (flexibility coarsening 1), so that only y is wrong.
  write(dir / "far.toml", wheel_rail_case(3e-3) + "flexibility_coarsening = 1\n");
  // The case's automatic coarsening, or another material, against the table's.
  write(dir / "other_recipe.toml", wheel_rail_case(0.25e-3));
  std::string other_material = wheel_rail_case(0.25e-3) + "flexibility_coarsening = 1\n";
  other_material.replace(other_material.find("E = 2.1e11"), 10, "E = 2.0e11");
  write(dir / "other_material.toml", other_material);
  write(dir / "broken.json", "{\"format\": \"railcontact flexibility table\",\n\"format_version\": ");
  write(dir / "not_a_table.json", "{\"y\": 1}");
  const std::string ellipse = std::string(RAILCONTACT_SOURCE_DIR) + "/examples/hertz_ellipse.toml";
  const std::string missing_dir = (dir / "no" / "such" / "t.json").string();
  const std::pair<std::string, std::string> cases[] = {
      {"run " + ellipse + " --flextable " + table, "wheel-rail cases only"},
      {"run " + (dir / "other_rail.toml").string() + " --flextable " + table, "was built for other profiles"},
      {"run " + (dir / "far.toml").string() + " --flextable " + table,
       "y = 3.0000 mm lies outside its range y = 0.0000 ... 0.5000 mm"},
      {"run " + (dir / "other_recipe.toml").string() + " --flextable " + table,
       "flexibility table " + table + " was built with the flexibility coarsening 1 and is used with 0 (automatic)"},
      {"run " + (dir / "other_material.toml").string() + " --flextable " + table,
       "flexibility table " + table + " was built for another material (E = 2.1e+11 Pa, nu = 0.3; given E = 2e+11 Pa, nu = 0.3)"},
      {"run --flextable " + (dir / "nonexistent.json").string(), "cannot read the flexibility table"},
      {"run --flextable " + (dir / "broken.json").string(), "malformed JSON"},
      {"run --flextable " + (dir / "not_a_table.json").string(), "not a flexibility table"},
      {"flextable check --table " + table + " --rail " + rail, "was built for other profiles"},
      {"flextable check --table " + table + " --y-m 0.001", "outside its range"},
      {"flextable check --table " + table + " --load-N 90000", "holds the one vertical load"},
      {"flextable check --table " + table + " --mu 0", "mu"},
      {"flextable check --table " + table + " --interpolation cubic", "interpolation"},
      {"flextable check", "--table"},
      {"flextable build", "--out"},
      {"flextable build --out " + (dir / "t.json").string() + " --y-step-m 0", "y step"},
      {"flextable build --out " + (dir / "t.json").string() + " --y-from-m 1e-3 --y-to-m 0", "y_to >= y_from"},
      {"flextable build --out " + (dir / "t.json").string() + " --load-N -1", "--load-N"},
      {"flextable build --out " + (dir / "t.json").string() + " --elements 0", "--elements"},
      {"flextable build --out " + missing_dir, "no directory"},
      {"flextable build --out " + (dir / "t.json").string() + " --wheel " + (dir / "none.prw").string(), "none.prw"},
      {"flextable frobnicate", "subcommand"},
  };
  for (const auto& [arguments, expected] : cases) {
    SCOPED_TRACE(arguments);
    expect_one_error_line(run_cli(arguments), expected);
  }
}

}  // namespace
