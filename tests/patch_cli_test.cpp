// `railcontact patch` and `railcontact study patches`, run as a user would: the JSON keys, the
// files of --out, and one clear error line with a non-zero exit code for bad input.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.hpp"

namespace {

using railcontact::test::CommandResult;
using railcontact::test::count_lines;
using railcontact::test::run_cli;

using railcontact::test::ScratchDirectory;  // removed with its files at the end of each test

using railcontact::test::read_csv;

using railcontact::test::expect_one_error_line;

TEST(PatchCli, JsonIsOneObjectWithTheDocumentedKeys) {
  const CommandResult r = run_cli("patch --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);  // exactly one object (throws otherwise)
  ASSERT_TRUE(j.is_object());
  for (const char* key : {"y", "contact_angle_rad", "rolling_radius_m", "spin_per_m", "normal_force_N", "area_m2",
                          "elements_in_contact", "extent_x1_m", "extent_x2_m", "max_pressure_Pa", "approach_m",
                          "iterations"})
    EXPECT_TRUE(j.contains(key)) << key;
  const double gamma = j["contact_angle_rad"].get<double>();
  EXPECT_EQ(j["y"].get<double>(), 0.0);
  // On the tread, about the 1:40 cant: the smooth reference's 0.0351 rad at y = 0 (the point of
  // first touch: 0.0243 rad).
  EXPECT_GT(gamma, 0.025);
  EXPECT_LT(gamma, 0.045);
  EXPECT_EQ(j["contact_reference"].get<std::string>(), "smooth");
  // The squared-gap weighted reference point (docs/WHEELSET.md §4): CONTACT's y_cp = -750.385 mm
  // of the wheelset is rail y = -10.15 mm.
  EXPECT_NEAR(j["reference_point"]["y_rail_m"].get<double>(), -10.15e-3, 0.05e-3);
  EXPECT_NEAR(j["normal_force_N"].get<double>(), 98100.0 / std::cos(gamma), 1e-9 * 98100.0);
  EXPECT_NEAR(j["spin_per_m"].get<double>(), 2.0 * std::sin(gamma) / 0.92, 1e-12);
  EXPECT_NEAR(j["elements_in_contact"].get<double>(), 3000.0, 0.15 * 3000.0);
  EXPECT_GT(j["max_pressure_Pa"].get<double>(), 5e8);
  EXPECT_GT(j["area_m2"].get<double>(), 1e-4);
}

TEST(PatchCli, TextTableAndOutputFiles) {
  const ScratchDirectory dir("patch_out");
  const CommandResult r = run_cli("patch --y-m -0.003 --load-N 80000 --elements 1500 --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("contact angle"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("normal force F3"), std::string::npos) << r.out;
  std::ifstream json_file(dir / "patch.json");
  const nlohmann::json j = nlohmann::json::parse(json_file);
  const auto rows = read_csv(dir / "pressure.csv");
  ASSERT_GE(rows.size(), 2u);
  EXPECT_EQ(rows[0], (std::vector<std::string>{"x1_m", "x2_m", "pressure_Pa"}));
  EXPECT_EQ(rows.size() - 1, j["elements_in_contact"].get<std::size_t>());
  // The CSV holds the whole load, with the origin at the centre of pressure.
  const double S = j["mesh"]["dx1_m"].get<double>() * j["mesh"]["dx2_m"].get<double>();
  double force = 0.0, moment1 = 0.0, moment2 = 0.0;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const double p = std::stod(rows[k][2]);
    EXPECT_GT(p, 0.0);
    force += p * S;
    moment1 += p * S * std::stod(rows[k][0]);
    moment2 += p * S * std::stod(rows[k][1]);
  }
  const double F3 = j["normal_force_N"].get<double>();
  EXPECT_NEAR(F3, 80000.0 / std::cos(j["contact_angle_rad"].get<double>()), 1e-6);
  EXPECT_NEAR(force, F3, 1e-6 * F3);
  EXPECT_NEAR(moment1 / force, 0.0, 1e-9);
  EXPECT_NEAR(moment2 / force, 0.0, 1e-9);
  EXPECT_TRUE(std::filesystem::exists(dir / "pressure.png"));
}

// --contact-surface conformal / auto: the right wheel of `railcontact wheelset` (by load on the normal
// forces alone) on that surface: the same patch numbers as the wheelset's, the load carried by the
// pressure's vertical resultant, the developed patch in pressure_K.csv and a map.
TEST(PatchCli, TheConformalSurfaceIsTheWheelsetsRightWheel) {
  const ScratchDirectory dir("patch_conformal");
  const CommandResult r =
      run_cli("patch --y-m -0.0052 --contact-surface conformal --element-size-m 0.0004 --json --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["patches"].size(), 1u);
  const nlohmann::json& p = j["patches"][0];
  EXPECT_EQ(p["contact_surface"], "conformal");
  EXPECT_TRUE(p.contains("strip_angle_range_rad"));
  EXPECT_NEAR(p["pressure_force_track_N"][2].get<double>(), 98100.0, 1e-5 * 98100.0);
  // The wheelset's right wheel, frictionless balance: the same patch to the last digit.
  const CommandResult w = run_cli(
      "wheelset --y-m -0.0052 --contact-surface conformal --element-size-m 0.0004 --frictionless-balance --json");
  ASSERT_EQ(w.exit_code, 0) << w.err;
  const nlohmann::json wheelset = nlohmann::json::parse(w.out);
  const nlohmann::json& q = wheelset["wheels"][0]["patches"][0];
  EXPECT_EQ(p["normal_force_N"], q["normal_force_N"]);
  EXPECT_EQ(p["area_m2"], q["area_m2"]);
  EXPECT_EQ(p["strip_angle_range_rad"], q["strip_angle_range_rad"]);
  // The developed patch's pressures integrate to its normal force.
  const auto rows = read_csv(dir / p["pressure_csv"].get<std::string>());
  ASSERT_EQ(rows.size() - 1, p["elements_in_contact"].get<std::size_t>());
  std::ifstream written_file(dir / "patch.json");
  const nlohmann::json written = nlohmann::json::parse(written_file);
  const double S = written["patches"][0]["mesh"]["dx1_m"].get<double>() * written["patches"][0]["mesh"]["dx2_m"].get<double>();
  double force = 0.0;
  for (std::size_t k = 1; k < rows.size(); ++k) force += std::stod(rows[k][2]) * S;
  EXPECT_NEAR(force, p["normal_force_N"].get<double>(), 1e-6 * force);
  EXPECT_TRUE(std::filesystem::exists(dir / "pressure.png"));
}

TEST(PatchCli, StudyWritesOneSinglePatchRowPerDisplacement) {
  const ScratchDirectory dir("patch_study");
  const CommandResult r = run_cli("study patches --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.out.empty());  // progress on stderr
  EXPECT_NE(r.err.find("[19/19]"), std::string::npos) << r.err;
  const auto rows = read_csv(dir / "patches.csv");
  ASSERT_EQ(rows.size(), 20u);
  const auto& header = rows[0];
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  for (const char* key : {"y_m", "status", "contact_angle_rad", "rolling_radius_m", "spin_per_m", "normal_force_N",
                          "area_m2", "elements_in_contact", "extent_x1_m", "extent_x2_m", "max_pressure_Pa",
                          "approach_m", "iterations"})
    EXPECT_LT(column(key), header.size()) << key;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    ASSERT_EQ(rows[k].size(), header.size());
    EXPECT_NEAR(std::stod(rows[k][column("y_m")]), -4.5e-3 + 0.5e-3 * static_cast<double>(k - 1), 1e-12);
    EXPECT_EQ(rows[k][column("status")], "single") << "row " << k;
    EXPECT_TRUE(std::filesystem::exists(dir / rows[k][column("patch_file")]));
  }
  for (const char* file : {"summary.md", "contact_position.png", "patch_shapes.png", "patch_size.png"})
    EXPECT_TRUE(std::filesystem::exists(dir / file)) << file;
}

TEST(PatchCli, MalformedProfileNamesFileAndLine) {
  const ScratchDirectory dir("bad_profiles");
  std::ofstream(dir / "wheel.txt") << "0 0\n1 0.1\nfoo bar\n2 0.3\n3 0.5\n";
  expect_one_error_line(run_cli("patch --wheel " + (dir / "wheel.txt").string()), "wheel.txt:3:");
  std::ofstream(dir / "rail.prr") << "header.begin\n type = 0\nheader.end\nspline.begin\n point.begin\n"
                                     "  1.0 2.0\n  1.5 x\n point.end\nspline.end\n";
  expect_one_error_line(run_cli("patch --rail " + (dir / "rail.prr").string()), "rail.prr:7:");
}

class PatchCliBadInput : public ::testing::TestWithParam<std::pair<const char*, const char*>> {};

TEST_P(PatchCliBadInput, OneClearErrorLineAndNonZeroExit) {
  const auto [arguments, expected] = GetParam();
  expect_one_error_line(run_cli(arguments), expected);
}

INSTANTIATE_TEST_SUITE_P(
    Patch, PatchCliBadInput,
    ::testing::Values(std::pair{"patch --wheel /nonexistent/wheel.prw", "/nonexistent/wheel.prw"},
                      std::pair{"patch --rail /nonexistent/rail.prr", "cannot open"},
                      std::pair{"patch --load-N -1", "--load-N must be positive"},
                      std::pair{"patch --load-N 0", "--load-N must be positive"},
                      std::pair{"patch --y-m 1", "never touch"},
                      std::pair{"patch --y-m -0.005 --load-N 10000", "several contact patches"},
                      std::pair{"patch --y-m nan", "--y-m"},
                      std::pair{"patch --elements 0", "--elements"},
                      std::pair{"patch --mesh hexagonal", "mesh"},
                      std::pair{"patch --contact-surface curved", "--contact-surface"},
                      std::pair{"patch --contact-surface conformal --elements 2000",
                                "--elements applies to --contact-surface planar only"},
                      std::pair{"patch --element-size-m 0.0001", "--element-size-m applies to --contact-surface conformal"},
                      std::pair{"patch --contact-surface auto --element-size-m 1e-7", "--element-size-m 1e-07: wheelset: the element size"},
                      std::pair{"patch --load-N 1e9", "too large"},
                      std::pair{"patch --wheel " RAILCONTACT_DATA_DIR "/profiles/MBench_UIC60_v3.prr", "rail profile"},
                      std::pair{"study patches --out /nonexistent/railcontact --y-step-m 0", "step"},
                      std::pair{"study patches --out /nonexistent/railcontact --load-N -5", "--load-N"},
                      std::pair{"study bound --out /nonexistent/railcontact --elements 10", "--elements"},
                      std::pair{"study bound --out /nonexistent/railcontact --y-step-m 0", "--y-step-m"}));

}  // namespace
