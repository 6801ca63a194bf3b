// The rail normal angle's range over each patch (InterpenetrationRegion::contact_angle_min_rad,
// _max_rad, contact_angle_variation_rad; docs/WHEELSET.md §4 "Angle variation") on S1002/UIC60:
// the range holds the contact angle; on the tread at y = 0 it stays below the flag; where the
// contact runs from the flange root onto the flange it spans more than 0.2 rad (Kalker's CONTACT in
// its conformal mode finds 0.33 to 0.82 rad at y = -6.5 mm, issue #31), and the CLI's JSON and text
// output flag it (the text with the remedy, on a planar patch only).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_run.hpp"
#include "railcontact/wheelset.hpp"

namespace railcontact {
namespace {

WheelsetResult evaluate_at(double y_m) {
  WheelsetOptions options;
  options.element_size_m = 0.5e-3;
  Wheelset wheelset(default_wheelset_track(), options);
  WheelsetState state;
  state.position.lateral_displacement_m = y_m;
  return wheelset.evaluate(state);
}

TEST(ContactAngleVariation, NarrowOnTheTreadWideOnTheFlangeRoot) {
  const WheelsetResult centred = evaluate_at(0.0);
  for (const WheelResult& w : centred.wheels) {
    ASSERT_EQ(w.patches.size(), 1u);
    const InterpenetrationRegion& g = w.patches[0].region;
    EXPECT_LE(g.contact_angle_min_rad, g.contact_angle_rad);
    EXPECT_GE(g.contact_angle_max_rad, g.contact_angle_rad);
    EXPECT_LT(contact_angle_variation_rad(g), kLargeContactAngleVariation_rad);  // the crown: 0.062 rad, not flagged
  }
  // At y = -6.5 mm the right wheel's patch runs from the flange root onto the flange: its normal
  // turns by more than 0.2 rad (issue #31: 19 to 47 degrees) and the patch is flagged.
  const WheelsetResult at_flange = evaluate_at(-6.5e-3);
  const InterpenetrationRegion& flange = at_flange.wheels[0].patches[0].region;
  EXPECT_GT(flange.contact_angle_max_rad - flange.contact_angle_min_rad, 0.2);
  EXPECT_GT(contact_angle_variation_rad(flange), kLargeContactAngleVariation_rad);
}

TEST(ContactAngleVariation, TheJsonAndTheTextFlagALargeVariation) {
  const test::CommandResult flange = test::run_cli("wheelset --y-m -0.0065 --element-size-m 0.0005 --json");
  ASSERT_EQ(flange.exit_code, 0) << flange.err;
  const nlohmann::json j = nlohmann::json::parse(flange.out);
  const nlohmann::json& patch = j.at("wheels").at(0).at("patches").at(0);
  EXPECT_TRUE(patch.at("large_angle_variation").get<bool>());
  EXPECT_GT(patch.at("contact_angle_variation_rad").get<double>(), 0.1);
  EXPECT_EQ(patch.at("contact_angle_range_rad").size(), 2u);
  const test::CommandResult text = test::run_cli("wheelset --y-m -0.0065 --element-size-m 0.0005");
  EXPECT_NE(text.out.find("note: the rail's normal angle varies over the patch"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("--contact-surface auto (or conformal) solves it on the curved surface"), std::string::npos)
      << text.out;
  // On the curved surface the same patch is solved as its angle varies: no note.
  const test::CommandResult curved =
      test::run_cli("wheelset --y-m -0.0065 --element-size-m 0.0005 --contact-surface conformal");
  ASSERT_EQ(curved.exit_code, 0) << curved.err;
  EXPECT_NE(curved.out.find("contact surface: conformal"), std::string::npos) << curved.out;
  EXPECT_EQ(curved.out.find("note: the rail's normal angle"), std::string::npos) << curved.out;
  const test::CommandResult tread = test::run_cli("wheelset --y-m 0 --element-size-m 0.0005 --json");
  ASSERT_EQ(tread.exit_code, 0) << tread.err;
  EXPECT_FALSE(nlohmann::json::parse(tread.out).at("wheels").at(0).at("patches").at(0).at("large_angle_variation").get<bool>());
}

}  // namespace
}  // namespace railcontact
