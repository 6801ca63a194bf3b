// The elastic coupling between a wheel's separate patches (docs/WHEELSET.md §5 "Coupled patches"):
// Boussinesq's point load, the weight's fade, and the wheel's vertical force where two overlaps
// cross the merge distance, against the merged patch's own mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "railcontact/error.hpp"
#include "railcontact/wheel_rail.hpp"
#include "railcontact/wheelset.hpp"
#include "wheel_rail/patch_coupling.hpp"

namespace railcontact {
namespace {

// A square flat area of n × n elements of 0.2 mm centred on the origin, every element overlapping,
// in the plane z = 0 with its normal along z: its elements' centres and normals.
struct FlatArea {
  TangentPlaneArea area;
  detail::SurfacePoints points;
};
FlatArea flat_area(int n) {
  FlatArea f;
  f.area.mesh.n1 = f.area.mesh.n2 = n;
  f.area.mesh.dx1_m = f.area.mesh.dx2_m = 0.2e-3;
  f.area.mesh.x1_first_m = f.area.mesh.x2_first_m = -0.1e-3 * (n - 1);
  f.area.h_m.assign(static_cast<std::size_t>(n * n), -1e-5);
  InterpenetrationRegion region;
  region.x1_axis = {1.0, 0.0, 0.0};
  region.x2_axis = {0.0, 1.0, 0.0};
  region.x3_axis = {0.0, 0.0, 1.0};
  f.points = detail::surface_points(region, f.area);
  return f;
}

TEST(PatchCoupling, WeightIsOneUpToTheFullDistanceAndFadesToZeroAtTheEnd) {
  const PatchCouplingOptions o;  // 6 and 10 mm
  EXPECT_EQ(detail::patch_coupling_weight(2e-3, o), 1.0);
  EXPECT_EQ(detail::patch_coupling_weight(6e-3, o), 1.0);
  EXPECT_NEAR(detail::patch_coupling_weight(8e-3, o), 0.5, 1e-12);
  EXPECT_EQ(detail::patch_coupling_weight(10e-3, o), 0.0);
  EXPECT_EQ(detail::patch_coupling_weight(30e-3, o), 0.0);
  // Continuous at both ends of the fade.
  EXPECT_NEAR(detail::patch_coupling_weight(6.001e-3, o), 1.0, 1e-6);
  EXPECT_NEAR(detail::patch_coupling_weight(9.999e-3, o), 0.0, 1e-6);
  const PatchCouplingOptions off{0.0, 0.0};
  EXPECT_EQ(detail::patch_coupling_weight(0.0, off), 0.0);
  EXPECT_NO_THROW(validate(o));
  EXPECT_THROW(validate(PatchCouplingOptions{8e-3, 6e-3}), Error);
  EXPECT_THROW(validate(PatchCouplingOptions{0.0, 0.2}), Error);
  EXPECT_THROW(validate(PatchCouplingOptions{-1e-3, 1e-3}), Error);
}

// A patch's pressure far from the target acts as Boussinesq's point load: the two bodies approach
// by (1 − ν)/(πG) F / r.
TEST(PatchCoupling, DisplacementFarFromAPatchIsBoussinesqsPointLoad) {
  const Material material{2.1e11, 0.3};
  const FlatArea flat = flat_area(10);
  const TangentPlaneArea& area = flat.area;
  const detail::SurfacePoints& points = flat.points;
  std::vector<double> pressure(100, 0.0);
  double force = 0.0;
  for (int i2 = 0; i2 < 10; ++i2)
    for (int i1 = 0; i1 < 10; ++i1) {
      const double p = 1e9 * (1.0 + 0.1 * i1);
      pressure[area.mesh.index(i1, i2)] = p;
      force += p * area.mesh.element_area_m2();
    }
  const detail::PressureBlocks blocks = detail::pressure_blocks(area, points, pressure);
  double gathered = 0.0;
  for (double f : blocks.force_N) gathered += f;
  EXPECT_NEAR(gathered, force, 1e-9 * force);
  // Targets 50 mm away along y, one of them on a surface turned by 0.5 rad.
  detail::SurfacePoints target;
  target.point_m = {{0.0, 0.05, 0.0}, {0.0, 0.05, 0.0}};
  target.normal = {{0.0, 0.0, 1.0}, {0.0, -std::sin(0.5), std::cos(0.5)}};
  const std::vector<double> h{-1e-5, -1e-5};
  std::vector<double> lift{1e-5, 1e-5};  // added to
  detail::add_coupling_displacement(blocks, target, 0.5, material, h, lift);
  double moment = 0.0;  // about x1 = 0
  for (int i1 = 0; i1 < 10; ++i1) moment += 10.0 * 1e9 * (1.0 + 0.1 * i1) * area.mesh.element_area_m2() * area.mesh.x1(i1);
  const double r = std::hypot(0.05, moment / force);  // from the centre of force, on x2 = 0
  const double expected = 0.5 * (1.0 - 0.3) / (M_PI * material.shear_modulus_Pa()) * force / r;
  EXPECT_NEAR(lift[0] - 1e-5, expected, 1e-3 * expected);
  EXPECT_NEAR(lift[1] - 1e-5, expected * std::cos(0.5), 1e-3 * expected);
  // A separated element (h > 0) is left alone: no contact can arise there.
  std::vector<double> apart(2, 0.0);
  detail::add_coupling_displacement(blocks, target, 1.0, material, {1e-5, -1e-5}, apart);
  EXPECT_EQ(apart[0], 0.0);
  EXPECT_GT(apart[1], 0.0);
}

// Nearer than two blocks a target takes the block's elements one by one: a uniform pressure on a
// 1 mm square (25 elements of 0.2 mm) displaces its centre by (1 − ν)/(πG) p s 4 ln(1 + √2), and a
// point 1.5 mm from its centre by the integral of 1/r over the square (a 400 × 400 midpoint sum
// here); the block as one point load would miss them by infinity and 1.7 %.
TEST(PatchCoupling, ANearTargetTakesTheBlocksElementsOneByOne) {
  const Material material{2.1e11, 0.3};
  const FlatArea flat = flat_area(5);
  const TangentPlaneArea& area = flat.area;
  const detail::SurfacePoints& points = flat.points;
  constexpr double p_Pa = 1e9, side_m = 1e-3;
  const std::vector<double> pressure(25, p_Pa);
  const detail::PressureBlocks blocks = detail::pressure_blocks(area, points, pressure);
  ASSERT_EQ(blocks.force_N.size(), 1u);
  detail::SurfacePoints target;
  target.point_m = {{0.0, 0.0, 0.0}, {1.5e-3, 0.0, 0.0}};
  target.normal = {{0.0, 0.0, 1.0}, {0.0, 0.0, 1.0}};
  std::vector<double> lift(2, 0.0);
  detail::add_coupling_displacement(blocks, target, 1.0, material, {-1e-5, -1e-5}, lift);
  const double compliance = (1.0 - 0.3) / (M_PI * material.shear_modulus_Pa());
  const double at_centre = compliance * p_Pa * side_m * 4.0 * std::log(1.0 + std::sqrt(2.0));
  double mean_inverse_r = 0.0;
  constexpr int m = 400;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = ((i + 0.5) / m - 0.5) * side_m, v = ((j + 0.5) / m - 0.5) * side_m;
      mean_inverse_r += 1.0 / std::hypot(1.5e-3 - u, v) / (m * m);
    }
  const double beside = compliance * p_Pa * side_m * side_m * mean_inverse_r;
  EXPECT_NEAR(lift[0], at_centre, 0.03 * at_centre);
  EXPECT_NEAR(lift[1], beside, 0.005 * beside);
  EXPECT_GT(std::abs(compliance * p_Pa * side_m * side_m / 1.5e-3 - beside), 0.01 * beside);
}

// S1002 on UIC60 at 1:30, y = −5.1 mm, by position: lifting the wheel from z = 0.1905 to 0.1925 mm
// opens the gap between the flange root's and the tread's overlaps beyond the merge distance
// (2 mm) at z = 0.192 mm, so that one patch becomes two.
class CouplingAcrossTheMergeDistance : public ::testing::Test {
 protected:
  static WheelsetTrack track() {
    return WheelsetTrack(load_wheel_rail_pair(read_wheel_rail_setup(std::string(RAILCONTACT_DATA_DIR) +
                                                                     "/wheel_rail/s1002_uic60_1in30.json")));
  }
  static WheelsetOptions options(bool coupled) {
    WheelsetOptions o;
    o.loads.reset();
    o.allow_wheel_lift = true;
    if (!coupled) o.patch_coupling = {0.0, 0.0};
    return o;
  }
  static WheelResult right_wheel(const WheelsetTrack& t, const WheelsetOptions& o, double z_m) {
    WheelsetState s;
    s.position.lateral_displacement_m = -5.1e-3;
    s.position.vertical_displacement_m = z_m;
    Wheelset w(t, o);
    return w.evaluate(s).wheels[0];
  }
  // The wheel's vertical force at z = 0.1905 ... 0.1925 mm in steps of 0.5 µm, the patch counts, and
  // the largest second difference of the force over them.
  struct Scan {
    std::vector<double> force_N;
    std::vector<std::size_t> patches;
    double largest_second_difference_N = 0.0;
  };
  static Scan scan(bool coupled) {
    const WheelsetTrack t = track();
    Scan s;
    for (int k = 0; k < 5; ++k) {
      const WheelResult w = right_wheel(t, options(coupled), (0.1905 + 0.0005 * k) * 1e-3);
      s.force_N.push_back(w.force_track_N[2]);
      s.patches.push_back(w.patches.size());
    }
    for (std::size_t k = 1; k + 1 < s.force_N.size(); ++k)
      s.largest_second_difference_N = std::max(
          s.largest_second_difference_N, std::abs(s.force_N[k + 1] - 2.0 * s.force_N[k] + s.force_N[k - 1]));
    return s;
  }
};

// Measured: coupled, the largest second difference is 11 N of 94 kN (the force falls by 680 N per
// step); uncoupled 3.4 kN, a jump of 3.6 % of the force (the flange root's overlap takes 3.4 kN at
// once).
TEST_F(CouplingAcrossTheMergeDistance, TheVerticalForceFallsSmoothlyWhereOnePatchBecomesTwo) {
  const Scan coupled = scan(true);
  ASSERT_EQ(coupled.patches.front(), 1u);
  ASSERT_EQ(coupled.patches.back(), 2u);
  for (std::size_t k = 1; k < coupled.force_N.size(); ++k) EXPECT_LT(coupled.force_N[k], coupled.force_N[k - 1]);
  EXPECT_LT(coupled.largest_second_difference_N, 1e-3 * coupled.force_N.front());
  const Scan uncoupled = scan(false);
  EXPECT_GT(uncoupled.largest_second_difference_N, 0.02 * uncoupled.force_N.front());
}

// Just beyond the merge distance the two coupled patches carry what one mesh across both overlaps
// (merge distance 3 mm: the half-space's influence coefficients couple its parts) carries: measured
// 92 199 N against 92 202 N (the tread's pressure lifts the flange root off: its overlap carries
// nothing in either); uncoupled 95 259 N, 3.3 % more.
TEST_F(CouplingAcrossTheMergeDistance, TwoCoupledPatchesCarryWhatOneMeshAcrossBothCarries) {
  const WheelsetTrack t = track();
  constexpr double z_m = 0.1925e-3;
  const WheelResult two = right_wheel(t, options(true), z_m);
  ASSERT_EQ(two.patches.size(), 2u);
  EXPECT_GT(two.patches.back().coupling_lift_m + two.patches.front().coupling_lift_m, 1e-6);
  WheelsetOptions merged = options(true);
  merged.search.merge_distance_m = 3e-3;
  const WheelResult one = right_wheel(t, merged, z_m);
  ASSERT_EQ(one.patches.size(), 1u);
  EXPECT_NEAR(two.force_track_N[2], one.force_track_N[2], 3e-3 * one.force_track_N[2]);
  const WheelResult uncoupled = right_wheel(t, options(false), z_m);
  EXPECT_GT(uncoupled.force_track_N[2] - one.force_track_N[2], 0.02 * one.force_track_N[2]);
}


// Car7358 (a measured worn wheel) on upright UIC60, r0 = 420 mm, +10 mrad: near y = −7.1 mm the
// flange (contact angle 1.1 rad) and the flange root (0.37 rad) overlap in one run of the locus,
// parted by a neck whose gap is −0.012 mm at z = 0.43935 mm: the neck is crossed at z = 0.4512 mm.
class PatchesAtANeck : public ::testing::Test {
 protected:
  static WheelsetTrack track() {
    WheelRailSetup setup = read_wheel_rail_setup(std::string(RAILCONTACT_DATA_DIR) + "/wheel_rail/car7358_uic60.json");
    setup.rail_profile = std::string(RAILCONTACT_DATA_DIR) + "/profiles/UIC60_upright.prr";
    setup.track.nominal_rolling_radius_m = 0.42;
    return WheelsetTrack(load_wheel_rail_pair(setup));
  }
  static WheelsetPosition position(double y_m, double z_m) {
    WheelsetPosition p;
    p.lateral_displacement_m = y_m;
    p.yaw_rad = 0.01;
    p.vertical_displacement_m = z_m;
    return p;
  }
};

// Below the neck the one run is cut there into two regions, each in its own tangent plane.
TEST_F(PatchesAtANeck, ARunIsCutAtItsNeckWhereItsHumpsDifferInContactAngle) {
  const WheelContactSearch s = track().contact_search(WheelSide::right, position(-7.1e-3, 0.43935e-3), {});
  ASSERT_EQ(s.regions.size(), 2u);
  EXPECT_EQ(s.regions[0].last_sample + 1, s.regions[1].first_sample);
  EXPECT_GT(std::abs(s.regions[0].contact_angle_rad - s.regions[1].contact_angle_rad), 0.6);
  for (const InterpenetrationRegion& r : s.regions) EXPECT_LT(r.contact_angle_spread_rad, 0.1);
}

// By position, the wheel's vertical force passes the z where the two overlaps meet (0.4512 mm)
// smoothly: measured second differences of at most 1.2 N of 88 kN per 0.5 µm step (the force
// falling by 415 N per step). Before the cut the joined run was one planar patch: by load at
// y = −7.1 mm one patch at 0.88 rad with an angle spread of 0.34 rad (Fy 152.9 kN), now two at 1.10
// and 0.38 rad with spreads of 0.08 and 0.07 rad (Fy 137.6 kN).
TEST_F(PatchesAtANeck, TheVerticalForcePassesTheNeckSmoothly) {
  const WheelsetTrack t = track();
  WheelsetOptions o;
  o.loads.reset();
  o.allow_wheel_lift = true;
  std::vector<double> force;
  for (int k = 0; k < 5; ++k) {
    WheelsetState s;
    s.position = position(-7.1e-3, (0.4502 + 0.0005 * k) * 1e-3);
    Wheelset w(t, o);
    const WheelResult r = w.evaluate(s).wheels[0];
    ASSERT_EQ(r.patches.size(), 2u);
    force.push_back(r.force_track_N[2]);
  }
  for (std::size_t k = 1; k < force.size(); ++k) EXPECT_LT(force[k], force[k - 1] - 100.0);
  for (std::size_t k = 1; k + 1 < force.size(); ++k)
    EXPECT_LT(std::abs(force[k + 1] - 2.0 * force[k] + force[k - 1]), 1e-4 * force[k]);
}

// By load, the wheel meets its load where the two overlaps are about to meet (y = −7.0 mm); merged
// at their facing ends' angles into one planar patch, its vertical force jumped across the load there
// (102.8 → 94.4 kN) and the wheel carried 95.1 kN.
TEST_F(PatchesAtANeck, ByLoadTheFlangeWheelCarriesItsLoad) {
  Wheelset w(track());
  WheelsetState s;
  s.position = position(-7.0e-3, 0.0);
  const WheelResult r = w.evaluate(s).wheels[0];
  EXPECT_EQ(r.patches.size(), 2u);
  EXPECT_NEAR(r.force_track_N[2], 98100.0, 1e-4 * 98100.0);
}

}  // namespace
}  // namespace railcontact
