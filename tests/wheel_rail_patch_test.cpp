// The wheel–rail normal contact of S1002 on UIC60 1:40 (METHOD.md §9, docs/WHEEL_RAIL.md):
// single, non-elliptical patches over y = −4.5 … 4.5 mm, F3 = Fz / cos γ, exact load,
// complementarity, the signed spin of Eq 24, the smooth reference (the wheelset's, continuous
// through the contact jump), several patches beyond the range, bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "elastic/influence_operator.hpp"
#include "tangential/cropped_patch.hpp"
#include "railcontact/wheel_rail.hpp"
#include "railcontact/normal.hpp"
#include "railcontact/error.hpp"
#include "railcontact/tangential.hpp"
#include "railcontact/wheelset.hpp"

namespace railcontact {
namespace {

constexpr double kMm = 1e-3;
constexpr double kFz_N = 98100.0;
constexpr double kDiameter_m = 0.92;

const WheelRailPair& s1002_uic60() {
  static const WheelRailPair pair = default_wheel_rail_pair();
  return pair;
}

std::vector<double> paper_displacements() {
  std::vector<double> y;
  for (int k = -9; k <= 9; ++k) y.push_back(0.5 * k * kMm);
  return y;
}

double total_force(const Mesh& mesh, const std::vector<double>& pressure) {
  double sum = 0.0;
  for (double p : pressure) sum += p;
  return sum * mesh.element_area_m2();
}

std::string message_of(const WheelRailPair& pair, double y, const WheelRailPatchOptions& options) {
  try {
    (void)solve_wheel_rail_patch(pair, y, options);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(WheelRailPatch, CentredWheelsetGivesOneTreadPatch) {
  const WheelRailPair& pair = s1002_uic60();
  const WheelRailPatch p = solve_wheel_rail_patch(pair, 0.0);
  // On the tread: first touch, reference point and centre of pressure within 10 mm of the taping
  // line (the flange root is 25 mm away), γ about the 1:40 cant (smooth reference 0.0357 rad,
  // first touch 0.0243 rad).
  EXPECT_LT(std::abs(p.contact.y_wheel_m - pair.taping_line_y_m()), 10 * kMm);
  EXPECT_LT(std::abs(p.region.wheel_profile_y_m - pair.taping_line_y_m()), 10 * kMm);
  EXPECT_LT(std::abs(p.region.wheel_profile_y_m - p.pressure_centre_x2_m * std::cos(p.contact_angle_rad)), 10 * kMm);
  EXPECT_EQ(p.reference, ContactReference::smooth);
  EXPECT_GT(p.contact_angle_rad, 0.025);
  EXPECT_LT(p.contact_angle_rad, 0.045);
  // One patch, nothing dropped, held by the mesh.
  EXPECT_EQ(p.regions.size(), 1u);
  EXPECT_EQ(p.patches, 1u);
  EXPECT_EQ(p.dropped_load_fraction, 0.0);
  EXPECT_FALSE(p.normal.touches_border);
  EXPECT_TRUE(p.normal.converged);
  EXPECT_EQ(p.elements_in_contact, p.normal.elements_in_contact);
  EXPECT_EQ(p.elements_in_contact, p.patch.elements().count());
  EXPECT_NEAR(static_cast<double>(p.elements_in_contact), 3000.0, 0.15 * 3000.0);
  EXPECT_NEAR(p.area_m2, p.patch.area_m2(), 1e-15);
  EXPECT_NEAR(p.normal_force_N, kFz_N / std::cos(p.contact_angle_rad), 1e-9);
}

// Non-ellipticity measure: the patch against the Hertz ellipse of the contact point's local
// curvatures A, B under the same F3 — area ratio area / (π a b) and pressure ratio pmax / p0 —
// and the fill area / (π/4 L1 L2) (1 for an ellipse). Near-Hertzian at y = +4.5 mm (B ≈ A),
// far from it on the flange side of the contact jump.
TEST(WheelRailPatch, PaperRangeGivesSingleNonEllipticalPatches) {
  const WheelRailPair& pair = s1002_uic60();
  double worst_area = 1.0, lowest_pressure = 1.0, lowest_fill = 1.0;
  std::printf("    y/mm  gamma/rad  F3/kN   area/mm2  area/Hertz  elements  pmax/MPa  pmax/p0  fill\n");
  for (const double y : paper_displacements()) {
    const WheelRailPatch p = solve_wheel_rail_patch(pair, y);
    SCOPED_TRACE("y = " + std::to_string(y / kMm) + " mm");
    EXPECT_EQ(p.regions.size(), 1u);  // single, not even a speck
    EXPECT_EQ(p.patches, 1u);
    EXPECT_TRUE(p.normal.converged);
    EXPECT_FALSE(p.normal.touches_border);
    EXPECT_NEAR(static_cast<double>(p.elements_in_contact), 3000.0, 0.15 * 3000.0);
    // F3 from vertical equilibrium, carried exactly by the pressure, p >= 0.
    EXPECT_NEAR(p.normal_force_N * std::cos(p.contact_angle_rad), kFz_N, 1e-9);
    EXPECT_NEAR(total_force(p.potential_area, p.normal.pressure_Pa), p.normal_force_N, 1e-10 * p.normal_force_N);
    EXPECT_NEAR(p.patch.normal_force_N(), p.normal_force_N, 1e-10 * p.normal_force_N);
    EXPECT_GE(*std::min_element(p.normal.pressure_Pa.begin(), p.normal.pressure_Pa.end()), 0.0);
    ASSERT_GT(p.local_hertz.a_m, 0.0);
    const double area_ratio = p.area_m2 / (M_PI * p.local_hertz.a_m * p.local_hertz.b_m);
    const double pressure_ratio = p.max_pressure_Pa / p.local_hertz.max_pressure_Pa;
    const double fill = p.area_m2 / (M_PI / 4 * p.extent_x1_m * p.extent_x2_m);
    std::printf("  %6.2f  %9.5f  %6.2f  %8.1f  %10.3f  %8zu  %8.0f  %7.3f  %5.3f\n", y / kMm, p.contact_angle_rad,
                p.normal_force_N * 1e-3, p.area_m2 * 1e6, area_ratio, p.elements_in_contact, p.max_pressure_Pa * 1e-6,
                pressure_ratio, fill);
    if (std::abs(area_ratio - 1) > std::abs(worst_area - 1)) worst_area = area_ratio;
    lowest_pressure = std::min(lowest_pressure, pressure_ratio);
    lowest_fill = std::min(lowest_fill, fill);
    if (y == 4.5 * kMm) {  // the calibration: nearly Hertzian
      EXPECT_NEAR(area_ratio, 1.0, 0.05);
      EXPECT_NEAR(pressure_ratio, 1.0, 0.01);
    }
  }
  // Clearly non-elliptical somewhere in the range (measured: area × 1.95 at y = −1 mm,
  // pmax × 0.74 at −0.5 mm, fill 0.74 at −2 mm).
  EXPECT_GT(worst_area, 1.5);
  EXPECT_LT(lowest_pressure, 0.8);
  EXPECT_LT(lowest_fill, 0.8);
}

// g = h − δ + A33 p on the whole potential area (A33 p by FFT): g = 0 on the patch, g >= 0
// outside; the undeformed distance h >= 0 (first touch).
TEST(WheelRailPatch, GapIsNonNegativeOutsideThePatch) {
  const WheelRailPair& pair = s1002_uic60();
  for (const double y : {-4.5 * kMm, -2.0 * kMm, -0.5 * kMm, 0.0, 3.0 * kMm}) {
    SCOPED_TRACE("y = " + std::to_string(y / kMm) + " mm");
    const WheelRailPatch p = solve_wheel_rail_patch(pair, y);
    const Mesh& mesh = p.potential_area;
    const std::vector<double>& h = p.potential_h_m;
    ASSERT_EQ(h.size(), mesh.size());
    EXPECT_GE(*std::min_element(h.begin(), h.end()), -1e-12);
    InfluenceOperator op = make_normal_operator(mesh, WheelRailPatchOptions{}.material);
    std::vector<double> Ap(mesh.size());
    op.apply_on_grid(p.normal.pressure_Pa, Ap);
    const double scale = *std::max_element(Ap.begin(), Ap.end());
    double worst_inside = 0.0, worst_outside = 0.0;
    for (std::size_t k = 0; k < mesh.size(); ++k) {
      const double g = h[k] - p.approach_m + Ap[k];
      if (p.normal.pressure_Pa[k] > 0.0) {
        worst_inside = std::max(worst_inside, std::abs(g));
      } else {
        worst_outside = std::min(worst_outside, g);
      }
    }
    EXPECT_LT(worst_inside, 1e-8 * scale);
    EXPECT_GT(worst_outside, -1e-8 * scale);
  }
}

TEST(WheelRailPatch, NormalForceFollowsFromVerticalEquilibrium) {
  WheelRailPatchOptions options;
  options.vertical_load_N = 50000.0;
  options.target_elements = 1000;
  const WheelRailPatch p = solve_wheel_rail_patch(s1002_uic60(), -3.0 * kMm, options);
  EXPECT_GT(p.contact_angle_rad, 0.08);  // steep enough for cos γ to matter (0.4 %)
  EXPECT_DOUBLE_EQ(p.vertical_load_N, 50000.0);
  EXPECT_NEAR(p.normal_force_N, 50000.0 / std::cos(p.contact_angle_rad), 1e-9);
  EXPECT_GT(p.normal_force_N - 50000.0, 150.0);
  EXPECT_NEAR(p.patch.normal_force_N(), p.normal_force_N, 1e-10 * p.normal_force_N);
  EXPECT_NEAR(static_cast<double>(p.elements_in_contact), 1000.0, 150.0);
}

TEST(WheelRailPatch, PatchOriginIsTheCentreOfPressure) {
  const WheelRailPatch p = solve_wheel_rail_patch(s1002_uic60(), 0.5 * kMm);
  const ContactPatch& patch = p.patch;
  double m1 = 0.0, m2 = 0.0;
  for (std::size_t e = 0; e < patch.elements().count(); ++e) {
    m1 += patch.pressure_Pa()[e] * patch.x1(e);
    m2 += patch.pressure_Pa()[e] * patch.x2(e);
  }
  const double sum = patch.normal_force_N() / patch.mesh().element_area_m2();
  EXPECT_NEAR(m1 / sum, 0.0, 1e-12);
  EXPECT_NEAR(m2 / sum, 0.0, 1e-12);
  EXPECT_NEAR(p.pressure_centre_x1_m, -patch.x1_shift_m(), 1e-15);
  EXPECT_NEAR(p.pressure_centre_x2_m, -patch.x2_shift_m(), 1e-15);
  EXPECT_NEAR(p.pressure_centre_x1_m, 0.0, 1e-9);  // h is even in x1 (zero yaw)
  // The patch's mesh is the potential area's, cropped to the patch's bounding box widened to whole
  // blocks of nH-FastSim's automatic coarsening counted from the reference point (smooth reference).
  EXPECT_DOUBLE_EQ(patch.mesh().dx1_m, p.potential_area.dx1_m);
  EXPECT_DOUBLE_EQ(patch.mesh().dx2_m, p.potential_area.dx2_m);
  const int block = NhFastSim::automatic_coarsening(patch);
  EXPECT_EQ(patch.mesh().n1 % block, 0);
  EXPECT_EQ(patch.mesh().n2 % block, 0);
  EXPECT_GE(patch.mesh().n1 * patch.mesh().dx1_m, p.extent_x1_m - 1e-12);
  EXPECT_GE(patch.mesh().n2 * patch.mesh().dx2_m, p.extent_x2_m - 1e-12);
  EXPECT_LT(patch.mesh().n1 * patch.mesh().dx1_m, p.extent_x1_m + 2 * block * patch.mesh().dx1_m);
  EXPECT_LT(patch.mesh().n2 * patch.mesh().dx2_m, p.extent_x2_m + 2 * block * patch.mesh().dx2_m);
  EXPECT_LT(patch.mesh().size(), p.potential_area.size());
  std::vector<double> on_potential_area(p.potential_area.size(), 0.0);
  for (std::size_t e = 0; e < patch.elements().count(); ++e) {
    const int i1 = static_cast<int>(std::lround((patch.x1(e) + p.pressure_centre_x1_m - p.potential_area.x1_first_m) /
                                                p.potential_area.dx1_m));
    const int i2 = static_cast<int>(std::lround((patch.x2(e) + p.pressure_centre_x2_m - p.potential_area.x2_first_m) /
                                                p.potential_area.dx2_m));
    on_potential_area[p.potential_area.index(i1, i2)] = patch.pressure_Pa()[e];
  }
  EXPECT_EQ(on_potential_area, p.normal.pressure_Pa);  // the same elements and pressures
  // Extents: edge to edge along X1 and X2.
  EXPECT_GT(p.extent_x1_m, 5 * kMm);
  EXPECT_GT(p.extent_x2_m, 5 * kMm);
  EXPECT_LE(p.area_m2, p.extent_x1_m * p.extent_x2_m);
  EXPECT_DOUBLE_EQ(p.max_pressure_Pa, *std::max_element(patch.pressure_Pa().begin(), patch.pressure_Pa().end()));
}

// A first potential area far too small (h < 7.5 µm for δ = 73 µm) touches the patch: the area is
// enlarged and the same patch results.
TEST(WheelRailPatch, EnlargesAPotentialAreaThatCannotHoldThePatch) {
  const WheelRailPatch reference = solve_wheel_rail_patch(s1002_uic60(), 0.0);
  WheelRailPatchOptions options;
  options.initial_approach_m = 5e-6;
  const WheelRailPatch p = solve_wheel_rail_patch(s1002_uic60(), 0.0, options);
  std::printf("  solves: %d (default start: %d), area %.2f vs %.2f mm2\n", p.mesh_passes, reference.mesh_passes,
              p.area_m2 * 1e6, reference.area_m2 * 1e6);
  EXPECT_GT(p.mesh_passes, reference.mesh_passes);
  EXPECT_FALSE(p.normal.touches_border);
  EXPECT_NEAR(p.area_m2, reference.area_m2, 0.03 * reference.area_m2);
  EXPECT_NEAR(p.approach_m, reference.approach_m, 0.003 * reference.approach_m);
  EXPECT_NEAR(p.max_pressure_Pa, reference.max_pressure_Pa, 0.03 * reference.max_pressure_Pa);
  // Never enough: one clear error.
  options.initial_approach_m = 1e-6;
  options.max_enlargements = 0;
  EXPECT_NE(message_of(s1002_uic60(), 0.0, options).find("cannot hold the patch"), std::string::npos);
}

TEST(WheelRailPatch, MeshLayouts) {
  // y = 0: the patch is twice as wide (X2) as long (X1).
  const WheelRailPatch resolved = solve_wheel_rail_patch(s1002_uic60(), 0.0);
  WheelRailPatchOptions options;
  options.layout = PatchMeshLayout::square;
  const WheelRailPatch square = solve_wheel_rail_patch(s1002_uic60(), 0.0, options);
  EXPECT_DOUBLE_EQ(square.potential_area.dx1_m, square.potential_area.dx2_m);
  EXPECT_LT(resolved.potential_area.dx1_m, 0.7 * resolved.potential_area.dx2_m);
  // About as many elements along X1 as along X2.
  const double n1 = resolved.extent_x1_m / resolved.potential_area.dx1_m;
  const double n2 = resolved.extent_x2_m / resolved.potential_area.dx2_m;
  EXPECT_NEAR(n1 / n2, 1.0, 0.2);
  EXPECT_NEAR(square.area_m2, resolved.area_m2, 0.02 * resolved.area_m2);
  EXPECT_NEAR(square.approach_m, resolved.approach_m, 0.003 * resolved.approach_m);
}

// Beyond the paper's range the S1002 flange root comes into contact. At 98.1 kN its overlap and the
// tread's are one interpenetration region (one patch of two connected contact regions, as the
// wheelset solves it); at 10 kN they lie apart: two patches, refused unless allowed.
TEST(WheelRailPatch, ReportsSeveralPatchesBeyondThePaperRange) {
  const WheelRailPatch merged = solve_wheel_rail_patch(s1002_uic60(), -5.0 * kMm);
  EXPECT_EQ(merged.patches, 1u);
  EXPECT_EQ(merged.regions.size(), 2u);
  EXPECT_EQ(merged.patch.elements().count(), merged.elements_in_contact);
  EXPECT_EQ(merged.dropped_load_fraction, 0.0);

  WheelRailPatchOptions light;
  light.vertical_load_N = 10000.0;
  light.target_elements = 600;
  const std::string apart = message_of(s1002_uic60(), -5.0 * kMm, light);
  EXPECT_NE(apart.find("y = -5.000 mm gives several contact patches (2 patches:"), std::string::npos) << apart;
  EXPECT_NE(apart.find("% of the load at y_rail = "), std::string::npos) << apart;
  light.allow_several_patches = true;
  const WheelRailPatch two = solve_wheel_rail_patch(s1002_uic60(), -5.0 * kMm, light);
  EXPECT_EQ(two.patches, 2u);
  EXPECT_GT(two.dropped_load_fraction, 0.1);  // measured 0.24 on the flange root
  EXPECT_LT(two.dropped_load_fraction, 0.5);
  EXPECT_NEAR(two.normal_force_N * std::cos(two.contact_angle_rad), (1.0 - two.dropped_load_fraction) * 10000.0,
              1e-5 * 10000.0);

  // The point of first touch (one normal problem in its tangent plane): two connected regions.
  WheelRailPatchOptions options;
  options.reference = ContactReference::first_touch;
  const std::string message = message_of(s1002_uic60(), -5.0 * kMm, options);
  EXPECT_NE(message.find("y = -5.000 mm gives several contact patches (2 patches"), std::string::npos) << message;
  EXPECT_NE(message.find("out of scope"), std::string::npos) << message;
  options.allow_several_patches = true;
  const WheelRailPatch p = solve_wheel_rail_patch(s1002_uic60(), -5.0 * kMm, options);
  ASSERT_EQ(p.patches, 2u);
  ASSERT_EQ(p.regions.size(), 2u);
  EXPECT_NEAR(p.regions[0].load_fraction + p.regions[1].load_fraction, 1.0, 1e-12);
  EXPECT_GT(p.regions[0].load_fraction, p.regions[1].load_fraction);
  EXPECT_GT(p.regions[1].load_fraction, 0.2);
  EXPECT_EQ(p.patch.elements().count(), p.regions[0].elements.size());
  EXPECT_NEAR(p.dropped_load_fraction, p.regions[1].load_fraction, 1e-12);
  EXPECT_GT(p.regions[1].x2_centre_m - p.regions[0].x2_centre_m, 5 * kMm);  // towards the gauge side
}

// The smooth reference is the wheelset's: the right wheel of `railcontact wheelset` by load at the
// same y (zero roll and yaw, the frictionless vertical balance) has the same reference point,
// contact angle and rolling radius, to the difference of the meshes (0.2 mm squares there, ~3000
// elements here) in the wheel's height.
TEST(WheelRailPatch, SmoothReferenceIsTheWheelsetsRightWheel) {
  WheelsetOptions options;
  options.tangential_forces_in_vertical_balance = false;
  options.allow_wheel_lift = true;
  Wheelset wheelset(WheelsetTrack(s1002_uic60()), options);
  for (const double y : {-3.0 * kMm, -0.2 * kMm, 0.0, 2.5 * kMm}) {
    SCOPED_TRACE("y = " + std::to_string(y / kMm) + " mm");
    const WheelRailPatch p = solve_wheel_rail_patch(s1002_uic60(), y);
    WheelsetState state;
    state.position.lateral_displacement_m = y;
    const WheelsetResult w = wheelset.evaluate(state);
    ASSERT_EQ(w.wheels[0].patches.size(), 1u);
    const InterpenetrationRegion& r = w.wheels[0].patches.front().region;
    EXPECT_NEAR(p.contact_angle_rad, r.contact_angle_rad, 2e-4);
    EXPECT_NEAR(p.region.rail_profile_y_m, r.rail_profile_y_m, 0.02 * kMm);
    EXPECT_NEAR(p.rolling_radius_m, r.rolling_radius_m, 1e-6);
    EXPECT_NEAR(p.vertical_displacement_m, w.wheels[0].vertical_displacement_m, 0.5e-6);
    // The patch carries Fz exactly, and its centre of pressure lies near the reference point.
    EXPECT_NEAR(p.normal_force_N * std::cos(p.contact_angle_rad), kFz_N, 1e-9 * kFz_N);
    EXPECT_LT(std::abs(p.pressure_centre_x2_m), 1.5 * kMm);
  }
}

// Through the contact jump of the point of first touch (y ≈ −0.21 mm: γ from 0.0645 to 0.027 rad),
// the smooth reference moves continuously: in 0.01 mm steps γ changes by less than 0.3 mrad, the
// reference point by less than 0.05 mm, F3 by less than 0.01 %.
TEST(WheelRailPatch, SmoothReferenceIsContinuousThroughTheContactJump) {
  WheelRailPatchOptions options;
  options.target_elements = 600;
  WheelRailPatchOptions first_touch = options;
  first_touch.reference = ContactReference::first_touch;
  double worst_gamma = 0.0, worst_point = 0.0, worst_force = 0.0, jump_gamma = 0.0;
  WheelRailPatch previous, previous_first;
  for (int k = 0; k <= 8; ++k) {
    const double y = (-0.17 - 0.01 * k) * kMm;
    const WheelRailPatch p = solve_wheel_rail_patch(s1002_uic60(), y, options);
    const WheelRailPatch f = solve_wheel_rail_patch(s1002_uic60(), y, first_touch);
    if (k > 0) {
      worst_gamma = std::max(worst_gamma, std::abs(p.contact_angle_rad - previous.contact_angle_rad));
      worst_point = std::max(worst_point, std::abs(p.region.rail_profile_y_m - previous.region.rail_profile_y_m));
      worst_force = std::max(worst_force, std::abs(p.normal_force_N / previous.normal_force_N - 1.0));
      jump_gamma = std::max(jump_gamma, std::abs(f.contact_angle_rad - previous_first.contact_angle_rad));
    }
    previous = p;
    previous_first = f;
  }
  std::printf("  per 0.01 mm: smooth dγ %.2e rad, d(reference) %.2e mm, dF3/F3 %.1e; first touch dγ %.3f rad\n",
              worst_gamma, worst_point / kMm, worst_force, jump_gamma);
  EXPECT_GT(jump_gamma, 0.03);  // the first-touch point does jump in this range
  EXPECT_LT(worst_gamma, 0.3e-3);
  EXPECT_LT(worst_point, 0.05 * kMm);
  EXPECT_LT(worst_force, 1e-4);
}

TEST(WheelRailPatch, BadInputThrows) {
  const WheelRailPair& pair = s1002_uic60();
  for (const double load : {0.0, -1.0, std::nan("")}) {
    WheelRailPatchOptions options;
    options.vertical_load_N = load;
    EXPECT_NE(message_of(pair, 0.0, options).find("load must be positive"), std::string::npos) << load;
  }
  WheelRailPatchOptions options;
  options.target_elements = 0;
  EXPECT_NE(message_of(pair, 0.0, options).find("target number of elements"), std::string::npos);
  EXPECT_NE(message_of(pair, 1.0, {}).find("never touch"), std::string::npos);
  EXPECT_NE(message_of(pair, std::nan(""), {}).find("finite"), std::string::npos);
  options = {};
  options.significant_load_fraction = 1.0;
  EXPECT_THROW((void)solve_wheel_rail_patch(pair, 0.0, options), Error);
  options = {};
  options.vertical_load_N = 1e9;  // the interpenetration reaches beyond the profiles
  EXPECT_NE(message_of(pair, 0.0, options).find("too large"), std::string::npos);
}

// ---- spin (Eq 24) -------------------------------------------------------------------------------

TEST(ConicitySpin, RightWheelSpinHasTheSignOfTheContactAngle) {
  const WheelRailPair& pair = s1002_uic60();
  for (const double y : {-4.5 * kMm, 0.0, 4.5 * kMm}) {
    const WheelRailContactPoint c = pair.contact_point(y);
    ASSERT_GT(c.contact_angle_rad, 0.0);
    const double phi = conicity_spin_per_m(c.contact_angle_rad, WheelSide::right, kDiameter_m);
    EXPECT_NEAR(phi, 2 * std::sin(c.contact_angle_rad) / kDiameter_m, 1e-15);
    // The same from the geometry's own contact normal: φ = ω·X3 / V.
    EXPECT_NEAR(spin_creepage_per_m(c.x3_axis_track, 0.5 * kDiameter_m), phi, 1e-15);
  }
  EXPECT_GT(solve_wheel_rail_patch(pair, -2.0 * kMm).spin_per_m, 0.0);
  EXPECT_LT(conicity_spin_per_m(-0.05, WheelSide::right), 0.0);  // normal leaning outwards
  EXPECT_EQ(conicity_spin_per_m(0.0, WheelSide::right), 0.0);
}

// The left wheel is the mirror image (y -> -y) of the right one. The geometry API models the right
// wheel only (WheelRailPair rejects mirrored profiles), so the mirror is applied to its frame.
TEST(ConicitySpin, MirroredLeftWheelHasTheOppositeSign) {
  const WheelRailContactPoint c = s1002_uic60().contact_point(-3.0 * kMm);
  const auto& n = c.x3_axis_track;
  // The contact normal is a polar vector: mirrored, it leans towards -y (the track centre seen
  // from the left rail). ω = (0, V/r0, 0) is an axial vector: mirrored, -(M ω) = ω (same axle).
  const std::array<double, 3> mirrored{n[0], -n[1], n[2]};
  const auto left = contact_normal_in_track_frame(c.contact_angle_rad, WheelSide::left);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(mirrored[i], left[i], 1e-15);
  const double right_phi = spin_creepage_per_m(n, 0.46);
  EXPECT_GT(right_phi, 0.0);
  EXPECT_NEAR(spin_creepage_per_m(mirrored, 0.46), -right_phi, 1e-15);
  EXPECT_NEAR(conicity_spin_per_m(c.contact_angle_rad, WheelSide::left), -right_phi, 1e-15);
  // The left contact frame is right-handed too: X2 = X3 × X1 points to +y (field side).
  const std::array<double, 3> x2_left{0.0, left[2], -left[1]};
  EXPECT_GT(x2_left[1], 0.0);
}

// ω = (0, V/r0, 0) is rolling forward without slip: the wheel point at the bottom is at rest.
TEST(ConicitySpin, AngularVelocityRollsForwardWithoutSlip) {
  const double V = 30.0, r0 = 0.46;
  const std::array<double, 3> omega{0.0, V / r0, 0.0}, r{0.0, 0.0, -r0};
  const std::array<double, 3> cross{omega[1] * r[2] - omega[2] * r[1], omega[2] * r[0] - omega[0] * r[2],
                                    omega[0] * r[1] - omega[1] * r[0]};
  EXPECT_NEAR(V + cross[0], 0.0, 1e-12);
  EXPECT_NEAR(cross[1], 0.0, 1e-12);
  EXPECT_NEAR(cross[2], 0.0, 1e-12);
  EXPECT_NEAR(spin_creepage_per_m({0.0, std::sin(0.1), std::cos(0.1)}, r0), omega[1] * std::sin(0.1) / V, 1e-15);
}

// ---- connected regions --------------------------------------------------------------------------

TEST(ContactRegions, LabelsFourNeighbourComponents) {
  const Mesh mesh = Mesh::covering(0.0, 6.0, 0.0, 4.0, 6, 4);  // unit elements
  std::vector<double> p(mesh.size(), 0.0);
  // A 2 x 2 block, a 3-element L, and one element touching the block only at a corner.
  for (auto [i1, i2, value] : std::vector<std::array<int, 3>>{
           {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}, {4, 0, 2}, {5, 0, 2}, {5, 1, 2}, {2, 2, 1}})
    p[mesh.index(i1, i2)] = value;
  const std::vector<ContactRegion> regions = contact_regions(mesh, p);
  ASSERT_EQ(regions.size(), 3u);
  EXPECT_EQ(regions[0].elements.size(), 3u);  // the L carries 6 of 11
  EXPECT_NEAR(regions[0].load_fraction, 6.0 / 11.0, 1e-15);
  EXPECT_EQ(regions[1].elements.size(), 4u);
  EXPECT_NEAR(regions[1].x1_centre_m, 1.0, 1e-15);
  EXPECT_NEAR(regions[1].x2_centre_m, 1.0, 1e-15);
  EXPECT_EQ(regions[2].elements, (std::vector<std::size_t>{mesh.index(2, 2)}));
  EXPECT_TRUE(contact_regions(mesh, std::vector<double>(mesh.size(), 0.0)).empty());
  EXPECT_THROW((void)contact_regions(mesh, std::vector<double>(3, 1.0)), Error);
}

// The wheelset's quick lobe test on strip runs agrees with contact_regions on 3000 random patterns
// (12 x 9 elements, 35-75 % in contact: one lobe, several, corner-only contacts), and on the
// pattern of ContactRegions.LabelsFourNeighbourComponents.
TEST(ContactRegions, StripRunLobeTestAgreesWithTheRegions) {
  const Mesh mesh = Mesh::covering(0.0, 12e-3, 0.0, 9e-3, 12, 9);  // 1 mm elements
  std::mt19937 random(20261125);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  int several = 0, single = 0;
  for (int pattern = 0; pattern < 3000; ++pattern) {
    const double density = 0.35 + 0.4 * uniform(random);
    std::vector<double> p(mesh.size(), 0.0);
    for (double& value : p)
      if (uniform(random) < density) value = 1e9;
    const std::vector<ContactRegion> regions = contact_regions(mesh, p);
    if (regions.empty()) continue;
    const bool expected = regions.size() > 1;
    (expected ? several : single) += 1;
    ASSERT_EQ(detail::has_several_lobes(ContactPatch(mesh, p, Material{})), expected) << "pattern " << pattern;
  }
  EXPECT_GT(several, 100);
  EXPECT_GT(single, 100);
  std::vector<double> p(mesh.size(), 0.0);
  for (auto [i1, i2] : std::vector<std::array<int, 2>>{{0, 0}, {1, 0}, {0, 1}, {1, 1}, {2, 2}}) p[mesh.index(i1, i2)] = 1e9;
  EXPECT_TRUE(detail::has_several_lobes(ContactPatch(mesh, p, Material{})));  // a corner is no edge
  p[mesh.index(2, 1)] = 1e9;
  EXPECT_FALSE(detail::has_several_lobes(ContactPatch(mesh, p, Material{})));
}

}  // namespace
}  // namespace railcontact
