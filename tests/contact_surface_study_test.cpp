// `railcontact study surfaces` on a coarse mesh (docs/WHEELSET.md §4 "Choosing the surface"): per
// patch the planar, conformal and automatic surfaces' forces with the automatic surface's measure
// and weight, the blend window swept in fine steps, and bad options named.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_run.hpp"

namespace {

using railcontact::test::CommandResult;
using railcontact::test::read_csv;
using railcontact::test::run_cli;
using railcontact::test::ScratchDirectory;

TEST(ContactSurfaceStudy, ComparesTheSurfacesPerPatchAndSweepsTheBlend) {
  const ScratchDirectory dir("contact_surface_study");
  const std::string data = std::string(RAILCONTACT_DATA_DIR) + "/wheel_rail/";
  const CommandResult r = run_cli("study surfaces " + data + "s1002_uic60.json --element-size-m 0.0005 --y-step-m 0.001 "
                                  "--fine-y-step-m 0.0001 --yaw-rad 0 --no-figures --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = read_csv(dir.path() / "surfaces.csv");
  ASSERT_GT(rows.size(), 15u);  // y = 0, -1, ..., -9 mm, both wheels
  EXPECT_EQ(rows[0][7], "measure");
  EXPECT_EQ(rows[0][8], "conformal_weight");
  const double scale = 0.3 * 98100.0;
  int planar = 0, conformal = 0, blended = 0;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const double measure = std::stod(rows[k][7]), weight = std::stod(rows[k][8]);
    // The automatic surface's forces are the planar ones below the band, the conformal ones above.
    const std::size_t same = measure <= 0.02 ? 9 : measure >= 0.03 ? 12 : 0;
    if (same == 0) {
      ++blended;
      EXPECT_GT(weight, 0.0) << k;
      EXPECT_LT(weight, 1.0) << k;
      continue;
    }
    (same == 9 ? planar : conformal) += 1;
    EXPECT_EQ(weight, same == 9 ? 0.0 : 1.0) << k;
    for (std::size_t i = 0; i < 3; ++i)
      EXPECT_NEAR(std::stod(rows[k][15 + i]), std::stod(rows[k][same + i]), 1e-6 * scale) << k << " " << i;
  }
  EXPECT_GT(planar, 0);
  EXPECT_GT(conformal, 0);
  EXPECT_GT(blended, 0);
  // At the flange the surfaces differ by more than 10 % of μFz in the lateral force.
  const auto& flange = rows[rows.size() - 2][3] == "right" ? rows[rows.size() - 2] : rows[rows.size() - 1];
  EXPECT_GT(std::abs(std::stod(flange[13]) - std::stod(flange[10])), 0.1 * scale);
  // The fine window: 0.1 mm steps across the step where the right wheel's weight changes most.
  const auto fine = read_csv(dir.path() / "smoothness.csv");
  EXPECT_EQ(fine.size(), 12u);  // the header and 11 states
  std::ifstream md(dir.path() / "summary.md");
  std::stringstream text;
  text << md.rdbuf();
  EXPECT_NE(text.str().find("| measure | patches | conformal − planar Fx |"), std::string::npos);
  EXPECT_NE(text.str().find("| s1002_uic60 |"), std::string::npos);
  // The sweep's end is said, with its reason: the flange climbing beyond y = -9 mm.
  EXPECT_NE(text.str().find("- s1002_uic60 at yaw +0 mrad: y = -10.00 mm: "), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("flange is climbing"), std::string::npos);

  const CommandResult bad = run_cli("study surfaces --fine-y-step-m 0.002 --y-step-m 0.001 --out " + dir.string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--fine-y-step-m 0.002 m must lie in [1e-06, 0.001] m (the sweep's step)"), std::string::npos)
      << bad.err;
}

}  // namespace
