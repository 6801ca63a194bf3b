// The conformal contact surface (docs/WHEELSET.md §4 "Conformal contact"): the exact solvers and
// FastSim with creepages per strip against one creepage per patch, the conformal wheelset's mirror
// symmetry, its agreement with the planar surface where the contact angle hardly varies, and
// nH-FastSim on it against the exact solver.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "carter.hpp"
#include "geometry/conformal_surface.hpp"
#include "cli_run.hpp"
#include "railcontact/contact_patch.hpp"
#include "railcontact/error.hpp"
#include "railcontact/kalker.hpp"
#include "railcontact/normal.hpp"
#include "railcontact/tangential.hpp"
#include "railcontact/wheelset.hpp"
#include "railcontact/wheelset_table.hpp"

namespace railcontact {
namespace {

const Material kSteel{2.1e11, 0.3};
constexpr double kMu = 0.3, kLoad = 98100.0;

const WheelsetTrack& track() {
  static const WheelsetTrack t = default_wheelset_track();
  return t;
}

// One creepage (ξ, η, φ) is the strip creepages (ξ − φ x2, η, φ): both rigid slips are the same
// numbers up to rounding, so the solutions agree to the solvers' tolerance (1e-9 of μ max p3).
TEST(ConformalContact, StripCreepagesOfAPlanarPatchAreItsOneCreepage) {
  const ContactPatch p = hertzian_patch(
      elliptical_contact_with_count(6e-3, 4e-3, 1200, EllipseMeshLayout::rolling_resolved), 6e-3, 4e-3, kLoad, kSteel);
  const Creepage c{-1.2e-3, 0.8e-3, 0.6};
  StripCreepages strips(static_cast<std::size_t>(p.mesh().n2));
  for (int i2 = 0; i2 < p.mesh().n2; ++i2) strips[static_cast<std::size_t>(i2)] = {c.xi - c.phi * p.mesh().x2(i2), c.eta, c.phi};
  for (const bool regularised : {false, true}) {
    const RollingSolution one = regularised ? solve_rolling_regularised(p, c, kMu) : solve_rolling_exact(p, c, kMu);
    const RollingSolution per_strip =
        regularised ? solve_rolling_regularised(p, strips, kMu) : solve_rolling_exact(p, strips, kMu);
    const double scale = kMu * kLoad;
    EXPECT_NEAR(per_strip.forces.F1_N, one.forces.F1_N, 1e-8 * scale);
    EXPECT_NEAR(per_strip.forces.F2_N, one.forces.F2_N, 1e-8 * scale);
    EXPECT_NEAR(per_strip.forces.M3_Nm, one.forces.M3_Nm, 1e-8 * scale * 6e-3);
  }
  // FastSim marches the strips' ξ variation with L3 as Eq 2 marches −φ x2: the same numbers, with
  // every slip direction (rigid_slip turns the strips' ξ variation to L1 as it turns −φ x2).
  const NhFastSim nh(p);
  for (const SlipDirection d : {SlipDirection::radial, SlipDirection::flexibility_weighted, SlipDirection::rigid_slip}) {
    const NhFastSim with(p, nh.flexibilities(), NhFastSimOptions{.bound = {TractionBound{}.skew, d}});
    const FastSimResult a = with.solve(c, kMu), b = with.solve(strips, kMu);
    EXPECT_NEAR(b.forces.F1_N, a.forces.F1_N, 1e-9 * kMu * kLoad) << slip_direction_name(d);
    EXPECT_NEAR(b.forces.F2_N, a.forces.F2_N, 1e-9 * kMu * kLoad) << slip_direction_name(d);
    EXPECT_NEAR(b.forces.M3_Nm, a.forces.M3_Nm, 1e-9 * kMu * kLoad * 6e-3) << slip_direction_name(d);
  }
  EXPECT_THROW((void)nh.solve(StripCreepages(3), kMu), Error);
  // FastSim::strip_forces: the same march, each strip's S Σ p1 and S Σ p2 (the table's conformal
  // lookups), to rounding of solve()'s tractions summed per column.
  const FastSim fastsim(p);
  const FastSimResult traced = fastsim.solve(strips, nh.flexibility(), kMu);
  const StripForces by_strip = fastsim.strip_forces(strips, nh.flexibility(), kMu);
  std::vector<double> F1(strips.size(), 0.0), F2(strips.size(), 0.0);
  const std::vector<std::size_t>& indices = p.elements().indices();
  for (std::size_t e = 0; e < indices.size(); ++e) {
    F1[indices[e] / static_cast<std::size_t>(p.mesh().n1)] += traced.p1_Pa[e] * p.mesh().element_area_m2();
    F2[indices[e] / static_cast<std::size_t>(p.mesh().n1)] += traced.p2_Pa[e] * p.mesh().element_area_m2();
  }
  for (std::size_t j = 0; j < strips.size(); ++j) {
    EXPECT_NEAR(by_strip.F1_N[j], F1[j], 1e-9 * kMu * kLoad) << j;
    EXPECT_NEAR(by_strip.F2_N[j], F2[j], 1e-9 * kMu * kLoad) << j;
  }
  EXPECT_NEAR(by_strip.forces.F1_N, traced.forces.F1_N, 1e-12 * kMu * kLoad);
  EXPECT_NEAR(by_strip.forces.M3_Nm, traced.forces.M3_Nm, 1e-12 * kMu * kLoad * 6e-3);
  EXPECT_THROW((void)fastsim.strip_forces(StripCreepages(3), nh.flexibility(), kMu), Error);
  // The count of strips and their values are checked.
  EXPECT_THROW((void)solve_rolling_exact(p, StripCreepages(3), kMu), Error);
  strips[2].eta = std::nan("");
  EXPECT_THROW((void)solve_rolling_exact(p, strips, kMu), Error);
}

WheelsetOptions conformal_options() {
  WheelsetOptions o;
  o.element_size_m = 0.2e-3;
  o.solvers = {TangentialSolver::exact};
  o.contact_surface = ContactSurface::conformal;
  return o;
}

WheelsetState rolling_at(double y_m, double yaw_rad = 0.0) {
  WheelsetState s;
  s.position.lateral_displacement_m = y_m;
  s.position.yaw_rad = yaw_rad;
  s.velocity.forward_speed_m_per_s = 20.0;
  return s;
}

// The left wheel at (y, ψ) is the mirrored right wheel at (−y, −ψ), in flange contact too.
TEST(ConformalContact, TheLeftWheelIsTheMirroredRightWheel) {
  Wheelset wheelset(track(), conformal_options());
  const WheelsetResult a = wheelset.evaluate(rolling_at(6.5e-3, 2e-3));
  const WheelsetResult b = wheelset.evaluate(rolling_at(-6.5e-3, -2e-3));
  for (int w = 0; w < 2; ++w) {
    const Vector3& f = a.wheels[w].force_track_N;
    const Vector3& g = b.wheels[1 - w].force_track_N;
    EXPECT_NEAR(f[0], g[0], 1e-6 * f[2]) << w;
    EXPECT_NEAR(f[1], -g[1], 1e-6 * f[2]) << w;
    EXPECT_NEAR(f[2], g[2], 1e-6 * f[2]) << w;
  }
  ASSERT_EQ(a.wheels[1].patches.size(), 1u);
  EXPECT_EQ(a.wheels[1].patches[0].surface, ContactSurface::conformal);
}

// On the tread (y = 0: the strips in contact turn by less than 0.05 rad from the contact frame)
// the curved surface changes the lateral and vertical forces little: within 1 % of μ Fz of the
// planar surface. (F1 moves by 1.7 kN: the strips' rolling radii follow the curved surface, see
// conformal_patch.hpp.) At the flange (y = 6.5 mm, strips from −0.20 to +0.26 rad) it changes the
// lateral force by 16 % of μ Fz.
TEST(ConformalContact, OnTheTreadItIsNearlyThePlanarSurface) {
  WheelsetOptions planar = conformal_options();
  planar.contact_surface = ContactSurface::planar;
  Wheelset curved(track(), conformal_options()), flat(track(), planar);
  const double scale = kMu * 98.1e3;
  const WheelsetResult c0 = curved.evaluate(rolling_at(0.0)), p0 = flat.evaluate(rolling_at(0.0));
  for (int w = 0; w < 2; ++w)
    for (int i = 1; i < 3; ++i)
      EXPECT_NEAR(c0.wheels[w].force_track_N[i], p0.wheels[w].force_track_N[i], 0.01 * scale) << w << " " << i;
  const WheelsetResult c1 = curved.evaluate(rolling_at(6.5e-3)), p1 = flat.evaluate(rolling_at(6.5e-3));
  EXPECT_GT(c1.wheels[1].force_track_N[1] - p1.wheels[1].force_track_N[1], 0.1 * scale);
}

// nH-FastSim on a conformal patch (K2 on the developed patch, the strips' own creepages) against
// the exact solver on it, per patch, at the tread, flange root and flange: within 3 % of μ F3
// (measured 0.85, 0.34 and 1.08 %; the flange root's two lobes are marched per lobe).
TEST(ConformalContact, NhFastSimIsWithinThreePercentOfTheExactSolverOnIt) {
  WheelsetOptions o = conformal_options();
  o.solvers = {TangentialSolver::exact, TangentialSolver::nh_fastsim};
  Wheelset wheelset(track(), o);
  for (const double y : {0.0, 5e-3, 6.5e-3}) {
    const WheelsetResult r = wheelset.evaluate(rolling_at(y));
    for (const WheelResult& w : r.wheels)
      for (const WheelsetPatch& p : w.patches) {
        const double scale = kMu * p.normal_force_N;
        EXPECT_NEAR(p.solvers[1].forces.F1_N, p.solvers[0].forces.F1_N, 0.03 * scale) << y;
        EXPECT_NEAR(p.solvers[1].forces.F2_N, p.solvers[0].forces.F2_N, 0.03 * scale) << y;
      }
  }
  EXPECT_EQ(parse_contact_surface("conformal"), ContactSurface::conformal);
  EXPECT_THROW((void)parse_contact_surface("curved"), Error);
}

// The wheelset table on the conformal and the automatic surface (docs/WHEELSET_TABLE.md §1): each
// node keeps a patch's conformal solution with one strip frame per column of its runtime copy, and
// a lookup marches FastSim strip by strip with each strip's creepages. With the fine patches as the
// runtime copies, at a node it is the wheelset on the fly to rounding, on the tread (y = 0), in the
// automatic surface's blend (−0.5 mm: the right wheel's tread), at the flange root (a
// patch of two lobes, −5.2 mm) and in flange contact (−6.5 mm), for a moving state; the round trip
// through the file keeps it to the digit.
WheelsetOptions table_wheelset_options(ContactSurface surface) {
  WheelsetOptions o;
  o.element_size_m = 0.5e-3;
  o.contact_surface = surface;
  o.tangential_forces_in_vertical_balance = false;  // the table's nodes: the frictionless balance
  return o;
}

WheelsetState moving_at(double y_m, double yaw_rad) {
  WheelsetState s = rolling_at(y_m, yaw_rad);
  s.velocity.lateral_velocity_m_per_s = 0.02;
  s.velocity.yaw_rate_rad_per_s = 0.01;
  s.velocity.extra_longitudinal_creepage = -1e-3;
  return s;
}

TEST(ConformalContact, AWheelsetTableOnTheCurvedSurfaceIsTheWheelsetOnTheFlyAtItsNodes) {
  const std::vector<double> y{-6.5e-3, -5.2e-3, -0.5e-3, 0.0};
  for (const ContactSurface surface : {ContactSurface::conformal, ContactSurface::automatic}) {
    WheelsetTableOptions o;
    o.wheelset = table_wheelset_options(surface);
    o.runtime_elements = 100000;  // the fine patches themselves
    const WheelsetTable built = build_wheelset_table(track(), {y, {0.0}, {kLoad}}, o);
    EXPECT_EQ(built.metadata().contact_surface, surface);
    // At −5.2 mm the flange root and the tread form one conformal patch of two lobes, each with its
    // own flexibilities and strips (as the wheelset solves it: NhFastSimPerLobe on the developed patch).
    const WheelsetTablePatch& root = built.node(1, 0, 0).wheels[0].front();
    ASSERT_TRUE(root.conformal.has_value());
    EXPECT_EQ(root.conformal->lobes.size(), 2u);
    for (const WheelsetTableLobe& lobe : root.conformal->lobes)
      EXPECT_EQ(lobe.strips.size(), static_cast<std::size_t>(lobe.runtime_mesh.n2));
    if (surface == ContactSurface::automatic) {  // the tread at −0.5 mm: both surfaces, blended
      const WheelsetTablePatch& tread = built.node(2, 0, 0).wheels[0].front();
      ASSERT_TRUE(tread.conformal.has_value());
      EXPECT_GT(tread.conformal->weight, 0.1);
      EXPECT_LT(tread.conformal->weight, 0.9);
      EXPECT_FALSE(tread.runtime_pressure_Pa.empty());
    }
    const WheelsetTable table = parse_wheelset_table(wheelset_table_json(built), "round trip");
    // A malformed conformal part is refused, naming the node, wheel and patch.
    nlohmann::json file = nlohmann::json::parse(wheelset_table_json(built));
    nlohmann::json& flange = file["nodes"][0]["wheels"][0][0]["conformal"];
    ASSERT_TRUE(flange.is_object());
    const auto refusal = [](const nlohmann::json& f) {
      try {
        (void)parse_wheelset_table(f.dump(), "t.json");
      } catch (const Error& e) {
        return std::string(e.what());
      }
      return std::string("no error");
    };
    flange["weight"] = 1.5;
    EXPECT_NE(refusal(file).find("nodes[0] wheel 0 patch 0: the conformal surface's weight must lie in (0, 1]"),
              std::string::npos)
        << refusal(file);
    flange["weight"] = 0.5;  // a blend needs the planar surface's runtime copy, which the flange has not
    EXPECT_NE(refusal(file).find("needs its runtime copy (runtime_pressure_Pa)"), std::string::npos) << refusal(file);
    flange["weight"] = 1.0;
    flange["strips"].erase(0);
    EXPECT_NE(refusal(file).find("one strip per column of its runtime mesh"), std::string::npos) << refusal(file);
    for (const double at : y) {
      const WheelsetState state = moving_at(at, 0.0);
      const WheelsetResult expected = Wheelset(track(), o.wheelset).evaluate(state);
      const WheelsetResult got = table.evaluate(state, WheelLoads{kLoad, kLoad, false}, kMu);
      for (int w = 0; w < 2; ++w) {
        ASSERT_EQ(got.wheels[w].patches.size(), expected.wheels[w].patches.size()) << at;
        for (int i = 0; i < 3; ++i)
          EXPECT_NEAR(got.wheels[w].force_track_N[i], expected.wheels[w].force_track_N[i], 1e-7 * kLoad)
              << contact_surface_name(surface) << " y " << at << " wheel " << w << " component " << i;
        for (std::size_t k = 0; k < got.wheels[w].patches.size(); ++k) {
          const WheelsetPatch &p = got.wheels[w].patches[k], &q = expected.wheels[w].patches[k];
          EXPECT_NEAR(p.conformal_weight, q.conformal_weight, 1e-11);
          EXPECT_EQ(p.surface, q.surface);
          EXPECT_NEAR(p.forces().M3_Nm, q.forces().M3_Nm, 1e-9 * kLoad);
          EXPECT_NEAR(p.normal_force_N, q.normal_force_N, 1e-9 * kLoad);
          for (int i = 0; i < 3; ++i)
            EXPECT_NEAR(p.pressure_force_track_N[i], q.pressure_force_track_N[i], 1e-9 * kLoad);
        }
      }
    }
  }
  // What the table was built with is a setting of its lookups.
  WheelsetTableOptions planar;
  planar.wheelset = table_wheelset_options(ContactSurface::planar);
  const WheelsetTable table = build_wheelset_table(track(), {{0.0}, {0.0}, {kLoad}}, planar);
  const std::vector<WheelsetTableMismatch> m = table.mismatches(table_wheelset_options(ContactSurface::automatic));
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].setting, WheelsetTableSetting::contact_surface);
  EXPECT_EQ(m[0].requested, "auto (conformal from 0.02 to 0.03)");
  EXPECT_EQ(m[0].table, "planar");
}

