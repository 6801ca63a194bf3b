// The rail cant (TrackWheelsetParameters::rail_cant_rad, docs/GEOMETRY.md §1): the rail profile
// inclined towards the track centre before anything uses it. Its sense is checked against an
// independent reference, the CONTACT distribution's inclined UIC60 (MBench_UIC60_v3.prr, inclined
// 1:40 in its coordinates), which the upright 60E1 head (UIC60_upright.prr, written by
// scripts/make_rail_profile.py from the EN 13674-1 head radii) canted by atan(1/40) must reproduce.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_run.hpp"
#include "railcontact/railcontact.hpp"

namespace railcontact {
namespace {

const double kCant1in40_rad = std::atan(1.0 / 40.0);
const double kCant1in20_rad = std::atan(1.0 / 20.0);

std::filesystem::path profile_path(const char* name) {
  return std::filesystem::path(RAILCONTACT_SOURCE_DIR) / "data" / "profiles" / name;
}

Profile upright_uic60() { return read_profile(profile_path("UIC60_upright.prr")); }
Profile inclined_uic60() { return read_profile(profile_path("MBench_UIC60_v3.prr")); }

std::string validation_message(double cant_rad) {
  TrackWheelsetParameters p;
  p.rail_cant_rad = cant_rad;
  try {
    validate(p, "");
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::invalid_input);
    return e.what();
  }
  return "no error";
}

// The highest point (smallest z, z down) of a smoothed profile, scanned every 0.01 mm.
double highest_point_y_m(const SmoothProfile& p) {
  double best_y = p.y_min_m(), best_z = std::numeric_limits<double>::infinity();
  for (double y = p.y_min_m(); y <= p.y_max_m(); y += 1e-5) {
    if (p.z(y) < best_z) {
      best_z = p.z(y);
      best_y = y;
    }
  }
  return best_y;
}

TEST(RailCant, OutOfRangeValuesNameTheKeyTheValueAndTheRange) {
  EXPECT_EQ(validation_message(0.0), "no error");
  EXPECT_EQ(validation_message(kCant1in20_rad), "no error");
  EXPECT_EQ(validation_message(-0.1), "no error");
  // 0.025, the ratio 1/40 given for the angle, is accepted: atan(1/40) differs from it by 5e-6 rad.
  EXPECT_EQ(validation_message(0.025), "no error");
  const std::string ratio = validation_message(40.0);
  EXPECT_NE(ratio.find("rail_cant_rad = 40 rad must lie in [-0.1, 0.1] rad (the rail inclinations in use are 0, "
                       "1:40, 1:30 and 1:20"),
            std::string::npos)
      << ratio;
  EXPECT_NE(ratio.find("an inclination 1:40 is atan(1/40) = 0.0249948 rad"), std::string::npos) << ratio;
  const std::string degrees = validation_message(2.86);
  EXPECT_NE(degrees.find("2.86 degrees would be 0.0499164 rad"), std::string::npos) << degrees;
  EXPECT_NE(validation_message(std::nan("")).find("rail_cant_rad = nan rad"), std::string::npos);
  EXPECT_NE(validation_message(0.11).find("rail_cant_rad = 0.11 rad must lie in"), std::string::npos);
  // The pair names the parameter before it touches a profile.
  TrackWheelsetParameters p;
  p.rail_cant_rad = 1.0 / 0.0;
  try {
    (void)WheelRailPair(read_profile(default_wheel_profile_path()), inclined_uic60(), p);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("track parameters: rail_cant_rad = inf rad"), std::string::npos) << e.what();
  }
}

