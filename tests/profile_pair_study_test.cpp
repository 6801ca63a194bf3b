// `railcontact study profiles` on a coarse mesh (docs/VALIDATION.md "Other profile pairs"): each
// set-up swept from y = 0 to where its flange climbs, the conicity of the shipped pair as EN 15302
// gives it (docs/CONTACT_GEOMETRY.md), nH-FastSim's miss against the exact solver reported for
// every patch, the wheelset table against the sweep's states, and a bad yaw named.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "study/profile_pair_study.hpp"

namespace {

using railcontact::test::CommandResult;
using railcontact::test::run_cli;
using railcontact::test::ScratchDirectory;

using railcontact::test::read_csv;

TEST(ProfilePairStudy, SweepsEachSetUpToItsFlangeClimb) {
  const ScratchDirectory dir("profile_pair_study");
  const std::string data = std::string(RAILCONTACT_DATA_DIR) + "/wheel_rail/";
  const CommandResult r = run_cli("study profiles " + data + "s1002_uic60.json " + data + "car7358_uic60.json" +
                                  " --element-size-m 0.001 --y-step-m 0.001 --yaw-rad 0 --no-figures --out " +
                                  dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto pairs = read_csv(dir.path() / "pairs.csv");
  ASSERT_EQ(pairs.size(), 3u);
  EXPECT_EQ(pairs[0][0], "setup");
  EXPECT_EQ(pairs[0][2], "tan_gamma_e_3mm");
  // The shipped pair: y = 0, -1, ..., -6 mm (its flange climbs beyond -6.5 mm), one patch a wheel
  // up to there, and tan γe(3 mm) = 0.1854 (docs/CONTACT_GEOMETRY.md, EN 15302 Annex C).
  const auto& s1002 = pairs[2][0] == "s1002_uic60" ? pairs[2] : pairs[1];
  EXPECT_EQ(s1002[0], "s1002_uic60");
  EXPECT_NEAR(std::stod(s1002[2]), 0.1854, 5e-4);
  EXPECT_EQ(std::stoi(s1002[3]), 7);
  EXPECT_NEAR(std::stod(s1002[4]), -6.0, 1e-9);
  // The measured wheel reaches further before its flange climbs.
  const auto& car = pairs[1][0] == "car7358_uic60" ? pairs[1] : pairs[2];
  EXPECT_LT(std::stod(car[4]), -6.0);
  // Every patch row has finite misses; on 1 mm elements nH-FastSim stays within 6 % of μF3.
  const auto rows = read_csv(dir.path() / "profile_pairs.csv");
  ASSERT_GT(rows.size(), 20u);
  EXPECT_EQ(rows[0][16], "dF1_percent_mu_F3");
  for (std::size_t k = 1; k < rows.size(); ++k) {
    EXPECT_LT(std::abs(std::stod(rows[k][16])), 6.0) << k;
    EXPECT_LT(std::abs(std::stod(rows[k][17])), 6.0) << k;
  }
  // The wheelset table of each set-up, looked up at every state: both wheels, the vertical balance
  // met (Fz within 0.01 % of μFz of the load the wheelset on the fly meets), Fx and Fy within 5 % of
  // μFz on this coarse recipe (1 mm elements, nodes 1 mm apart; 2.9 % measured), no state refused.
  EXPECT_EQ(pairs[0][16], "table_states");
  EXPECT_EQ(pairs[0].back(), "table_refused_beyond_nadal");
  for (std::size_t k = 1; k < pairs.size(); ++k) {
    EXPECT_EQ(pairs[k][16], pairs[k][3]) << k;
    EXPECT_EQ(pairs[k][17], "0") << k;
    EXPECT_EQ(pairs[k].back(), "0") << k;
  }
  const auto table = read_csv(dir.path() / "table_check.csv");
  ASSERT_EQ(table.size(), 1u + 2u * (7u + std::stoul(car[3])));
  EXPECT_EQ(table[0][11], "dFx_percent_mu_Fz");
  for (std::size_t k = 1; k < table.size(); ++k) {
    EXPECT_LT(std::abs(std::stod(table[k][11])), 5.0) << k;
    EXPECT_LT(std::abs(std::stod(table[k][12])), 5.0) << k;
    EXPECT_LT(std::abs(std::stod(table[k][13])), 0.01) << k;
  }
  std::ifstream summary(dir.path() / "summary.md");
  std::stringstream text;
  text << summary.rdbuf();
  EXPECT_NE(text.str().find("| s1002_uic60 | +0 | 0.185"), std::string::npos) << text.str();

  const CommandResult bad = run_cli("study profiles --yaw-rad 1 --out " + dir.string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--yaw-rad 1 rad must lie in [-0.05, 0.05] rad"), std::string::npos) << bad.err;
}

// On S1002/UIC60 at yaw 10 mrad the right wheel's lateral force rises by 52 kN over the last
// 0.1 mm before the flange climbs (−6.5 to −6.6 mm), ten times its step before: a candidate jump.
// Swept again in 0.01 mm steps it rises continuously (by at most 7 kN a step on 0.2 mm elements),
// so it is swept once and not counted.
TEST(ProfilePairStudy, ASteepButContinuousFlangeRiseIsSweptAgainAndIsNoJump) {
  const ScratchDirectory dir("profile_pair_study_jump");
  const std::string data = std::string(RAILCONTACT_DATA_DIR) + "/wheel_rail/";
  const CommandResult r = run_cli("study profiles " + data + "s1002_uic60.json --element-size-m 0.001 --yaw-rad 0.01"
                                  " --no-table --no-figures --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto pairs = read_csv(dir.path() / "pairs.csv");
  ASSERT_EQ(pairs.size(), 2u);
  ASSERT_EQ(pairs[0][10], "worst_step_N");
  ASSERT_EQ(pairs[0][12], "jumps");
  ASSERT_EQ(pairs[0][13], "fine_swept_steps");
  EXPECT_NEAR(std::stod(pairs[1][4]), -6.6, 1e-9);
  EXPECT_GT(std::stod(pairs[1][10]), 0.03 * 98100.0);
  EXPECT_NEAR(std::stod(pairs[1][11]), -6.6, 1e-9);
  EXPECT_EQ(pairs[1][13], "1");
  EXPECT_EQ(pairs[1][12], "0");
}

// Nadal's limit (tan γ − μ)/(1 + μ tan γ) is tan(γ − arctan μ), the friction angle taken off the
// flange angle: the classical 1.34 at 70° and μ = 0.3, and no climb resistance left (0) where the
// contact angle equals the friction angle.
TEST(ProfilePairStudy, NadalsLimitIsTheTangentOfTheFlangeAngleLessTheFrictionAngle) {
  for (double gamma_deg : {50.0, 63.6, 70.0, 75.0})
    for (double mu : {0.1, 0.3, 0.5}) {
      const double gamma = gamma_deg * M_PI / 180.0;
      EXPECT_NEAR(railcontact::study::nadal_limit(gamma, mu), std::tan(gamma - std::atan(mu)), 1e-12)
          << gamma_deg << " deg, mu " << mu;
    }
  EXPECT_NEAR(railcontact::study::nadal_limit(70.0 * M_PI / 180.0, 0.3), 1.34, 0.005);
  EXPECT_NEAR(railcontact::study::nadal_limit(std::atan(0.3), 0.3), 0.0, 1e-15);
}

}  // namespace