// Between nodes 0.1 mm apart, from the flange root to flange contact (the right wheel's patch on the
// conformal surface, weight 1), with the default runtime copies (2 × 2 blocks on the flange): within
// 2 % of μFz of the wheelset on the fly in every component (largest 1.09 %, at y = −5.65 mm).
TEST(ConformalContact, BetweenNodesTheCurvedTableStaysWithinTwoPercentOfMuFz) {
  WheelsetTableOptions o;
  o.wheelset = table_wheelset_options(ContactSurface::automatic);
  std::vector<double> nodes;
  for (const double y : {-6.4e-3, -5.7e-3, -5.1e-3, -4.4e-3}) nodes.insert(nodes.end(), {y, y + 0.1e-3});
  std::sort(nodes.begin(), nodes.end());
  const WheelsetTable table = build_wheelset_table(track(), {nodes, {0.0}, {90e3, 110e3}}, o);
  WheelsetOptions fly = o.wheelset;
  fly.loads = WheelLoads{97e3, 104e3, false};
  for (const double y : {-6.35e-3, -5.65e-3, -5.05e-3, -4.35e-3}) {
    const WheelsetState state = moving_at(y, 0.0);
    const WheelsetResult expected = Wheelset(track(), fly).evaluate(state);
    EXPECT_EQ(expected.wheels[0].patches.back().conformal_weight, 1.0) << y;
    const WheelsetResult got = table.evaluate(state, *fly.loads, kMu);
    for (int w = 0; w < 2; ++w)
      for (int i = 0; i < 3; ++i) {
        const double miss = std::abs(got.wheels[w].force_track_N[i] - expected.wheels[w].force_track_N[i]) /
                            (kMu * (w == 0 ? 97e3 : 104e3));
        EXPECT_LT(miss, 0.02) << "y " << y << " wheel " << w << " component " << i;
      }
  }
}