// The rail's upward axis leans towards the track centre (-y): a point above the origin moves to
// -y; the crown then faces the track centre, so every point of the rail's surface has its contact
// angle (positive: the normal into the wheel leaning towards the track centre) larger by the cant,
// and the crown's highest point moves towards the FIELD side, by R sin c = 7.5 mm for the R300
// crown at 1:40 (the shipped, inclined MBench_UIC60_v3.prr has its highest point 7.5 mm on the
// field side of its head's axis, too: see the reference test below).
TEST(RailCant, TheRailLeansTowardsTheTrackCentre) {
  Profile point;
  point.y_m = {0.0};
  point.z_m = {-0.010};  // 10 mm above the origin (z down)
  const Profile turned = canted_rail_profile(point, kCant1in40_rad);
  EXPECT_NEAR(turned.y_m[0], -0.010 * std::sin(kCant1in40_rad), 1e-15);
  EXPECT_NEAR(turned.z_m[0], -0.010 * std::cos(kCant1in40_rad), 1e-15);

  const Profile upright = upright_uic60();
  const Profile same = canted_rail_profile(upright, 0.0);
  EXPECT_EQ(same.y_m, upright.y_m);  // cant 0: the profile as given (the same values, no arithmetic)
  const SmoothProfile flat(upright), canted(canted_rail_profile(upright, kCant1in40_rad));
  // The upright head is symmetric: its top on the axis (within the 0.01 mm scan).
  EXPECT_NEAR(highest_point_y_m(flat), 0.0, 0.02e-3);
  EXPECT_NEAR(highest_point_y_m(canted), 0.300 * std::sin(kCant1in40_rad), 0.02e-3);
  // The same material points, y = -20 ... 20 mm on the upright rail: the contact angle atan(-dz/dy)
  // grows by the cant. Tolerance 1e-6 rad: the smoothing spline of the turned points is the turned
  // spline (chord-length parameter and penalty are invariant under rotation) up to the graph form's
  // root finding.
  for (double y = -0.020; y <= 0.020; y += 0.005) {
    const double z = flat.z(y);
    const double y_canted = std::cos(kCant1in40_rad) * y + std::sin(kCant1in40_rad) * z;
    const double angle_flat = std::atan(-flat.dz_dy(y)), angle_canted = std::atan(-canted.dz_dy(y_canted));
    EXPECT_NEAR(angle_canted - angle_flat, kCant1in40_rad, 1e-6) << "y = " << y * 1e3 << " mm";
  }
}

// The reference: the upright 60E1 canted by atan(1/40) against CONTACT's inclined UIC60. The two
// files put their origins at different points (the upright rail's at the top of the crown on its
// axis, which the cant turns about; the inclined file's at the top of the inclined rail, 7.5 mm to
// the field side): both are placed as the track places a rail, by the gauge point 14 mm below the
// top laterally and by the top vertically (the offsets below), then z(y) of the smoothed
// profiles is compared over the head, |y| < 30 mm from the canted rail's axis. Measured: 0.043 mm
// at most (the inclined file is a sampled UIC60, the other the drawing's arcs; aligned by a
// least-squares fit instead of the gauge point, 0.025 mm), so the tolerance is 0.05 mm. The
// opposite sense of rotation differs by 0.66 mm even at its best alignment.
TEST(RailCant, TheCantedUprightUic60IsTheShippedInclinedUic60) {
  const Profile wheel = read_profile(default_wheel_profile_path());
  TrackWheelsetParameters canted_track;
  canted_track.rail_cant_rad = kCant1in40_rad;
  const WheelRailPair canted(wheel, upright_uic60(), canted_track), shipped(wheel, inclined_uic60());
  const double dy = shipped.rail_gauge_point_y_m() - canted.rail_gauge_point_y_m();
  const double dz = shipped.rail_top_z_m() - canted.rail_top_z_m();
  EXPECT_NEAR(dy, -7.5e-3, 0.3e-3);  // the origins' lateral distance: about R300 sin c
  EXPECT_NEAR(dz, 0.094e-3, 0.05e-3);  // ... and vertical: R300 (1 - cos c)
  double largest = 0.0;
  for (double y = -0.030; y <= 0.030; y += 0.1e-3) {
    const double difference = shipped.rail().z(y + dy) - (canted.rail().z(y) + dz);
    largest = std::max(largest, std::abs(difference));
  }
  EXPECT_LT(largest, 0.05e-3) << "largest difference " << largest * 1e3 << " mm";
  EXPECT_GT(largest, 0.0);  // two different profiles
}

WheelsetTrack track_on(const Profile& rail, double cant_rad) {
  TrackWheelsetParameters t;
  t.rail_cant_rad = cant_rad;
  return WheelsetTrack(read_profile(default_wheel_profile_path()), rail, t);
}

