// The wheelset's 3-D contact geometry (docs/WHEELSET.md §1–4) on S1002 / UIC60 1:40: agreement
// with the zero-yaw wheel–rail pair, mirror symmetry of the two wheels, the classic contact-point
// lead of a yawed wheel, smooth reference points, separate tread and flange regions.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/wheel_locus.hpp"
#include "geometry/wheelset_frames.hpp"
#include "railcontact/error.hpp"
#include "railcontact/wheel_rail.hpp"
#include "railcontact/geometry.hpp"
#include "railcontact/wheelset_geometry.hpp"

namespace railcontact {
namespace {

constexpr double kMm = 1e-3;
const std::filesystem::path kProfiles = std::filesystem::path(RAILCONTACT_DATA_DIR) / "profiles";

const WheelsetTrack& s1002_uic60() {
  static const WheelsetTrack track(read_profile(kProfiles / "MBench_S1002_v3.prw"),
                                   read_profile(kProfiles / "MBench_UIC60_v3.prr"));
  return track;
}

WheelsetPosition at(double y_m, double z_m = 0.0, double roll = 0.0, double yaw = 0.0) {
  WheelsetPosition p;
  p.lateral_displacement_m = y_m;
  p.vertical_displacement_m = z_m;
  p.roll_rad = roll;
  p.yaw_rad = yaw;
  return p;
}

// The position with the right wheel lowered by `overlap` below its first touch.
WheelsetPosition pressed(double y_m, double overlap_m, double roll = 0.0, double yaw = 0.0) {
  WheelsetPosition p = at(y_m, 0.0, roll, yaw);
  p.vertical_displacement_m = s1002_uic60().touching_vertical_displacement_m(WheelSide::right, p) - overlap_m;
  return p;
}

// Without yaw and roll, the lowest point of the vertical gap is the first touch of the 2-D pair.
TEST(WheelsetGeometry, FirstTouchAgreesWithTheZeroYawPair) {
  const WheelsetTrack& track = s1002_uic60();
  for (double y : {-3e-3, -1e-3, 0.0, 2e-3, 4e-3}) {
    const WheelContactSearch s = track.contact_search(WheelSide::right, at(y, 0.0));
    const WheelRailContactPoint c = track.pair(WheelSide::right).contact_point(y);
    EXPECT_NEAR(s.locus[s.min_gap_sample].rail_profile_y_m, c.y_rail_m, 0.15 * kMm) << "y = " << y;
    // The wheelset's height above the pair's first touch: the gap at the first touch is the
    // difference of the lowering of the wheel.
    EXPECT_NEAR(s.min_vertical_gap_m - s.min_vertical_gap_m, 0.0, 1e-12);
  }
  // At y = 0 the right wheel touches at z = 0 (H0 is defined by it, symmetric profiles).
  EXPECT_NEAR(track.contact_search(WheelSide::right, at(0.0, 0.0)).min_vertical_gap_m, 0.0, 1e-9);
}

// Each valid locus sample keeps the rail profile's parameter at its lateral position (the region's
// tangent-plane box reads the rail point from it): the profile there is the sample's position and
// its height gives the sample's vertical gap.
TEST(WheelsetGeometry, EachLocusSampleKeepsItsRailParameter) {
  const WheelsetTrack& track = s1002_uic60();
  int valid = 0;
  for (const WheelsetPosition& p : {at(0.0, -0.05e-3), at(-6.5e-3, -0.05e-3, 0.0, 3e-3), at(4e-3, 0.0, 1e-3, -2e-3)}) {
    for (const WheelSide side : {WheelSide::right, WheelSide::left}) {
      const WheelContactSearch s = track.contact_search(side, p);
      const SmoothProfile& rail = track.pair(side).rail();
      for (std::size_t k = 0; k < s.locus.size(); ++k) {
        const ContactLocusSample& sample = s.locus[k];
        if (std::isnan(sample.rail_parameter_m)) continue;
        ++valid;
        const ProfileCurvePoint q = rail.at(sample.rail_parameter_m);
        ASSERT_NEAR(q.y_m, sample.rail_profile_y_m, 1e-12) << k;
        EXPECT_NEAR(sample.point_track_m[2] + q.z_m, sample.vertical_gap_m, 1e-12) << k;
        EXPECT_NEAR(sample.rail_parameter_m, rail.parameter_at(sample.rail_profile_y_m), 1e-12) << k;
      }
    }
  }
  EXPECT_GT(valid, 1000);
}

// The exact undeformed distance on the mesh agrees with the 2-D pair's at zero yaw, where the
// wheel is lowered by the same overlap (both measure along the same normal when the contact
// angles agree: compare at the pair's first touch with the region's own angle).
TEST(WheelsetGeometry, UndeformedDistanceIsConsistentAlongTheNormal) {
  const WheelsetTrack& track = s1002_uic60();
  const WheelsetPosition p = pressed(1e-3, 0.08e-3);
  const WheelContactSearch s = track.contact_search(WheelSide::right, p);
  ASSERT_EQ(s.regions.size(), 1u);
  const InterpenetrationRegion& r = s.regions.front();
  // h < 0 at the reference point (overlap) and rises along x1 like x1² cos γ / 2r.
  const double h0 = track.undeformed_distance_m(p, r, 0.0, 0.0);
  EXPECT_LT(h0, 0.0);
  EXPECT_GT(h0, -0.08e-3);
  const double x1 = 4e-3;
  const double rise = track.undeformed_distance_m(p, r, x1, 0.0) - h0;
  EXPECT_NEAR(rise, x1 * x1 * std::cos(r.contact_angle_rad) / (2 * r.rolling_radius_m), 0.02 * rise);
  // Even in x1 without yaw.
  EXPECT_NEAR(track.undeformed_distance_m(p, r, -x1, 0.5e-3), track.undeformed_distance_m(p, r, x1, 0.5e-3), 1e-12);
  // The mesh evaluation equals the pointwise one.
  const TangentPlaneArea area = track.potential_contact_area(p, r, 0.5e-3);
  const int i1 = area.mesh.n1 / 3, i2 = area.mesh.n2 / 2;
  EXPECT_NEAR(area.h_m[area.mesh.index(i1, i2)],
              track.undeformed_distance_m(p, r, area.mesh.x1(i1), area.mesh.x2(i2)), 1e-12);
  // The overlap lies inside the mesh, off its border.
  int overlap = 0;
  for (double h : area.h_m) overlap += h < 0.0 ? 1 : 0;
  EXPECT_GT(overlap, 50);
}

// The potential contact area's undeformed distance is the exact one, element by element: the
// mesh evaluation finds the root at every tenth element of a strip (0.2 mm elements; every 20th at
// 0.1 mm) and interpolates between roots with quintics; on the tread, on a yawed flange (γ up to
// 1.2 rad) and at 0.1 mm elements it agrees with the pointwise root to 1e-10 m (measured 2e-13 m
// on the tread, 6.2e-11 m on the flange, where the strip crosses the profile spline's knots; a
// loaded wheel's overlap is 1e-4 m). It fails with roots 4 mm apart (4.3e-10 m).
TEST(WheelsetGeometry, TheUndeformedDistanceIsTheExactOneOnEveryElement) {
  const WheelsetTrack& track = s1002_uic60();
  struct Case {
    double y_m, yaw_rad, element_m;
  };
  for (const Case c : {Case{0.0, 0.0, 0.2e-3}, Case{-7e-3, 8e-3, 0.2e-3}, Case{-6.5e-3, -5e-3, 0.1e-3}}) {
    const WheelsetPosition p = pressed(c.y_m, 0.1e-3, 0.0, c.yaw_rad);
    for (const InterpenetrationRegion& r : track.contact_search(WheelSide::right, p).regions) {
      const TangentPlaneArea area = track.potential_contact_area(p, r, c.element_m);
      double largest = 0.0;
      for (int i2 = 0; i2 < area.mesh.n2; i2 += 3)
        for (int i1 = 0; i1 < area.mesh.n1; ++i1) {
          const double h = area.h_m[area.mesh.index(i1, i2)];
          if (h > 0.5) continue;  // a strip another region owns
          largest = std::max(largest, std::abs(h - track.undeformed_distance_m(p, r, area.mesh.x1(i1), area.mesh.x2(i2))));
        }
      EXPECT_LT(largest, 1e-10) << c.y_m << " " << c.yaw_rad << " " << r.contact_angle_rad;
    }
  }
}

// The left wheel's potential area is the mirrored right wheel's, element by element, to rounding:
// its strips are solved in the right wheel's order, each from the same neighbour's root (9.5e-14 m
// apart at y = -6.8 mm, yaw 2 mrad when they ran in the left mesh's own order).
TEST(WheelsetGeometry, TheLeftWheelsUndeformedDistanceIsTheMirroredRightWheels) {
  const WheelsetTrack& track = s1002_uic60();
  for (const WheelsetPosition& p : {pressed(-6.8e-3, 0.3e-3, 0.0, 2e-3), pressed(2e-3, 0.08e-3)}) {
    const WheelsetPosition mirrored = at(-p.lateral_displacement_m, p.vertical_displacement_m, -p.roll_rad, -p.yaw_rad);
    const WheelContactSearch right = track.contact_search(WheelSide::right, p);
    const WheelContactSearch left = track.contact_search(WheelSide::left, mirrored);
    ASSERT_EQ(left.regions.size(), right.regions.size());
    for (std::size_t k = 0; k < right.regions.size(); ++k) {
      const TangentPlaneArea r = track.potential_contact_area(p, right.regions[k], 0.5e-3);
      const TangentPlaneArea l = track.potential_contact_area(mirrored, left.regions[k], 0.5e-3);
      ASSERT_EQ(l.mesh.n1, r.mesh.n1);
      ASSERT_EQ(l.mesh.n2, r.mesh.n2);
      double largest = 0.0;
      int overlapping = 0;
      for (int i2 = 0; i2 < r.mesh.n2; ++i2)
        for (int i1 = 0; i1 < r.mesh.n1; ++i1) {
          const double h = r.h_m[r.mesh.index(i1, i2)];
          if (!(h < 0.0)) continue;
          ++overlapping;
          largest = std::max(largest, std::abs(h - l.h_m[l.mesh.index(i1, l.mesh.n2 - 1 - i2)]));
        }
      EXPECT_GT(overlapping, 100);
      EXPECT_LT(largest, 1e-14) << p.lateral_displacement_m;
    }
  }
}

// The left wheel at (y, roll, yaw) is the mirror image of the right wheel at (−y, −roll, −yaw).
TEST(WheelsetGeometry, LeftWheelIsTheMirroredRightWheel) {
  const WheelsetTrack& track = s1002_uic60();
  for (const WheelsetPosition& p :
       {pressed(2e-3, 0.05e-3), pressed(-5e-3, 0.05e-3, 0.0, 4e-3), pressed(7.5e-3, 0.05e-3, 1e-3, -6e-3)}) {
    const WheelsetPosition mirrored = at(-p.lateral_displacement_m, p.vertical_displacement_m, -p.roll_rad, -p.yaw_rad);
    const WheelContactSearch left = track.contact_search(WheelSide::left, p);
    const WheelContactSearch right = track.contact_search(WheelSide::right, mirrored);
    ASSERT_EQ(left.regions.size(), right.regions.size());
    for (std::size_t k = 0; k < left.regions.size(); ++k) {
      const InterpenetrationRegion& l = left.regions[k];
      const InterpenetrationRegion& r = right.regions[k];
      EXPECT_NEAR(l.reference_point_track_m[0], r.reference_point_track_m[0], 1e-9);
      EXPECT_NEAR(l.reference_point_track_m[1], -r.reference_point_track_m[1], 1e-9);
      EXPECT_NEAR(l.reference_point_track_m[2], r.reference_point_track_m[2], 1e-9);
      EXPECT_NEAR(l.contact_angle_rad, r.contact_angle_rad, 1e-9);
      EXPECT_NEAR(l.x3_axis[1], -r.x3_axis[1], 1e-12);
      EXPECT_NEAR(l.x2_axis[1], r.x2_axis[1], 1e-12);  // X2 points +y on both wheels
      EXPECT_NEAR(track.undeformed_distance_m(p, l, 1e-3, 0.7e-3),
                  track.undeformed_distance_m(mirrored, r, 1e-3, -0.7e-3), 1e-10);
    }
  }
}

// Two-point contact: at y = −5 mm the tread and the flange root touch 10 mm apart, their gaps 0.007 mm
// apart with a hump of 0.04 mm between them: pressed by 0.03 mm, two regions;
// at −7 mm the flange alone, steep; with yaw ψ its point leads or lags by the classic
// −r tan γ sin ψ on the right wheel (docs/WHEELSET.md §2).
TEST(WheelsetGeometry, FlangeContactIsASeparateRegionThatLeadsWithYaw) {
  const WheelsetTrack& track = s1002_uic60();
  const WheelContactSearch two = track.contact_search(WheelSide::right, pressed(-5e-3, 0.03e-3));
  ASSERT_EQ(two.regions.size(), 2u);
  const InterpenetrationRegion& root = two.regions.front();  // gauge side first (−y_p)
  const InterpenetrationRegion& tread = two.regions.back();
  EXPECT_GT(root.contact_angle_rad, tread.contact_angle_rad + 0.1);
  EXPECT_GT(tread.rail_profile_y_m - root.rail_profile_y_m, 8e-3);

  const WheelContactSearch s = track.contact_search(WheelSide::right, pressed(-7e-3, 0.1e-3));
  ASSERT_EQ(s.regions.size(), 1u);
  EXPECT_GT(s.regions.front().contact_angle_rad, 1.0);

  const double yaw = 5e-3;
  const WheelContactSearch yawed = track.contact_search(WheelSide::right, pressed(-7e-3, 0.1e-3, 0.0, yaw));
  ASSERT_EQ(yawed.regions.size(), 1u);
  const InterpenetrationRegion& f = yawed.regions.front();
  // The wheel's own section at the contact moves by s a_x = s (−sin ψ) with the yawed axle (s: its
  // axial coordinate, −(W0 + y_w) on the right wheel, W0 = 0.75 m); the contact lags it by r tan γ sin ψ.
  const double axial = -(0.75 + f.wheel_profile_y_m);
  const double lead = -f.rolling_radius_m * std::tan(f.contact_angle_rad) * std::sin(yaw);
  EXPECT_NEAR(f.reference_point_track_m[0] - axial * -std::sin(yaw), lead, 0.03 * std::abs(lead));
  EXPECT_LT(lead, -5e-3);  // several millimetres
}

// The reference point and contact angle move continuously through the S1002 / UIC60 contact jump
// near y = −0.21 mm (where the point of first touch jumps).
TEST(WheelsetGeometry, ReferencePointIsContinuousThroughTheContactJump) {
  const WheelsetTrack& track = s1002_uic60();
  double previous_y = 0.0, previous_angle = 0.0;
  double largest_step_y = 0.0, largest_step_angle = 0.0;
  for (int k = 0; k <= 60; ++k) {
    const double y = (0.1 - 0.01 * k) * kMm;  // 0.1 ... -0.5 mm
    const WheelContactSearch s = track.contact_search(WheelSide::right, pressed(y, 0.08e-3));
    ASSERT_EQ(s.regions.size(), 1u) << "y = " << y;
    const InterpenetrationRegion& r = s.regions.front();
    if (k > 0) {
      largest_step_y = std::max(largest_step_y, std::abs(r.reference_point_track_m[1] - previous_y));
      largest_step_angle = std::max(largest_step_angle, std::abs(r.contact_angle_rad - previous_angle));
    }
    previous_y = r.reference_point_track_m[1];
    previous_angle = r.contact_angle_rad;
  }
  EXPECT_LT(largest_step_y, 0.1e-3);     // steps of 0.01 mm in y: no jump of millimetres
  EXPECT_LT(largest_step_angle, 1e-3);   // the first-touch angle jumps by 0.037 rad here
}

// The wheelset's locus on demand (every 8th sample first, the rest where the wheel may overlap its
// rail; docs/WHEELSET.md §8 "The locus on demand") gives the fully sampled locus's first touch and
// regions to the last bit: on S1002/UIC60 1:40, S1002 on the 1:20 rail, the hollow-worn S1002 and
// Car7358 on the worn rail, y from 0 to the flange (−7 mm) in 0.25 mm steps at yaw 0 and ±8 mrad,
// roll 1 mrad, 10 µm, 0.1 mm and 0.5 mm below first touch (tread, flange root, flange and two-point
// contact), on both wheels.
TEST(WheelsetGeometry, TheLocusOnDemandGivesTheFullLocussRegions) {
  const std::filesystem::path setups = std::filesystem::path(RAILCONTACT_DATA_DIR) / "wheel_rail";
  int regions = 0, two_region_searches = 0;
  for (const char* setup :
       {"s1002_uic60.json", "s1002_uic60_1in20.json", "s1002hollow_uic60.json", "car7358_uic60.json"}) {
    const WheelsetTrack track(load_wheel_rail_pair(read_wheel_rail_setup(setups / setup)));
    for (const WheelSide side : {WheelSide::right, WheelSide::left}) {
      const double sign = side == WheelSide::right ? 1.0 : -1.0;  // towards this wheel's flange
      for (double y_mm = 0.0; y_mm <= 7.0; y_mm += 0.25) {
        for (const double yaw : {0.0, 8e-3, -8e-3}) {
          const WheelsetPosition p = at(-sign * y_mm * kMm, 0.0, 1e-3, yaw);
          const double step = ContactSearchOptions{}.locus_step_m;
          detail::WheelLocus full = detail::sample_wheel_locus(track, side, p, step);
          detail::WheelLocus lazy = detail::sample_wheel_locus(track, side, p, step, 8);
          const double touching = detail::touching_vertical_displacement_m(track, full);
          EXPECT_EQ(detail::touching_vertical_displacement_m(track, lazy), touching) << setup << " y " << y_mm;
          for (const double overlap_m : {10e-6, 0.1e-3, 0.5e-3}) {
            WheelsetPosition q = p;
            q.vertical_displacement_m = touching - overlap_m;
            WheelContactSearch a, b;
            try {
              a = detail::contact_search(track, full, q, ContactSearchOptions{});
            } catch (const Error&) {
              EXPECT_THROW((void)detail::contact_search(track, lazy, q, ContactSearchOptions{}), Error);
              continue;
            }
            b = detail::contact_search(track, lazy, q, ContactSearchOptions{});
            ASSERT_EQ(a.regions.size(), b.regions.size()) << setup << " y " << y_mm << " yaw " << yaw;
            regions += static_cast<int>(a.regions.size());
            two_region_searches += a.regions.size() > 1 ? 1 : 0;
            for (std::size_t r = 0; r < a.regions.size(); ++r) {
              const InterpenetrationRegion &A = a.regions[r], &B = b.regions[r];
              EXPECT_EQ(A.first_sample, B.first_sample);
              EXPECT_EQ(A.last_sample, B.last_sample);
              EXPECT_EQ(A.rail_profile_y_m, B.rail_profile_y_m) << setup << " y " << y_mm;
              EXPECT_EQ(A.contact_angle_rad, B.contact_angle_rad);
              EXPECT_EQ(A.contact_angle_spread_rad, B.contact_angle_spread_rad);
              EXPECT_EQ(A.max_interpenetration_m, B.max_interpenetration_m);
              EXPECT_EQ(A.reference_point_track_m, B.reference_point_track_m);
              EXPECT_EQ(A.x1_min_m, B.x1_min_m);
              EXPECT_EQ(A.x1_max_m, B.x1_max_m);
              EXPECT_EQ(A.x2_min_m, B.x2_min_m);
              EXPECT_EQ(A.x2_max_m, B.x2_max_m);
            }
          }
        }
      }
    }
  }
  EXPECT_GT(regions, 2000);  // 2174 regions, 81 searches with two
  EXPECT_GT(two_region_searches, 60);
}

TEST(WheelsetGeometry, RefusesBadPositions) {
  const WheelsetTrack& track = s1002_uic60();
  EXPECT_THROW((void)track.contact_search(WheelSide::right, at(std::nan(""))), Error);
  EXPECT_THROW((void)track.contact_search(WheelSide::right, at(0.0, 0.0, 0.0, 0.2)), Error);
  // The flange climbing over the rail (y = −30 mm: the contact beyond the flange's steepest point).
  try {
    (void)track.contact_search(WheelSide::right, pressed(-0.03, 0.1e-3));
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::invalid_input);
    EXPECT_NE(std::string(e.what()).find("climbing"), std::string::npos) << e.what();
  }
  // Far off the track: the overlap reaches the end of the wheel profile.
  EXPECT_THROW((void)track.contact_search(WheelSide::right, pressed(0.09, 1e-3)), Error);
}

}  // namespace
}  // namespace railcontact