// A developed surface that turns by more than 90° from the reference's tangent plane folds over:
// its strips' tangent-plane points run back. Strips on a circle of radius 10 mm turning from −0.5 to
// 2 rad rise in x2 = R sin Δ up to Δ = π/2, then fall: refused, naming the wheel, the position and
// the angles where it folds; strips that cannot touch are not counted. The potential contact area of
// the flange of S1002/UIC60 at y = −6.5 mm turns by 1.4 rad across its strips, each within ±π/2 of
// the reference: accepted.
TEST(ConformalContact, ASurfaceThatFoldsOverIsRefusedNamingWhereItFolds) {
  std::vector<ConformalStrip> strips;
  for (double angle = -0.5; angle <= 2.0; angle += 0.1) {
    ConformalStrip strip;
    strip.angle_rad = angle;
    strip.x2_m = 10e-3 * std::sin(angle);
    strip.s_m = 10e-3 * angle;
    strips.push_back(strip);
  }
  WheelsetPosition at;
  at.lateral_displacement_m = -6.5e-3;
  at.yaw_rad = 2e-3;
  try {
    geometry::require_unfolded(strips, WheelSide::left, at);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::invalid_input);
    EXPECT_NE(std::string(e.what()).find("conformal contact area of the left wheel at y = -6.500 mm, yaw 2.00 mrad: the "
                                         "curved surface folds over (its normal turns from 1.600 to 1.700 rad"),
              std::string::npos)
        << e.what();
  }
  // Up to a quarter turn, or with the strips beyond it out of contact, it does not fold.
  for (ConformalStrip& strip : strips) strip.possible_contact = strip.angle_rad < 1.55;
  EXPECT_NO_THROW(geometry::require_unfolded(strips, WheelSide::left, at));
  const TangentPlaneArea flange = track().conformal_contact_area(
      at, track().contact_search(WheelSide::right, at).regions.front(), 0.2e-3);
  double lowest = 10.0, highest = -10.0;
  for (const ConformalStrip& strip : flange.strips)
    if (strip.possible_contact) lowest = std::min(lowest, strip.angle_rad), highest = std::max(highest, strip.angle_rad);
  EXPECT_GT(highest - lowest, 1.0);
  EXPECT_LT(std::max(highest, -lowest), std::acos(-1.0) / 2);
}