// The rigid contact geometry of S1002 on the canted upright rail and on the shipped inclined rail,
// y = -6 ... 6 mm. Tread and crown nearly conform, so the heads' 0.04 mm difference of shape moves
// the contact point and the flange contact's onset: measured, the contact angles differ by
// 5.3 mrad at most, the rolling-radius difference Δr by 5.1 % (at y = ±4.8 mm; 3.5 % at ±3 mm),
// and the flange contact (γ > 0.2 rad) begins at |y| = 4.9 mm on the shipped rail, 5.1 mm on the
// canted one. Tolerances: 7 mrad and 7 % where both wheels touch on the same part (tread or
// flange), the onset within 0.3 mm, and the equivalent conicity at 3 mm within 5 % (0.1774 and
// 0.1838: 3.5 %).
TEST(RailCant, TheRigidContactGeometryOnTheCantedUprightRailIsThatOfTheShippedRail) {
  const WheelsetTrack canted = track_on(upright_uic60(), kCant1in40_rad), shipped = track_on(inclined_uic60(), 0.0);
  const auto a = rigid_contact_sweep(canted, -6e-3, 6e-3, 0.1e-3), b = rigid_contact_sweep(shipped, -6e-3, 6e-3, 0.1e-3);
  ASSERT_EQ(a.size(), b.size());
  constexpr double kFlange_rad = 0.2;
  const auto on_flange = [&](const RigidContactGeometry& g) {
    return std::max(g.right.contact_angle_rad, g.left.contact_angle_rad) > kFlange_rad;
  };
  double onset_a = 1.0, onset_b = 1.0;  // the smallest |y| with flange contact
  for (std::size_t k = 0; k < a.size(); ++k) {
    const double y = a[k].lateral_displacement_m;
    if (on_flange(a[k])) onset_a = std::min(onset_a, std::abs(y));
    if (on_flange(b[k])) onset_b = std::min(onset_b, std::abs(y));
    if (on_flange(a[k]) != on_flange(b[k])) continue;
    EXPECT_NEAR(a[k].right.contact_angle_rad, b[k].right.contact_angle_rad, 7e-3) << "y = " << y * 1e3 << " mm";
    EXPECT_NEAR(a[k].left.contact_angle_rad, b[k].left.contact_angle_rad, 7e-3) << "y = " << y * 1e3 << " mm";
    EXPECT_NEAR(a[k].rolling_radius_difference_m, b[k].rolling_radius_difference_m,
                0.07 * std::abs(b[k].rolling_radius_difference_m) + 1e-9)
        << "y = " << y * 1e3 << " mm";
  }
  EXPECT_LT(onset_b, 5.5e-3);  // both reach the flange within the sweep
  EXPECT_NEAR(onset_a, onset_b, 0.3e-3 + 1e-9);
  const double conicity_canted = equivalent_conicity(RollingRadiusDifference(a), 3e-3).tan_gamma_e_wavelength;
  const double conicity_shipped = equivalent_conicity(RollingRadiusDifference(b), 3e-3).tan_gamma_e_wavelength;
  EXPECT_NEAR(conicity_canted / conicity_shipped, 1.0, 0.05) << conicity_canted << " " << conicity_shipped;
}

// A centred S1002 on the same rail vertical, at 1:40 and at 1:20: the more the crown faces the
// track centre, the further its point of the wheel's slope lies to the field side, where the
// S1002's tread is flatter: the contact moves to the field side of the tread and its angle falls
// (measured 0.074, 0.024, 0.009 rad). The contact angle changes by more than the cant because
// the tread and the crown nearly conform (R300 crown, a tread curving by about 1/265 mm).
TEST(RailCant, ACentredS1002TouchesFurtherOutAndFlatterTheMoreTheRailIsCanted) {
  const Profile upright = upright_uic60();
  double previous_angle = std::numeric_limits<double>::infinity(), previous_y = -std::numeric_limits<double>::infinity();
  for (double cant : {0.0, kCant1in40_rad, kCant1in20_rad}) {
    const RigidContactGeometry g = rigid_contact_geometry(track_on(upright, cant), 0.0);
    EXPECT_LT(g.right.contact_angle_rad, previous_angle) << "cant " << cant;
    EXPECT_GT(g.right.wheel_profile_y_m, previous_y + 5e-3) << "cant " << cant;
    EXPECT_NEAR(g.left.contact_angle_rad, g.right.contact_angle_rad, 1e-9);  // the same code path, mirrored
    previous_angle = g.right.contact_angle_rad;
    previous_y = g.right.wheel_profile_y_m;
  }
  // On the 1:40 canted rail the contact sits near the S1002's taping line and its 1:40 tread slope.
  const RigidContactGeometry at_1in40 = rigid_contact_geometry(track_on(upright, kCant1in40_rad), 0.0);
  EXPECT_NEAR(at_1in40.right.contact_angle_rad, kCant1in40_rad, 2e-3);
  EXPECT_NEAR(at_1in40.right.wheel_profile_y_m, 3.2e-3, 1e-3);
}

