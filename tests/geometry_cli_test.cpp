// `railcontact geometry`, run as a user would: the files of --out with their columns, the JSON
// summary, and the equivalent conicity it reports agreeing with the library's.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.hpp"

namespace {

using railcontact::test::CommandResult;
using railcontact::test::run_cli;
using railcontact::test::ScratchDirectory;

using railcontact::test::read_csv;

TEST(GeometryCli, WritesTheSweepTheConicityAndTheFigures) {
  const ScratchDirectory dir("geometry_cli");
  const CommandResult r = run_cli("geometry --y-from-m -0.006 --y-to-m 0.006 --y-step-m 0.0005 --json --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("positions").get<int>(), 25);
  EXPECT_DOUBLE_EQ(j.at("amplitude_m").get<double>(), 3e-3);
  const double wavelength = j.at("tan_gamma_e_wavelength").get<double>();
  const double regression = j.at("tan_gamma_e_regression").get<double>();
  EXPECT_GT(wavelength, 0.05);
  EXPECT_LT(wavelength, 0.5);
  EXPECT_GT(regression, 0.05);
  EXPECT_LT(regression, 0.5);

  const auto geometry = read_csv(dir / "geometry.csv");
  ASSERT_EQ(geometry.size(), 26u);
  EXPECT_EQ(geometry[0][0], "y_mm");
  EXPECT_EQ(geometry[0][3], "delta_r_mm");
  EXPECT_EQ(geometry[0][1], "roll_mrad");
  // y = 0 in the middle row: Δr = 0; at y = +6 mm Δr > 0 (the left wheel on its flange root).
  EXPECT_NEAR(std::stod(geometry[13][0]), 0.0, 1e-9);
  EXPECT_NEAR(std::stod(geometry[13][3]), 0.0, 1e-6);
  EXPECT_GT(std::stod(geometry[25][3]), 0.0);
  const auto conicity = read_csv(dir / "conicity.csv");
  ASSERT_GE(conicity.size(), 2u);
  EXPECT_EQ(conicity[0][0], "amplitude_mm");
  EXPECT_EQ(conicity[0][1], "tan_gamma_e_wavelength");
  EXPECT_EQ(conicity[0][2], "tan_gamma_e_regression");
  EXPECT_TRUE(std::filesystem::exists(dir / "profiles.csv"));
  // The figures, when matplotlib is there (a missing one only warns).
  if (r.err.find("figures skipped") == std::string::npos) {
    for (const char* figure : {"contact_points.png", "delta_r.png", "contact_angles.png", "conicity.png"})
      EXPECT_TRUE(std::filesystem::exists(dir / figure)) << figure;
  }
}

TEST(GeometryCli, PrintsTheConicitySummary) {
  const ScratchDirectory dir("geometry_cli_text");
  const CommandResult r = run_cli("geometry --y-from-m -0.005 --y-to-m 0.005 --y-step-m 0.0005 --amplitude-m 0.002 --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("Equivalent conicity at amplitude 2 mm"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("geometry.csv"), std::string::npos) << r.out;
}

// A measured wheel whose flange climbs before ±6 mm (tests/data/car7216_uic60.toml): the default
// range ends where the flange climbs, on both sides, and says so; a range given explicitly that
// reaches beyond it is an error naming the position.
TEST(GeometryCli, TheDefaultRangeEndsWhereTheFlangeClimbs) {
  const ScratchDirectory dir("geometry_cli_climb");
  const std::string setup = std::string(RAILCONTACT_SOURCE_DIR) + "/tests/data/car7216_uic60.toml";
  const CommandResult r = run_cli("geometry " + setup + " --json --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  const double from = j.at("swept_from_m").get<double>(), to = j.at("swept_to_m").get<double>();
  EXPECT_GT(from, -6e-3);
  EXPECT_LT(to, 6e-3);
  EXPECT_GT(to, 3e-3);
  EXPECT_NEAR(from, -to, 0.1e-3 + 1e-9);  // the wheelset is symmetric (within one step of 0.1 mm)
  EXPECT_NE(r.err.find("the flange climbs beyond it"), std::string::npos) << r.err;
  const CommandResult given = run_cli("geometry " + setup + " --y-from-m -0.006 --y-to-m 0.006 --out " + dir.string());
  EXPECT_EQ(given.exit_code, 2);
  EXPECT_NE(given.err.find("the flange is climbing over the rail"), std::string::npos) << given.err;
}

}  // namespace