// A cylinder in a slightly larger groove (issue #31's check of the normal problem): a rail head of
// radius R1 = 50 mm (an arc of ±1 rad, flanks below) under a wheel whose tread is a groove of radius
// R2 = 50.25 mm, centred on it, 50 kN. The contact spans ±0.41 rad of the head (the strips' angles),
// 20.7 mm either side. The reference is the half-space problem on the developed surface (s = R1 θ)
// with the exact normal gap of the two circles, t(θ) = −e cos θ + √(R2² − e² sin² θ) − R1 with
// e = R2 − R1 + δ, plus x1² cos θ / (2 r_w) of the wheel's rolling curvature, solved at the approach δ
// the wheelset reports: the conformal surface meets it to 0.01 % in F3 and p0, to the element in its
// half-width; the planar surface, whose gap is measured along X3 in the tangent plane, is 1 % off in
// F3 at its approach and 0.4 mm (1 %) narrower.
namespace groove {
constexpr double kR1 = 0.05, kR2 = 0.05025, kArc = 1.0;
Profile rail() {
  Profile p;
  p.kind = ProfileKind::rail;
  p.source = "cylinder R50";
  const double y_flank = kR1 * std::sin(kArc), z_flank = kR1 * (1.0 - std::cos(kArc));
  for (double z = 0.045; z > z_flank + 1e-4; z -= 0.5e-3) p.y_m.push_back(-y_flank), p.z_m.push_back(z);
  for (double t = -kArc; t <= kArc + 1e-9; t += 0.002) p.y_m.push_back(kR1 * std::sin(t)), p.z_m.push_back(kR1 * (1.0 - std::cos(t)));
  for (double z = z_flank + 0.5e-3; z <= 0.045; z += 0.5e-3) p.y_m.push_back(y_flank), p.z_m.push_back(z);
  return p;
}
Profile wheel() {  // z down; the deeper side of the groove (y < 0) stands for the flange
  Profile p;
  p.kind = ProfileKind::wheel;
  p.source = "groove R50.25";
  for (double t = std::asin(0.034 / kR2); t >= -std::asin(0.045 / kR2) - 1e-12; t -= 0.002)
    p.y_m.push_back(kR2 * std::sin(t)), p.z_m.push_back(kR2 * (1.0 - std::cos(t)));
  return p;
}
WheelsetTrack track() {
  TrackWheelsetParameters t;  // the groove centred on the rail: the gauge point 14 mm down the head
  t.flange_back_y_m = -(t.track_gauge_m / 2 + kR1 * std::sin(std::acos(1.0 - t.gauge_measuring_depth_m / kR1)) -
                        t.flange_back_distance_m / 2);
  return WheelsetTrack(wheel(), rail(), t);
}
// The reference's F3, p0 and half-width in s at approach δ (elements of size h centred as the wheelset's).
struct Reference {
  double normal_force_N = 0.0, max_pressure_Pa = 0.0, half_width_m = 0.0;
};
Reference solve(double delta_m, double rolling_radius_m, double h_m, const Material& material) {
  Mesh m;
  m.n1 = 61;
  m.n2 = 301;
  m.dx1_m = m.dx2_m = h_m;
  m.x1_first_m = -30 * h_m;
  m.x2_first_m = -150 * h_m;
  const double e = kR2 - kR1 + delta_m;
  std::vector<double> gap(m.size());
  for (int i2 = 0; i2 < m.n2; ++i2) {
    const double theta = m.x2(i2) / kR1;
    const double t = -e * std::cos(theta) + std::sqrt(kR2 * kR2 - e * e * std::sin(theta) * std::sin(theta)) - kR1;
    const double y_wheel = (kR1 + t) * std::sin(theta);
    const double r_wheel = rolling_radius_m + kR2 - std::sqrt(kR2 * kR2 - y_wheel * y_wheel);
    for (int i1 = 0; i1 < m.n1; ++i1)
      gap[m.index(i1, i2)] = t + m.x1(i1) * m.x1(i1) * std::cos(theta) / (2.0 * r_wheel);
  }
  const NormalSolution n = solve_normal_contact_at_approach(m, gap, 0.0, material);
  Reference r;
  r.normal_force_N = n.normal_force_N;
  for (int i2 = 0; i2 < m.n2; ++i2)
    for (int i1 = 0; i1 < m.n1; ++i1)
      if (const double p = n.pressure_Pa[m.index(i1, i2)]; p > 0.0) {
        r.max_pressure_Pa = std::max(r.max_pressure_Pa, p);
        r.half_width_m = std::max(r.half_width_m, std::abs(m.x2(i2)) + 0.5 * h_m);
      }
  return r;
}
}  // namespace groove

