// Wheel–rail set-up files (railcontact/wheel_rail.hpp): the default pair is data, relative profile
// paths resolve against the set-up file, bad files give one clear error naming the key. Also: the
// umbrella header gives the whole public API.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <optional>

#include "cli_run.hpp"
#include "railcontact/railcontact.hpp"

namespace railcontact {
namespace {

std::string message_of(const std::filesystem::path& path) {
  try {
    (void)read_wheel_rail_setup(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(WheelRailSetup, TheDefaultPairIsTheShippedSetUpFile) {
  const WheelRailSetup setup = read_wheel_rail_setup(default_wheel_rail_setup_path());
  EXPECT_EQ(setup.wheel_profile.filename(), "MBench_S1002_v3.prw");
  EXPECT_EQ(setup.rail_profile.filename(), "MBench_UIC60_v3.prr");
  EXPECT_TRUE(std::filesystem::exists(setup.wheel_profile));
  EXPECT_EQ(setup.track.track_gauge_m, 1.435);
  EXPECT_EQ(setup.track.nominal_rolling_radius_m, 0.46);
  const WheelRailPair pair = default_wheel_rail_pair();
  EXPECT_EQ(pair.parameters().flange_back_distance_m, 1.360);
  // Centred wheelset: the contact point near the taping line, a small contact angle.
  const WheelRailContactPoint c = pair.contact_point(0.0);
  EXPECT_NEAR(c.rolling_radius_m, 0.46, 1e-3);
  EXPECT_GT(c.contact_angle_rad, 0.0);
  EXPECT_LT(c.contact_angle_rad, 0.1);
}

TEST(WheelRailSetup, ProfilePathsResolveAgainstTheSetUpFileAndBadFilesAreNamed) {
  const test::ScratchDirectory dir("setup");  // removed with its files at the end
  std::filesystem::copy_file(default_wheel_profile_path(), dir / "wheel.prw");
  std::filesystem::copy_file(default_rail_profile_path(), dir / "rail.prr");
  const auto write = [&](const std::string& name, const std::string& track_extra) {
    std::ofstream(dir / name) << "{\"wheel_profile\": \"wheel.prw\", \"rail_profile\": \"rail.prr\", \"track\": {"
                              << "\"track_gauge_m\": 1.435, \"gauge_measuring_depth_m\": 0.014, "
                              << "\"flange_back_distance_m\": 1.36, \"flange_back_y_m\": -0.07, "
                              << "\"taping_line_from_flange_back_m\": 0.07, \"nominal_rolling_radius_m\": 0.46"
                              << track_extra << "}}";
    return dir / name;
  };
  const WheelRailSetup setup = read_wheel_rail_setup(write("good.json", ""));
  EXPECT_EQ(setup.wheel_profile, dir / "wheel.prw");
  EXPECT_EQ(load_wheel_rail_pair(setup).contact_point(0.0).contact_angle_rad,
            default_wheel_rail_pair().contact_point(0.0).contact_angle_rad);
  EXPECT_NE(message_of(write("unknown.json", ", \"gauge\": 1")).find("unknown key 'gauge'"), std::string::npos);
  // Where r0 is measured: the profile's origin by default, the taping line on request; another
  // name is refused naming the key and the names allowed.
  EXPECT_EQ(setup.track.nominal_radius_at, NominalRadiusDatum::profile_origin);
  EXPECT_EQ(read_wheel_rail_setup(write("taping.json", ", \"nominal_radius_at\": \"taping-line\"")).track.nominal_radius_at,
            NominalRadiusDatum::taping_line);
  const std::string datum = message_of(write("datum.json", ", \"nominal_radius_at\": \"tape\""));
  EXPECT_NE(datum.find("nominal_radius_at = \"tape\" is not a datum of the nominal rolling radius (allowed: "
                       "\"profile-origin\", the default, as in CONTACT; \"taping-line\")"),
            std::string::npos)
      << datum;
  EXPECT_NE(message_of(write("datum_number.json", ", \"nominal_radius_at\": 0")).find("nominal_radius_at must be a string"),
            std::string::npos);
  std::ofstream(dir / "missing.json") << "{\"wheel_profile\": \"wheel.prw\", \"rail_profile\": \"rail.prr\"}";
  EXPECT_NE(message_of(dir / "missing.json").find("missing object 'track'"), std::string::npos);
  std::ofstream(dir / "broken.json") << "{\"wheel_profile\": ";
  EXPECT_NE(message_of(dir / "broken.json").find("malformed JSON"), std::string::npos);
  try {
    (void)read_wheel_rail_setup(dir / "absent.json");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::io);
  }
}

}  // namespace
}  // namespace railcontact
