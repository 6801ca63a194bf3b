// Wheel–rail contact geometry: S1002 wheel on UIC60 rail (1:40) as in METHOD.md §9, and an
// analytic pair (a cylinder on a circular crown) for the exact undeformed distance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "railcontact/error.hpp"
#include "railcontact/geometry.hpp"

namespace railcontact {
namespace {

constexpr double kMm = 1e-3;
const std::filesystem::path kProfiles = std::filesystem::path(RAILCONTACT_DATA_DIR) / "profiles";

const WheelRailPair& s1002_uic60() {
  static const WheelRailPair pair(read_profile(kProfiles / "MBench_S1002_v3.prw"),
                                  read_profile(kProfiles / "MBench_UIC60_v3.prr"));
  return pair;
}

// Lateral displacements -4.5 ... 4.5 mm in 0.5 mm steps.
std::vector<double> displacements() {
  std::vector<double> y;
  for (int k = -9; k <= 9; ++k) y.push_back(0.5 * k * kMm);
  return y;
}

TEST(WheelRail, PlacesProfilesOnTheTrack) {
  const WheelRailPair& pair = s1002_uic60();
  // Taping line 70 mm from the flange back (y = -70 mm): the wheel file's origin, radius 0.46 m.
  EXPECT_DOUBLE_EQ(pair.taping_line_y_m(), 0.0);
  EXPECT_NEAR(pair.taping_line_z_m(), 0.0, 1e-7);
  // r0 is measured at the profile's origin (the default): the smoothed profile passes within 1e-10
  // m of it; at the taping line it is r0 exactly.
  EXPECT_NEAR(pair.wheel_radius_m(0.0), 0.46, 1e-9);
  TrackWheelsetParameters at_taping_line;
  at_taping_line.nominal_radius_at = NominalRadiusDatum::taping_line;
  const WheelRailPair taping(read_profile(kProfiles / "MBench_S1002_v3.prw"),
                             read_profile(kProfiles / "MBench_UIC60_v3.prr"), at_taping_line);
  EXPECT_DOUBLE_EQ(taping.wheel_radius_m(0.0), 0.46);
  EXPECT_NEAR(pair.wheel_radius_m(-54.5 * kMm) - 0.46, 28.0 * kMm, 0.1 * kMm);  // flange tip
  // Top of the rail near the rail file's origin; gauge face 14 mm below it at y = -43.0 mm.
  EXPECT_NEAR(pair.rail_top_z_m(), 0.0, 1e-6);
  EXPECT_NEAR(pair.rail_gauge_point_y_m(), -43.02 * kMm, 0.05 * kMm);
  // (The gauge face is nearly vertical: z(y) is ill-conditioned there.)
  EXPECT_NEAR(pair.rail().z(pair.rail_gauge_point_y_m()), 14.0 * kMm, 1e-7);
}

TEST(WheelRail, ContactAtCentredWheelsetLiesOnTheTread) {
  const WheelRailPair& pair = s1002_uic60();
  const WheelRailContactPoint c = pair.contact_point(0.0);
  EXPECT_LT(std::abs(c.y_wheel_m - pair.taping_line_y_m()), 10.0 * kMm);
  EXPECT_GT(c.contact_angle_rad, 0.015);  // about the 1:40 cant (0.025)
  EXPECT_LT(c.contact_angle_rad, 0.035);
  EXPECT_NEAR(c.rolling_radius_m, 0.46, 1.0 * kMm);
  EXPECT_NEAR(c.rolling_radius_m, pair.wheel_radius_m(c.y_wheel_m), 1e-12);
  // The same point seen from both profiles, and in the track frame (right rail, y to the left).
  EXPECT_NEAR(c.z_rail_m, pair.rail().z(c.y_rail_m), 1e-12);
  EXPECT_NEAR(c.z_rail_m, c.z_wheel_m + c.wheel_drop_m, 1e-12);
  EXPECT_NEAR(c.y_rail_m, c.y_wheel_m + c.wheel_to_rail_offset_m, 1e-12);
  EXPECT_NEAR(c.y_track_m, -(0.5 * 1.435 - pair.rail_gauge_point_y_m() + c.y_rail_m), 1e-12);
  // Common tangent: the slopes of the two profiles agree.
  EXPECT_NEAR(pair.rail().dz_dy(c.y_rail_m), pair.wheel().dz_dy(c.y_wheel_m), 1e-9);
}

TEST(WheelRail, NegativeDisplacementMovesContactTowardsTheFlange) {
  const WheelRailPair& pair = s1002_uic60();
  std::vector<WheelRailContactPoint> table;
  std::printf("    y/mm  y_rail/mm  y_wheel/mm  gamma/rad  r/mm      second gap/um\n");
  for (const double y : displacements()) {
    table.push_back(pair.contact_point(y));
    const auto& c = table.back();
    std::printf("  %6.2f  %9.3f  %10.3f  %9.5f  %8.3f  %10.3f\n", y / kMm, c.y_rail_m / kMm, c.y_wheel_m / kMm,
                c.contact_angle_rad, c.rolling_radius_m / kMm, c.secondary_gap_m * 1e6);
  }
  for (std::size_t k = 0; k + 1 < table.size(); ++k) {
    // More negative y: contact further towards the gauge corner / flange, steeper, larger radius.
    EXPECT_LE(table[k].y_rail_m, table[k + 1].y_rail_m);
    EXPECT_LE(table[k].y_wheel_m, table[k + 1].y_wheel_m);
    EXPECT_GE(table[k].contact_angle_rad, table[k + 1].contact_angle_rad);
    EXPECT_GE(table[k].rolling_radius_m, table[k + 1].rolling_radius_m);
  }
  EXPECT_GT(table.front().contact_angle_rad, 0.1);  // y = -4.5 mm: near the flange root
  EXPECT_LT(table.back().contact_angle_rad, 0.012);
  // The known contact jump of S1002 on UIC60 1:40 between y = -0.5 and 0 mm (two-point contact
  // near y = -0.21 mm): the contact point on the rail jumps by about 11 mm.
  EXPECT_GT(table[9].y_rail_m - table[8].y_rail_m, 8.0 * kMm);
  EXPECT_LT(table[8].secondary_gap_m, 20e-6);
  EXPECT_LT(table[9].secondary_gap_m, 20e-6);
}

TEST(WheelRail, ContactFrameIsRightHanded) {
  const WheelRailContactPoint c = s1002_uic60().contact_point(-3.0 * kMm);
  const auto& e2 = c.x2_axis_track;
  const auto& e3 = c.x3_axis_track;
  // X1 = (1, 0, 0): X1 × X2 = (0, -e2z, e2y) must equal X3.
  EXPECT_NEAR(-e2[2], e3[1], 1e-15);
  EXPECT_NEAR(e2[1], e3[2], 1e-15);
  EXPECT_NEAR(e3[1], std::sin(c.contact_angle_rad), 1e-15);  // leans towards the track centre (+y)
  EXPECT_NEAR(e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2], 1.0, 1e-15);
}

TEST(WheelRail, UndeformedDistanceVanishesAtContactAndIsNonNegative) {
  const WheelRailPair& pair = s1002_uic60();
  for (const double y : {-4.5 * kMm, -2.0 * kMm, -0.5 * kMm, 0.0, 3.0 * kMm}) {
    const WheelRailContactPoint c = pair.contact_point(y);
    EXPECT_NEAR(pair.undeformed_distance(c, 0.0, 0.0), 0.0, 1e-9);
    // Odd element counts: the centre element sits on the contact point.
    const Mesh mesh = Mesh::covering(-8.2 * kMm, 8.2 * kMm, -6.15 * kMm, 6.15 * kMm, 41, 41);
    const std::vector<double> h = pair.undeformed_distance(c, mesh);
    EXPECT_NEAR(h[mesh.index(20, 20)], 0.0, 1e-9) << "y = " << y;
    EXPECT_GE(*std::min_element(h.begin(), h.end()), -1e-12) << "y = " << y;
    // Symmetric in x1 (zero yaw), growing away from the contact along X1.
    EXPECT_NEAR(h[mesh.index(3, 11)], h[mesh.index(37, 11)], 1e-12);
    EXPECT_GT(h[mesh.index(3, 20)], h[mesh.index(10, 20)]);
  }
}

TEST(WheelRail, UndeformedDistanceMatchesLocalQuadraticForm) {
  const WheelRailPair& pair = s1002_uic60();
  for (const double y : {-3.0 * kMm, 0.0, 3.0 * kMm}) {
    const WheelRailContactPoint c = pair.contact_point(y);
    EXPECT_NEAR(c.A_per_m, std::cos(c.contact_angle_rad) / (2.0 * c.rolling_radius_m), 1e-15);
    const double x1 = 2.0 * kMm;
    EXPECT_NEAR(pair.undeformed_distance(c, x1, 0.0) / (c.A_per_m * x1 * x1), 1.0, 1e-4) << "y = " << y;
    // Lateral direction: the even part of h; odd (cubic) terms cancel.
    const double x2 = 0.2 * kMm;
    const double even = 0.5 * (pair.undeformed_distance(c, 0.0, x2) + pair.undeformed_distance(c, 0.0, -x2));
    EXPECT_NEAR(even / (c.B_per_m * x2 * x2), 1.0, 0.02) << "y = " << y;
    // And both together.
    const double both = pair.undeformed_distance(c, x1, x2) + pair.undeformed_distance(c, x1, -x2);
    EXPECT_NEAR(0.5 * both / (c.A_per_m * x1 * x1 + c.B_per_m * x2 * x2), 1.0, 0.02) << "y = " << y;
  }
}

// A cylinder of radius 0.46 m with a flange (wheel) on a rail whose crown is a circle of radius
// 0.2 m: the contact is at the crown top with γ = 0 and, exactly,
// h(x1, x2) = R - sqrt(R² - x2²) + r - sqrt(r² - x1²).
TEST(WheelRail, ExactUndeformedDistanceOfCylinderOnCircularCrown) {
  constexpr double crown = 0.2;
  Profile wheel{{}, {}, ProfileKind::wheel, "synthetic wheel"};
  for (double y = -70.0; y <= 60.0 + 1e-9; y += 0.25) {
    const double flange = y < -30.0 ? 25.0 * std::pow((-30.0 - y) / 40.0, 2) : 0.0;
    wheel.y_m.push_back(y * kMm);
    wheel.z_m.push_back(flange * kMm);
  }
  Profile rail{{}, {}, ProfileKind::rail, "synthetic rail"};
  const double edge_z = crown - std::sqrt(crown * crown - 0.02 * 0.02);
  for (double d = 40.0; d > 0.0; d -= 0.25) {  // gauge side, nearly vertical
    rail.y_m.push_back((-20.0 - 0.05 * d) * kMm);
    rail.z_m.push_back(edge_z + d * kMm);
  }
  for (double y = -20.0; y <= 20.0 + 1e-9; y += 0.25) {
    rail.y_m.push_back(y * kMm);
    rail.z_m.push_back(crown - std::sqrt(crown * crown - y * kMm * y * kMm));
  }
  for (double d = 0.25; d <= 40.0 + 1e-9; d += 0.25) {  // field side
    rail.y_m.push_back((20.0 + 0.05 * d) * kMm);
    rail.z_m.push_back(edge_z + d * kMm);
  }
  const WheelRailPair pair(wheel, rail);
  const WheelRailContactPoint c = pair.contact_point(0.0);
  EXPECT_NEAR(c.y_rail_m, 0.0, 1e-9);
  EXPECT_NEAR(c.contact_angle_rad, 0.0, 1e-9);
  EXPECT_NEAR(c.rolling_radius_m, 0.46, 1e-12);
  EXPECT_NEAR(c.B_per_m, 0.5 / crown, 1e-6);
  for (const double x1 : {0.0, 3.0 * kMm, 15.0 * kMm}) {
    for (const double x2 : {-8.0 * kMm, -1.0 * kMm, 0.5 * kMm, 8.0 * kMm}) {
      const double exact =
          crown - std::sqrt(crown * crown - x2 * x2) + 0.46 - std::sqrt(0.46 * 0.46 - x1 * x1);
      EXPECT_NEAR(pair.undeformed_distance(c, x1, x2), exact, 1e-9) << "x1 = " << x1 << ", x2 = " << x2;
    }
  }
}

TEST(WheelRail, PotentialContactAreaHoldsTheMarginRegion) {
  const WheelRailPair& pair = s1002_uic60();
  for (const double y : {-3.0 * kMm, 0.0}) {
    const WheelRailContactPoint c = pair.contact_point(y);
    const double approach = 0.05 * kMm;
    const PotentialAreaOptions options;
    const PotentialContactArea area = potential_contact_area(pair, c, approach, options);
    const Mesh& m = area.mesh;
    ASSERT_EQ(area.h_m.size(), m.size());
    // The contact point lies inside; no element of the border ring has h < 1.5 approach.
    EXPECT_LT(m.x1(0), 0.0);
    EXPECT_GT(m.x1(m.n1 - 1), 0.0);
    EXPECT_LT(m.x2(0), 0.0);
    EXPECT_GT(m.x2(m.n2 - 1), 0.0);
    int interpenetrating = 0;
    for (int i2 = 0; i2 < m.n2; ++i2) {
      for (int i1 = 0; i1 < m.n1; ++i1) {
        const double h = area.h_m[m.index(i1, i2)];
        const bool border = i1 < options.border_elements || i1 >= m.n1 - options.border_elements ||
                            i2 < options.border_elements || i2 >= m.n2 - options.border_elements;
        if (border) {
          EXPECT_GE(h, options.margin_factor * approach);
        }
        interpenetrating += h < approach ? 1 : 0;
      }
    }
    // About elements_across elements across the region h < approach in each direction.
    EXPECT_GT(interpenetrating, options.elements_across * options.elements_across / 2);
    EXPECT_LT(interpenetrating, 2 * options.elements_across * options.elements_across);
    EXPECT_NEAR(area.h_m[m.index(m.n1 / 3, m.n2 / 2)], pair.undeformed_distance(c, m.x1(m.n1 / 3), m.x2(m.n2 / 2)),
                1e-15);
  }
}

TEST(WheelRail, PotentialContactAreaIncludesSecondRegionNearTwoPointContact) {
  const WheelRailPair& pair = s1002_uic60();
  const WheelRailContactPoint c = pair.contact_point(-0.225 * kMm);
  ASSERT_LT(c.secondary_gap_m, 1e-6);  // two minima of the vertical gap ~10 mm apart
  const double approach = 0.03 * kMm;
  const PotentialContactArea area = potential_contact_area(pair, c, approach);
  const Mesh& m = area.mesh;
  // Lateral position of the second minimum in the tangent plane: x2 = (P - C)·X2.
  const double x2_second = (c.secondary_y_rail_m - c.y_rail_m) * -std::cos(c.contact_angle_rad) +
                           (pair.rail().z(c.secondary_y_rail_m) - c.z_rail_m) * std::sin(c.contact_angle_rad);
  EXPECT_LT(std::abs(x2_second), 15.0 * kMm);
  EXPECT_GT(std::abs(x2_second), 5.0 * kMm);
  EXPECT_LT(m.x2(0), x2_second);
  EXPECT_GT(m.x2(m.n2 - 1), x2_second);
  // Around x2_second, on the row x1 ≈ 0, h comes down to about the secondary gap.
  const int i1 = m.n1 / 2;
  double h_min_there = 1.0;
  for (int i2 = 0; i2 < m.n2; ++i2) {
    if (std::abs(m.x2(i2) - x2_second) < 1.0 * kMm) h_min_there = std::min(h_min_there, area.h_m[m.index(i1, i2)]);
  }
  EXPECT_LT(h_min_there, 0.5 * approach);
}

TEST(WheelRail, ProfilesThatNeverTouchThrow) {
  const WheelRailPair& pair = s1002_uic60();
  for (const double y : {1.0, -1.0}) {
    try {
      (void)pair.contact_point(y);
      ADD_FAILURE() << "no error for y = " << y;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("never touch"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW((void)potential_contact_area(pair, pair.contact_point(0.0), -1.0), Error);
}

TEST(WheelRail, RejectsWronglyOrientedProfiles) {
  const Profile wheel = read_profile(kProfiles / "MBench_S1002_v3.prw");
  const Profile rail = read_profile(kProfiles / "MBench_UIC60_v3.prr");
  EXPECT_THROW(WheelRailPair(mirrored_y(wheel), rail), Error);  // flange at +y
  EXPECT_THROW(WheelRailPair(wheel, mirrored_z(rail)), Error);  // z up
  EXPECT_THROW(WheelRailPair(wheel, mirrored_y(rail)), Error);  // gauge side at +y
  EXPECT_THROW(WheelRailPair(rail, rail), Error);               // a rail as the wheel
  // An upright rail with 2 mm of side wear has its top 1.0 mm on the gauge side of the head's
  // centre at the gauge depth: a worn rail, not a mirrored one (it was refused up to 2026-11-29).
  const Profile worn_upright = read_profile(kProfiles / "UIC60_gauge_corner_worn.prr");
  const WheelRailPair worn(wheel, worn_upright);
  const double angle = worn.contact_point(0.0).contact_angle_rad;  // on the crown
  EXPECT_TRUE(angle > -0.05 && angle < 0.15) << angle;
  // An upright new rail is its own mirror image.
  EXPECT_NO_THROW(WheelRailPair(wheel, mirrored_y(read_profile(kProfiles / "UIC60_upright.prr"))));
  TrackWheelsetParameters bad;
  bad.track_gauge_m = 0.0;
  EXPECT_THROW(WheelRailPair(wheel, rail, bad), Error);
}

}  // namespace
}  // namespace railcontact