TEST(ConformalContact, ACylinderInASlightlyLargerGrooveIsSolvedWithTheExactNormalGap) {
  const WheelsetTrack track = groove::track();
  double planar_off = 0.0, planar_width = 0.0, width = 0.0;
  for (const ContactSurface surface : {ContactSurface::conformal, ContactSurface::planar}) {
    WheelsetOptions o;
    o.contact_surface = surface;
    o.loads = WheelLoads{50e3, 50e3, false};
    o.keep_tractions = true;
    const WheelsetResult r = Wheelset(track, o).evaluate(rolling_at(0.0));
    ASSERT_EQ(r.wheels[0].patches.size(), 1u);
    const WheelsetPatch& p = r.wheels[0].patches[0];
    const groove::Reference ref = groove::solve(p.approach_m, p.rolling_radius_m, o.element_size_m, o.material);
    const Mesh& mesh = p.patch.mesh();
    double half_width = 0.0;
    for (const std::size_t k : p.patch.elements().indices())
      half_width = std::max(half_width, std::abs(mesh.x2(static_cast<int>(k) / mesh.n1) - mesh.x2(0) - 0.5 * (mesh.x2(mesh.n2 - 1) - mesh.x2(0))));
    if (surface == ContactSurface::conformal) {
      ASSERT_GT(p.strips.size(), 100u);
      EXPECT_NEAR(p.strips.front().angle_rad, 0.41, 0.01);
      EXPECT_NEAR(p.normal_force_N, ref.normal_force_N, 1e-4 * ref.normal_force_N);
      EXPECT_NEAR(p.max_pressure_Pa, ref.max_pressure_Pa, 1e-3 * ref.max_pressure_Pa);
      width = 2.0 * (half_width + 0.5 * o.element_size_m);
      EXPECT_NEAR(width, 2.0 * ref.half_width_m, 2.01 * o.element_size_m);
    } else {
      planar_off = p.normal_force_N / ref.normal_force_N - 1.0;
      planar_width = 2.0 * (half_width + 0.5 * o.element_size_m);
    }
  }
  EXPECT_GT(planar_off, 0.008);
  EXPECT_GT(width - planar_width, 0.0003) << width << " " << planar_width;
}