namespace railcontact {
namespace {

// A conical wheel (cone angle γ0) on a rail with a circular head: the contact stays where the
// rail's slope is tan γ0 (it does not move on the rail), so the contact angle is γ0 and the contact
// moves on the wheel by the wheelset's displacement y. The wheel moving towards its flange (the
// left wheel for y > 0) rolls on a larger radius: Δr = r_left − r_right = 2 y tan γ0, the classic
// rolling-radius difference of a coned wheelset.
TEST(WheelsetGeometry, ConicalWheelOnARoundRailGivesTheClassicRollingRadiusDifference) {
  const double gamma0 = 0.05, R = 0.05;
  Profile wheel, rail;
  wheel.kind = ProfileKind::wheel;
  rail.kind = ProfileKind::rail;
  wheel.source = "cone";
  rail.source = "round rail";
  for (int k = 0; k <= 140; ++k) {  // y from -70 to +70 mm, radius growing towards -y (the flange side)
    const double y = (-70.0 + k) * 1e-3;
    wheel.y_m.push_back(y);
    wheel.z_m.push_back(-std::tan(gamma0) * y + (y < -40e-3 ? 0.5 * (y + 40e-3) * (y + 40e-3) / 0.01 : 0.0));
  }
  for (int k = 0; k <= 72; ++k) {  // the head: y from -36 to +36 mm
    const double y = (-36.0 + k) * 1e-3;
    rail.y_m.push_back(y);
    rail.z_m.push_back(R - std::sqrt(R * R - y * y));
  }
  const WheelsetTrack track(wheel, rail);
  const auto radius_at = [&](WheelSide side, double y) {
    WheelsetPosition p;
    p.lateral_displacement_m = y;
    p.vertical_displacement_m = track.touching_vertical_displacement_m(side, p) - 1e-6;
    const WheelContactSearch s = track.contact_search(side, p);
    EXPECT_EQ(s.regions.size(), 1u);
    EXPECT_NEAR(s.regions.front().contact_angle_rad, gamma0, 2e-3);
    return s.regions.front().rolling_radius_m;
  };
  for (double y : {-4e-3, -1e-3, 2e-3, 5e-3}) {
    const double dr = radius_at(WheelSide::left, y) - radius_at(WheelSide::right, y);
    EXPECT_NEAR(dr, 2.0 * std::tan(gamma0) * y, 0.002 * std::abs(2.0 * std::tan(gamma0) * y)) << "y = " << y;
  }
}


// The area grows on each side where the overlap comes within the border of its edge, and only
// there: one overlapping element within the border's band of one edge at a time (in the middle of
// that edge, so that no other edge's band holds it), found in a border row or in a row between.
TEST(WheelsetGeometry, ThePotentialAreaGrowsOnTheSideTheOverlapReachesAndOnlyThere) {
  InterpenetrationRegion region;
  region.side = WheelSide::right;
  region.x1_min_m = -2e-3;
  region.x1_max_m = 2e-3;
  region.x2_min_m = -3e-3;
  region.x2_max_m = 3e-3;
  constexpr double dx = 0.2e-3;
  constexpr int border = 2;
  const geometry::GrowingArea growing{region, dx, dx, border, "test area", "in the tangent plane"};
  // The first mesh, without an overlap: its edges.
  const TangentPlaneArea first = geometry::grown_area(
      growing, [](const Mesh& mesh, TangentPlaneArea& area) { area.h_m.assign(mesh.size(), 1.0); });
  ASSERT_EQ(first.growth_steps, 0);
  const Mesh& m = first.mesh;
  const double x1_mid = m.x1(m.n1 / 2), x2_mid = m.x2(m.n2 / 2);
  struct Case {
    const char* edge;
    double x1_m, x2_m;  // the overlapping point: the edge's second element inwards
  };
  const Case cases[] = {{"low x1", m.x1(1), x2_mid},
                        {"high x1", m.x1(m.n1 - 2), x2_mid},
                        {"low x2", x1_mid, m.x2(1)},
                        {"high x2", x1_mid, m.x2(m.n2 - 2)}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.edge);
    const TangentPlaneArea grown = geometry::grown_area(growing, [&](const Mesh& mesh, TangentPlaneArea& area) {
      area.h_m.assign(mesh.size(), 1.0);
      const int i1 = static_cast<int>(std::lround((c.x1_m - mesh.x1_first_m) / dx));
      const int i2 = static_cast<int>(std::lround((c.x2_m - mesh.x2_first_m) / dx));
      area.h_m[mesh.index(i1, i2)] = -1e-6;
    });
    EXPECT_EQ(grown.growth_steps, 1);
    // Elements added on each side. A reached side grows by a quarter of the mesh (at least the
    // border); the high sides may also take the granule's rounding (fewer elements: the right
    // wheel's extra elements go to +x1 and +x2), the low sides nothing else.
    const Mesh& g = grown.mesh;
    const auto added = [&](double from_m, double to_m) { return static_cast<int>(std::lround((to_m - from_m) / dx)); };
    const int low1 = added(g.x1_first_m, m.x1_first_m), high1 = added(m.x1(m.n1 - 1), g.x1(g.n1 - 1));
    const int low2 = added(g.x2_first_m, m.x2_first_m), high2 = added(m.x2(m.n2 - 1), g.x2(g.n2 - 1));
    const int grow1 = std::max(border, m.n1 / 4), grow2 = std::max(border, m.n2 / 4);
    const std::string edge = c.edge;
    EXPECT_EQ(low1, edge == "low x1" ? grow1 : 0);
    EXPECT_EQ(low2, edge == "low x2" ? grow2 : 0);
    EXPECT_EQ(high1 >= grow1, edge == "high x1") << high1;
    EXPECT_EQ(high2 >= grow2, edge == "high x2") << high2;
  }
}

}  // namespace
}  // namespace railcontact