TEST(RailCant, TheSetUpKeyIsOptionalAndChecked) {
  const test::ScratchDirectory dir("rail_cant_setup");
  const auto write = [&](const std::string& name, const std::string& extra) {
    std::ofstream(dir / name) << "{\"wheel_profile\": \"" << default_wheel_profile_path().string()
                              << "\", \"rail_profile\": \"" << profile_path("UIC60_upright.prr").string()
                              << "\", \"track\": {\"track_gauge_m\": 1.435, \"gauge_measuring_depth_m\": 0.014, "
                              << "\"flange_back_distance_m\": 1.36, \"flange_back_y_m\": -0.07, "
                              << "\"taping_line_from_flange_back_m\": 0.07, \"nominal_rolling_radius_m\": 0.46" << extra
                              << "}}";
    return dir / name;
  };
  const auto message = [](const std::filesystem::path& file) {
    try {
      (void)read_wheel_rail_setup(file);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(read_wheel_rail_setup(write("plain.json", "")).track.rail_cant_rad, 0.0);
  EXPECT_EQ(read_wheel_rail_setup(write("canted.json", ", \"rail_cant_rad\": 0.0249948")).track.rail_cant_rad, 0.0249948);
  const std::string ratio = message(write("ratio.json", ", \"rail_cant_rad\": 40"));
  EXPECT_NE(ratio.find("ratio.json: track: rail_cant_rad = 40 rad must lie in [-0.1, 0.1] rad"), std::string::npos)
      << ratio;
  EXPECT_NE(ratio.find("atan(1/40) = 0.0249948 rad"), std::string::npos) << ratio;
  const std::string text = message(write("text.json", ", \"rail_cant_rad\": \"1:40\""));
  EXPECT_NE(text.find("'rail_cant_rad' must be a finite number (got \"1:40\")"), std::string::npos) << text;
}

// `railcontact geometry --rail-cant-rad` cants the rail of the default set-up (or of --rail): the
// upright rail canted 1:40 on the command line is the set-up file's canted rail (the same code
// path: equal to the last digit), and a bad value is one error naming the option.
TEST(RailCant, TheGeometryCommandTakesTheCant) {
  const test::ScratchDirectory dir("rail_cant_cli");
  const std::string rail = profile_path("UIC60_upright.prr").string();
  const test::CommandResult canted =
      test::run_cli("geometry --rail " + rail + " --rail-cant-rad 0.02499479361892016 --json --out " + (dir / "a").string());
  ASSERT_EQ(canted.exit_code, 0) << canted.err;
  const test::CommandResult vertical =
      test::run_cli("geometry --rail " + rail + " --json --out " + (dir / "b").string());
  ASSERT_EQ(vertical.exit_code, 0) << vertical.err;
  const auto conicity = [](const std::string& out) {
    return nlohmann::json::parse(out)["tan_gamma_e_wavelength"].get<double>();
  };
  const WheelsetTrack track = track_on(upright_uic60(), 0.02499479361892016);
  const auto sweep = rigid_contact_sweep(track, -6e-3, 6e-3, 0.1e-3);
  // The command's sweep steps y itself: the same positions within rounding, so 1e-9 relative.
  EXPECT_NEAR(conicity(canted.out) / equivalent_conicity(RollingRadiusDifference(sweep), 3e-3).tan_gamma_e_wavelength,
              1.0, 1e-9);
  EXPECT_NE(conicity(canted.out), conicity(vertical.out));
  EXPECT_NE(nlohmann::json::parse(canted.out)["profiles"].get<std::string>().find("rail cant 0.0249948 rad"),
            std::string::npos);
  const test::CommandResult bad = test::run_cli("geometry --rail-cant-rad 40");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--rail-cant-rad = 40 rad must lie in [-0.1, 0.1] rad"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace railcontact