// ContactSurface::automatic, patch by patch (by position, so that both surfaces are solved at one
// overlap of 0.08 mm): at y = −0.5 mm the left wheel's tread patch (spread / cos γ 0.017) is the
// planar patch, the right wheel's (0.025, in the band 0.02–0.03) the blend (1 − w) planar + w conformal of both
// surfaces' results, and at −6.5 mm the right wheel's flange patch (0.18) the conformal one.
TEST(ConformalContact, TheAutomaticSurfaceIsPlanarConformalOrTheirBlend) {
  WheelsetOptions o;
  o.element_size_m = 0.3e-3;
  o.loads.reset();
  const auto solved = [&](ContactSurface surface, double y_m) {
    WheelsetOptions with = o;
    with.contact_surface = surface;
    Wheelset wheelset(track(), with);
    WheelsetState s = rolling_at(y_m);
    s.position.vertical_displacement_m = -0.08e-3;
    return wheelset.evaluate(s);
  };
  const double scale = kMu * kLoad;
  const WheelsetResult planar = solved(ContactSurface::planar, -0.5e-3),
                       conformal = solved(ContactSurface::conformal, -0.5e-3),
                       automatic = solved(ContactSurface::automatic, -0.5e-3);
  const WheelsetPatch& tread = automatic.wheels[1].patches.at(0);
  EXPECT_EQ(tread.conformal_weight, 0.0);
  EXPECT_EQ(tread.surface, ContactSurface::planar);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(automatic.wheels[1].force_track_N[i], planar.wheels[1].force_track_N[i], 1e-9 * scale) << i;
  const WheelsetPatch& blended = automatic.wheels[0].patches.at(0);
  const double w = blended.conformal_weight;
  EXPECT_GT(w, 0.05);
  EXPECT_LT(w, 0.95);
  EXPECT_EQ(blended.surface, ContactSurface::conformal);
  const WheelsetPatch &p = planar.wheels[0].patches.at(0), &c = conformal.wheels[0].patches.at(0);
  EXPECT_NEAR(blended.normal_force_N, (1 - w) * p.normal_force_N + w * c.normal_force_N, 1e-6 * kLoad);
  EXPECT_NEAR(blended.creepage.xi, (1 - w) * p.creepage.xi + w * c.creepage.xi, 1e-12);
  for (int i = 0; i < 3; ++i) {
    const double expected = (1 - w) * p.solvers[0].force_track_N[i] + w * c.solvers[0].force_track_N[i];
    EXPECT_NEAR(blended.solvers[0].force_track_N[i], expected, 1e-6 * scale) << i;
  }
  // The blend matters: the two surfaces differ here by more than the tolerance above.
  EXPECT_GT(std::abs(c.solvers[0].force_track_N[0] - p.solvers[0].force_track_N[0]), 1e-3 * scale);
  const WheelsetResult flange = solved(ContactSurface::automatic, -6.5e-3),
                       flange_conformal = solved(ContactSurface::conformal, -6.5e-3);
  EXPECT_EQ(flange.wheels[0].patches.at(0).conformal_weight, 1.0);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(flange.wheels[0].force_track_N[i], flange_conformal.wheels[0].force_track_N[i], 1e-9 * scale) << i;
}

// The automatic surface's weight: 0 up to planar_up_to, 1 from conformal_from, ½ midway, and 1 for
// a region whose spread is not known; a band that is not one is refused.
TEST(ConformalContact, TheAutomaticSurfacesWeightRisesSmoothlyOverItsBand) {
  const ContactSurfaceSwitch band{0.02, 0.03};
  InterpenetrationRegion r;
  r.contact_angle_rad = 0.0;
  const auto weight = [&](double spread) {
    r.contact_angle_spread_rad = spread;
    return conformal_surface_weight(ContactSurface::automatic, band, r);
  };
  EXPECT_EQ(weight(0.01), 0.0);
  EXPECT_EQ(weight(0.02), 0.0);
  EXPECT_NEAR(weight(0.025), 0.5, 1e-12);
  EXPECT_EQ(weight(0.03), 1.0);
  EXPECT_EQ(weight(std::nan("")), 1.0);
  EXPECT_LT(weight(0.02 + 1e-6) / 1e-6, 0.1);  // flat at the band's ends (C¹; a ramp's slope is 100)
  EXPECT_LT((1.0 - weight(0.03 - 1e-6)) / 1e-6, 0.1);
  r.contact_angle_rad = 1.2;  // a steep flange: the same spread weighs 1 / cos γ = 2.8 times more
  EXPECT_EQ(weight(0.012), 1.0);
  EXPECT_EQ(conformal_surface_weight(ContactSurface::planar, band, r), 0.0);
  EXPECT_EQ(conformal_surface_weight(ContactSurface::conformal, band, r), 1.0);
  EXPECT_THROW(validate(ContactSurfaceSwitch{0.03, 0.02}), Error);
  EXPECT_THROW(validate(ContactSurfaceSwitch{-0.01, 0.02}), Error);
  EXPECT_EQ(parse_contact_surface("auto"), ContactSurface::automatic);
}

// The spread is continuous in y where the half-depth range jumps (S1002/UIC60 at 4.7 mm towards
// the flange: the flange root's overlap crosses half the deepest overlap and the range widens from
// 0.07 to 0.15 rad between two positions 5 µm apart), so the automatic choice is continuous too.
TEST(ConformalContact, TheSpreadIsContinuousWhereTheHalfDepthRangeJumps) {
  double largest_range_step = 0.0, largest_spread_step = 0.0;
  double previous_range = std::nan(""), previous_spread = std::nan("");
  for (int k = 0; k <= 80; ++k) {
    WheelsetPosition position;
    position.lateral_displacement_m = -4.6e-3 - k * 5e-6;
    position.vertical_displacement_m = track().touching_vertical_displacement_m(WheelSide::right, position) - 0.08e-3;
    const WheelContactSearch search = track().contact_search(WheelSide::right, position);
    ASSERT_EQ(search.regions.size(), 1u) << position.lateral_displacement_m;
    const InterpenetrationRegion& r = search.regions[0];
    const double range = contact_angle_variation_rad(r), spread = r.contact_angle_spread_rad;
    if (k > 0) {
      largest_range_step = std::max(largest_range_step, std::abs(range - previous_range));
      largest_spread_step = std::max(largest_spread_step, std::abs(spread - previous_spread));
    }
    previous_range = range;
    previous_spread = spread;
  }
  EXPECT_GT(largest_range_step, 0.04);
  EXPECT_LT(largest_spread_step, 1e-3);
}

// The case file's [mesh] contact_surface and the command line's --contact-surface choose the
// surface; the JSON names it per patch with its strips' angles; a bad name is refused with its place.
TEST(ConformalContact, TheCaseFileAndTheCommandLineChooseIt) {
  const test::ScratchDirectory dir("conformal_case");
  const std::string file = (dir.path() / "case.toml").string();
  std::ofstream(file) << "[position]\ny_mm = 6.5\n[mesh]\nelement_size_mm = 0.5\ncontact_surface = \"conformal\"\n"
                         "[solvers]\nrun = [\"nh-fastsim\", \"exact\"]\n";
  const test::CommandResult r = test::run_cli("wheelset " + file + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  const nlohmann::json& patch = j["wheels"][1]["patches"][0];
  EXPECT_EQ(patch["contact_surface"], "conformal");
  EXPECT_LT(patch["strip_angle_range_rad"][0].get<double>(), -0.1);
  EXPECT_GT(patch["strip_angle_range_rad"][1].get<double>(), 0.1);
  EXPECT_EQ(patch["conformal_weight"], 1.0);
  const test::CommandResult planar = test::run_cli("wheelset " + file + " --contact-surface planar --json");
  ASSERT_EQ(planar.exit_code, 0) << planar.err;
  EXPECT_EQ(nlohmann::json::parse(planar.out)["wheels"][1]["patches"][0]["contact_surface"], "planar");
  const test::CommandResult automatic = test::run_cli("wheelset " + file + " --contact-surface auto --json");
  ASSERT_EQ(automatic.exit_code, 0) << automatic.err;
  EXPECT_EQ(nlohmann::json::parse(automatic.out)["wheels"][1]["patches"][0]["conformal_weight"], 1.0);
  EXPECT_EQ(nlohmann::json::parse(automatic.out)["wheels"][0]["patches"][0]["conformal_weight"], 0.0);
  std::ofstream(file) << "[mesh]\ncontact_surface = \"curved\"\n";
  const test::CommandResult bad = test::run_cli("wheelset " + file);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find(":2: [mesh] contact_surface: unknown contact surface 'curved'"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace railcontact
