// The wheelset table (wheelset_table.hpp, docs/WHEELSET_TABLE.md) on S1002 / UIC60 1:40 against
// the wheelset it tabulates: at a node with the full patch it is Wheelset::evaluate to rounding;
// between nodes within the interpolation error; the left wheel is the mirrored right wheel; a
// flange patch that appears between nodes grows from zero force; bad lookups are refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "cli_run.hpp"
#include "railcontact/error.hpp"
#include "railcontact/wheel_rail.hpp"
#include "railcontact/wheelset_table.hpp"

namespace railcontact {
namespace {

constexpr double kMu = 0.3;

const WheelsetTrack& track() {
  static const WheelsetTrack t = default_wheelset_track();
  return t;
}

// Coarse elements keep the builds fast (0.5 mm: about 700 elements per tread patch).
WheelsetTableOptions coarse_table_options(int runtime_elements = kWheelsetTableRuntimeElements) {
  WheelsetTableOptions o;
  o.wheelset.element_size_m = 0.5e-3;
  o.runtime_elements = runtime_elements;
  return o;
}

// The same wheelset solved on the fly (frictionless load balance, as the table's nodes).
WheelsetResult on_the_fly(const WheelsetState& state, double load_right_N, double load_left_N) {
  WheelsetOptions o = coarse_table_options().wheelset;
  o.loads = WheelLoads{load_right_N, load_left_N, false};
  o.tangential_forces_in_vertical_balance = false;
  o.friction_coefficient = kMu;
  Wheelset wheelset(track(), o);
  return wheelset.evaluate(state);
}

WheelsetState moving_state(double y_m, double yaw_rad = 0.0) {
  WheelsetState s;
  s.position.lateral_displacement_m = y_m;
  s.position.yaw_rad = yaw_rad;
  s.velocity.forward_speed_m_per_s = 30.0;
  s.velocity.lateral_velocity_m_per_s = 0.02;
  s.velocity.yaw_rate_rad_per_s = 0.01;
  s.velocity.extra_longitudinal_creepage = -1e-3;
  return s;
}

// A table whose runtime patches are the fine patches themselves (no coarsening).
const WheelsetTable& full_patch_table() {
  static const WheelsetTable t =
      build_wheelset_table(track(), {{-2e-3, -1e-3, 0.0, 1e-3, 2e-3}, {0.0}, {90e3, 110e3}}, coarse_table_options(100000));
  return t;
}

// The default recipe (runtime patches of about 400 elements), y in steps of 0.5 mm.
const WheelsetTable& table() {
  static const WheelsetTable t = build_wheelset_table(
      track(), {{-2e-3, -1.5e-3, -1e-3, -0.5e-3, 0.0, 0.5e-3, 1e-3, 1.5e-3, 2e-3}, {0.0}, {90e3, 110e3}},
      coarse_table_options());
  return t;
}

// A table file as an older format wrote it: without format 6's contact surface and conformal parts
// (and format 8's patch coupling).
nlohmann::json before_format_6(nlohmann::json file) {
  file.erase("patch_coupling");
  file.erase("contact_surface");
  file.erase("contact_surface_switch");
  for (nlohmann::json& node : file["nodes"])
    for (nlohmann::json& wheel : node["wheels"])
      for (nlohmann::json& patch : wheel) patch.erase("conformal");
  return file;
}

TEST(WheelsetTable, AtANodeWithTheFullPatchItIsTheWheelsetSolvedOnTheFly) {
  for (double y : {-2e-3, 0.0, 1e-3}) {
    for (double load : {90e3, 110e3}) {
      const WheelsetState state = moving_state(y);
      const WheelsetResult expected = on_the_fly(state, load, load);
      const WheelsetResult got = full_patch_table().evaluate(state, WheelLoads{load, load, false}, kMu);
      for (int w = 0; w < 2; ++w) {
        ASSERT_EQ(got.wheels[w].patches.size(), expected.wheels[w].patches.size()) << "y " << y << " wheel " << w;
        for (int i = 0; i < 3; ++i)
          EXPECT_NEAR(got.wheels[w].force_track_N[i], expected.wheels[w].force_track_N[i], 1e-7 * load)
              << "y " << y << " load " << load << " wheel " << w << " component " << i;
        const WheelsetPatch& p = got.wheels[w].patches.front();
        const WheelsetPatch& q = expected.wheels[w].patches.front();
        EXPECT_NEAR(p.creepage.xi, q.creepage.xi, 1e-12);
        EXPECT_NEAR(p.creepage.eta, q.creepage.eta, 1e-12);
        EXPECT_NEAR(p.creepage.phi, q.creepage.phi, 1e-9);
        EXPECT_NEAR(p.forces().M3_Nm, q.forces().M3_Nm, 1e-9 * load);
        EXPECT_NEAR(p.region.contact_angle_rad, q.region.contact_angle_rad, 1e-12);
        EXPECT_NEAR(got.wheels[w].vertical_displacement_m, expected.wheels[w].vertical_displacement_m, 1e-12);
        // The same assembly: the forces per solver (the table's one, nH-FastSim) as on the fly.
        ASSERT_EQ(got.wheels[w].solver_force_track_N.size(), 1u);
        EXPECT_EQ(got.wheels[w].solver_force_track_N[0], got.wheels[w].force_track_N);
      }
      ASSERT_EQ(got.solver_force_track_N.size(), 1u);
      for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(got.solver_force_track_N[0][i], got.force_track_N[i]);
        EXPECT_NEAR(got.force_track_N[i], expected.force_track_N[i], 2e-7 * load);
      }
    }
  }
}

// Where the tread and the flange root form one patch of two lobes (y = −4.8 … −5.6 mm at 100 kN),
// the table keeps each lobe's flexibilities and coarse patch (NhFastSimPerLobe, docs/WHEELSET.md
// §8): at a node with the full patches it is the wheelset on the fly (forces to 1e-7 of the load),
// as without lobes. With the whole patch's flexibilities (the lobes dropped) it is not: the right
// wheel's longitudinal force moves by more than 1 % of μFz. The lobes survive a round trip.
TEST(WheelsetTable, APatchOfTwoLobesIsSolvedPerLobeAsOnTheFly) {
  const WheelsetTable t = build_wheelset_table(track(), {{-5.3e-3, -5.2e-3}, {0.0}, {100e3}}, coarse_table_options(100000));
  const WheelsetTableNode& node = t.node(0, 0, 0);
  ASSERT_EQ(node.wheels[0].size(), 1u);
  ASSERT_EQ(node.wheels[0][0].lobes.size(), 2u);
  EXPECT_TRUE(node.wheels[1][0].lobes.empty());  // the left wheel's tread
  for (double y : {-5.3e-3, -5.2e-3}) {
    const WheelsetState state = moving_state(y);
    const WheelsetResult expected = on_the_fly(state, 100e3, 100e3);
    const WheelsetResult got = t.evaluate(state, WheelLoads{100e3, 100e3, false}, kMu);
    for (int w = 0; w < 2; ++w) {
      for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(got.wheels[w].force_track_N[i], expected.wheels[w].force_track_N[i], 1e-7 * 100e3)
            << "y " << y << " wheel " << w << " component " << i;
      EXPECT_NEAR(got.wheels[w].patches.front().forces().M3_Nm, expected.wheels[w].patches.front().forces().M3_Nm, 1e-9 * 100e3);
    }
  }
  // The lobes dropped in the file: one set of flexibilities for the whole patch. With the
  // rigid-slip direction: with the elastic slip (the default) this state's patch slips everywhere
  // and takes Coulomb's law along the elastic slip, which does not depend on the flexibilities.
  WheelsetTableOptions rigid_options = coarse_table_options(100000);
  rigid_options.wheelset.nh_fastsim.bound.slip_direction = SlipDirection::rigid_slip;
  const WheelsetTable rigid = build_wheelset_table(track(), {{-5.3e-3, -5.2e-3}, {0.0}, {100e3}}, rigid_options);
  const std::string text = wheelset_table_json(rigid);
  const WheelsetTable back = parse_wheelset_table(text, "lobes.json");
  EXPECT_EQ(back.node(0, 0, 0).wheels[0][0].lobes.size(), 2u);
  nlohmann::json without = nlohmann::json::parse(text);
  for (auto& n : without["nodes"]) n["wheels"][0][0]["lobes"] = nlohmann::json::array();
  const WheelsetTable whole = parse_wheelset_table(without.dump(), "whole.json");
  const WheelsetState state = moving_state(-5.3e-3);
  const double a = rigid.evaluate(state, WheelLoads{100e3, 100e3, false}, kMu).wheels[0].force_track_N[0];
  const double b = whole.evaluate(state, WheelLoads{100e3, 100e3, false}, kMu).wheels[0].force_track_N[0];
  EXPECT_EQ(back.evaluate(state, WheelLoads{100e3, 100e3, false}, kMu).wheels[0].force_track_N[0], a);
  EXPECT_GT(std::abs(a - b), 0.01 * kMu * 100e3) << a << " " << b;

  // The left wheel at +y is the mirrored right wheel at −y, lobes included (a state without
  // lateral velocity and yaw rate, so that it mirrors).
  const WheelsetTable mirrored =
      build_wheelset_table(track(), {{5.2e-3, 5.3e-3}, {0.0}, {100e3}}, coarse_table_options(100000));
  ASSERT_EQ(mirrored.node(1, 0, 0).wheels[1][0].lobes.size(), 2u);
  WheelsetState right = moving_state(-5.3e-3), left = moving_state(5.3e-3);
  right.velocity.lateral_velocity_m_per_s = left.velocity.lateral_velocity_m_per_s = 0.0;
  right.velocity.yaw_rate_rad_per_s = left.velocity.yaw_rate_rad_per_s = 0.0;
  const WheelsetResult r = t.evaluate(right, WheelLoads{100e3, 100e3, false}, kMu);
  const WheelsetResult l = mirrored.evaluate(left, WheelLoads{100e3, 100e3, false}, kMu);
  EXPECT_NEAR(l.wheels[1].force_track_N[0], r.wheels[0].force_track_N[0], 1e-6 * 100e3);
  EXPECT_NEAR(l.wheels[1].force_track_N[1], -r.wheels[0].force_track_N[1], 1e-6 * 100e3);
  EXPECT_NEAR(l.wheels[1].force_track_N[2], r.wheels[0].force_track_N[2], 1e-6 * 100e3);
  EXPECT_NEAR(l.wheels[1].patches.front().forces().M3_Nm, -r.wheels[0].patches.front().forces().M3_Nm, 1e-8 * 100e3);
}

// With yaw in the grid, a node in flange contact at yaw is the wheelset solved on the fly at that
// yaw (the flange contact's lead included), and between yaw nodes 2 mrad apart the table stays
// within 0.5 % of mu Fz (measured: 0.2 %; with one yaw node the error at y = −6.5 mm reaches 8 %,
// docs/WHEELSET_TABLE.md §3).
TEST(WheelsetTable, WithYawInTheGridFlangeContactAtYawIsTheWheelsetOnTheFly) {
  const WheelsetTable t = build_wheelset_table(track(), {{-6.5e-3, -6.4e-3}, {-4e-3, -2e-3, 0.0, 2e-3, 4e-3}, {100e3}},
                                               coarse_table_options(100000));
  // At a node: to the solvers' tolerances (the wheelset's normal tolerance 5e-6, the load balance's
  // 1e-6; the build's heights start from the node 0.1 mm before, a time step away, docs/WHEELSET.md
  // §8).
  for (const auto& [y, yaw, tolerance] : {std::tuple{-6.4e-3, 4e-3, 5e-6}, std::tuple{-6.5e-3, -2e-3, 5e-6},
                                          std::tuple{-6.4e-3, 3e-3, 5e-3}, std::tuple{-6.5e-3, -1e-3, 5e-3}}) {
    const WheelsetState state = moving_state(y, yaw);
    const WheelsetResult expected = on_the_fly(state, 100e3, 100e3);
    const WheelsetResult got = t.evaluate(state, WheelLoads{100e3, 100e3, false}, kMu);
    for (int w = 0; w < 2; ++w)
      for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(got.wheels[w].force_track_N[i], expected.wheels[w].force_track_N[i], tolerance * kMu * 100e3)
            << "y " << y << " yaw " << yaw << " wheel " << w << " component " << i;
  }
}

// Between nodes (y, load and yaw off the grid), the default recipe (coarse runtime patches)
// against the wheelset on the fly (0.5 mm elements, y in steps of 0.5 mm): within 1.5 % of mu Fz
// per component (docs/WHEELSET_TABLE.md §3 gives the errors of the 0.2 mm recipe).
TEST(WheelsetTable, BetweenNodesItStaysWithinOneAndAHalfPercentOfMuFzOfTheWheelsetOnTheFly) {
  for (double y : {-1.25e-3, -0.3e-3, 1.7e-3}) {
    for (double yaw : {0.0, 3e-3}) {
      const WheelsetState state = moving_state(y, yaw);
      const double right = 97e3, left = 104e3;
      const WheelsetResult expected = on_the_fly(state, right, left);
      const WheelsetResult got = table().evaluate(state, WheelLoads{right, left, false}, kMu);
      for (int w = 0; w < 2; ++w) {
        const double scale = kMu * (w == 0 ? right : left);
        for (int i = 0; i < 2; ++i)
          EXPECT_NEAR(got.wheels[w].force_track_N[i], expected.wheels[w].force_track_N[i], 0.015 * scale)
              << "y " << y << " yaw " << yaw << " wheel " << w << " component " << i;
        EXPECT_NEAR(got.wheels[w].force_track_N[2], expected.wheels[w].force_track_N[2], 2e-3 * scale);
      }
    }
  }
}

// With the tangential forces in the vertical balance (Wheelset's default, the command line's), each
// wheel is looked up at the table load that makes its normal and tangential forces carry its load:
// near the flange root (y = -5.9 mm, between nodes 0.2 mm apart; the tangential forces' vertical
// components are 2.6 kN there) Fz meets the load within 1e-6 and Fx, Fy are within 2 % of μFz of
// the wheelset on the fly with the same balance; with the frictionless balance Fz was 2.7 % of the
// load off.
TEST(WheelsetTable, TheTangentialForcesJoinTheVerticalBalanceAsOnTheFly) {
  const WheelsetTable t = build_wheelset_table(track(), {{-6.2e-3, -6.0e-3, -5.8e-3, -5.6e-3}, {0.0}, {80e3, 100e3, 120e3}},
                                               coarse_table_options());
  WheelsetOptions o = coarse_table_options().wheelset;
  o.friction_coefficient = kMu;
  Wheelset wheelset(track(), o);  // tangential forces in the balance (the default)
  const WheelsetState state = moving_state(-5.9e-3);
  const WheelsetResult expected = wheelset.evaluate(state);
  const WheelsetResult got = t.evaluate(state, WheelLoads{98.1e3, 98.1e3, false}, kMu, true);
  const WheelsetResult frictionless = t.evaluate(state, WheelLoads{98.1e3, 98.1e3, false}, kMu);
  for (int w = 0; w < 2; ++w) {
    const double scale = kMu * 98.1e3;
    EXPECT_NEAR(got.wheels[w].force_track_N[2], 98.1e3, 1e-6 * 98.1e3) << w;
    for (int i = 0; i < 2; ++i)
      EXPECT_NEAR(got.wheels[w].force_track_N[i], expected.wheels[w].force_track_N[i], 0.02 * scale) << w << " " << i;
  }
  EXPECT_GT(std::abs(frictionless.wheels[0].force_track_N[2] - 98.1e3), 0.01 * 98.1e3);
}

// The table's nodes are mirror images (the left wheel is solved as the mirrored right wheel), so
// lookups at (y, ψ, loads) and (−y, −ψ, loads swapped) are mirror images to rounding.
TEST(WheelsetTable, TheLeftWheelIsTheMirroredRightWheel) {
  WheelsetState a = moving_state(-1.37e-3, 2e-3);
  WheelsetState b = a;
  b.position.lateral_displacement_m = -a.position.lateral_displacement_m;
  b.position.yaw_rad = -a.position.yaw_rad;
  b.velocity.lateral_velocity_m_per_s = -a.velocity.lateral_velocity_m_per_s;
  b.velocity.yaw_rate_rad_per_s = -a.velocity.yaw_rate_rad_per_s;
  const WheelsetResult ra = table().evaluate(a, WheelLoads{95e3, 105e3, false}, kMu);
  const WheelsetResult rb = table().evaluate(b, WheelLoads{105e3, 95e3, false}, kMu);
  for (int w = 0; w < 2; ++w) {
    const Vector3& f = ra.wheels[w].force_track_N;
    const Vector3& g = rb.wheels[1 - w].force_track_N;
    EXPECT_NEAR(f[0], g[0], 1e-8 * f[2]);
    EXPECT_NEAR(f[1], -g[1], 1e-8 * f[2]);
    EXPECT_NEAR(f[2], g[2], 1e-8 * f[2]);
    EXPECT_NEAR(ra.wheels[w].patches[0].forces().M3_Nm, -rb.wheels[1 - w].patches[0].forces().M3_Nm, 1e-8 * f[2]);
  }
}

// A patch that one node has and its neighbour has not (a flange contact appearing between them)
// grows from zero force, and the wheel's forces change continuously. The second patch is made by
// hand: a copy of the tread patch 10 mm towards the gauge face, added to the node at y = −4.4 mm
// (both nodes' tread patches lie within 1 mm of each other on the rail: one patch).
TEST(WheelsetTable, APatchThatAppearsBetweenNodesGrowsFromZero) {
  const WheelsetTable built = build_wheelset_table(track(), {{-4.4e-3, -4.0e-3}, {0.0}, {100e3}}, coarse_table_options());
  std::vector<WheelsetTableNode> nodes = built.nodes();
  ASSERT_EQ(nodes[0].wheels[0].size(), 1u);
  ASSERT_EQ(nodes[1].wheels[0].size(), 1u);
  WheelsetTablePatch flange = nodes[0].wheels[0][0];
  flange.rail_profile_y_m -= 10e-3;
  flange.normal_force_N *= 0.5;
  nodes[0].wheels[0].insert(nodes[0].wheels[0].begin(), flange);
  const WheelsetTable t(built.grid(), nodes, built.nominal_rolling_radius_m(), built.material(), built.bound());
  Vector3 previous{};
  double largest_step = 0.0, flange_force_near_node = 0.0;
  for (int k = 0; k <= 40; ++k) {
    const double y = -4.0e-3 - k * 0.01e-3;
    const WheelsetResult r = t.evaluate(moving_state(y), WheelLoads{100e3, 100e3, false}, kMu);
    const WheelResult& right = r.wheels[0];
    ASSERT_EQ(right.patches.size(), k == 0 ? 1u : 2u) << "y " << y;
    if (k == 1) flange_force_near_node = right.patches.front().normal_force_N;  // gauge side first
    if (k > 0)
      for (int i = 0; i < 3; ++i) largest_step = std::max(largest_step, std::abs(right.force_track_N[i] - previous[i]));
    previous = right.force_track_N;
  }
  // One step of 0.01 mm out of 0.4 mm: 1/40 of the node's flange force.
  EXPECT_NEAR(flange_force_near_node, flange.normal_force_N / 40.0, 1e-9 * flange.normal_force_N);
  EXPECT_LT(largest_step, 0.05 * flange.normal_force_N);
}

TEST(WheelsetTable, LookupsOutsideTheTableOrWithBadInputAreRefused) {
  const auto message = [](const WheelsetState& state, const WheelLoads& loads, double mu) {
    try {
      (void)table().evaluate(state, loads, mu);
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::invalid_input);
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const WheelLoads loads{100e3, 100e3, false};
  EXPECT_NE(message(moving_state(2.5e-3), loads, kMu).find("y = 2.5 mm lies outside the table's range [-2, 2] mm"),
            std::string::npos);
  EXPECT_NE(message(moving_state(0.0), WheelLoads{100e3, 120e3, false}, kMu)
                .find("the left wheel's load = 120 kN lies outside the table's range [90, 110] kN"),
            std::string::npos);
  EXPECT_NE(message(moving_state(0.0), loads, 0.0).find("friction coefficient 0"), std::string::npos);
  EXPECT_NE(message(moving_state(std::nan("")), loads, kMu).find("lateral displacement"), std::string::npos);
  WheelsetState stopped = moving_state(0.0);
  stopped.velocity.forward_speed_m_per_s = 0.0;
  EXPECT_NE(message(stopped, loads, kMu), "no error");
  EXPECT_THROW((void)build_wheelset_table(track(), {{1e-3, 0.0}, {0.0}, {100e3}}, coarse_table_options()), Error);
  EXPECT_THROW((void)build_wheelset_table(track(), {{0.0}, {0.0}, {-1.0}}, coarse_table_options()), Error);
  EXPECT_THROW((void)build_wheelset_table(track(), {{0.0}, {0.0, 0.2}, {100e3}}, coarse_table_options()), Error);
}

// A table holds the settings of its build (material, element size, nH-FastSim's coarsening,
// collocation offset, slip direction, bound skew, recipe): mismatches names each that a wheelset's
// options would change, with both values; the options of the build give none.
TEST(WheelsetTable, MismatchesNameEverySettingItWasNotBuiltFor) {
  const WheelsetOptions built = coarse_table_options().wheelset;
  EXPECT_TRUE(table().mismatches(built).empty());
  WheelsetOptions other = built;
  other.element_size_m = 0.5 * 1e-3;  // the same value in other units: within 1e-9
  EXPECT_TRUE(table().mismatches(other).empty());
  other.material = Material{1e11, 0.25};
  other.element_size_m = 2e-3;
  other.nh_fastsim.flexibility_coarsening = 1;
  other.nh_fastsim.collocation_offset = 0.5;
  other.nh_fastsim.bound.slip_direction = SlipDirection::radial;
  other.nh_fastsim.bound.skew = 0.2;
  const std::vector<WheelsetTableMismatch> m = table().mismatches(other);
  ASSERT_EQ(m.size(), 6u);
  const auto is = [&](std::size_t k, WheelsetTableSetting setting, const std::string& requested, const std::string& table) {
    EXPECT_EQ(m[k].setting, setting);
    EXPECT_EQ(m[k].requested, requested);
    EXPECT_EQ(m[k].table, table);
  };
  is(0, WheelsetTableSetting::material, "E = 1e+11 Pa, nu = 0.25", "E = 2.1e+11 Pa, nu = 0.3");
  is(1, WheelsetTableSetting::element_size, "2 mm", "0.5 mm");
  is(2, WheelsetTableSetting::flexibility_coarsening, "1", "0 (automatic)");
  is(3, WheelsetTableSetting::collocation_offset, "0.5", "0");
  is(4, WheelsetTableSetting::slip_direction, "radial", "elastic-slip");
  EXPECT_EQ(m[5].setting, WheelsetTableSetting::traction_bound_skew);
  // A table of an older recipe (format 3: not recorded) differs from this railcontact's.
  nlohmann::json old = before_format_6(nlohmann::json::parse(wheelset_table_json(table())));
  old.erase("nh_fastsim_recipe");
  old.erase("reference_weighting");
  old.erase("creepage_point");
  old["format_version"] = 3;
  const std::vector<WheelsetTableMismatch> recipe = parse_wheelset_table(old.dump(), "t.json").mismatches(built);
  ASSERT_EQ(recipe.size(), 3u);
  EXPECT_EQ(recipe[0].setting, WheelsetTableSetting::nh_fastsim_recipe);
  EXPECT_EQ(recipe[0].table, "1 or 2, not recorded");
  // ... and its contact definition (format 4 and older: depth-weighted reference points, creepages
  // on the rail surface) from this railcontact's; so does a table built with the depth weighting.
  EXPECT_EQ(recipe[1].setting, WheelsetTableSetting::contact_definition);
  EXPECT_NE(recipe[1].table.find("depth reference point, creepages on the rail surface"), std::string::npos);
  // ... and its separate patches were not coupled (format 7 and older).
  EXPECT_EQ(recipe[2].setting, WheelsetTableSetting::patch_coupling);
  EXPECT_EQ(recipe[2].requested, "full up to 6 mm apart, none from 10 mm");
  EXPECT_EQ(recipe[2].table, "none");
  WheelsetOptions uncoupled = built;
  uncoupled.patch_coupling = {0.0, 0.0};
  const std::vector<WheelsetTableMismatch> coupling = table().mismatches(uncoupled);
  ASSERT_EQ(coupling.size(), 1u);
  EXPECT_EQ(coupling[0].setting, WheelsetTableSetting::patch_coupling);
  EXPECT_EQ(coupling[0].requested, "none");
  WheelsetOptions depth = built;
  depth.search.weighting = ReferenceWeighting::depth;
  const std::vector<WheelsetTableMismatch> weighting = table().mismatches(depth);
  ASSERT_EQ(weighting.size(), 1u);
  EXPECT_EQ(weighting[0].setting, WheelsetTableSetting::contact_definition);
  for (WheelsetTableSetting setting : kWheelsetTableSettings)
    EXPECT_EQ(parse_wheelset_table_setting(wheelset_table_setting_name(setting)), setting);
  EXPECT_THROW((void)parse_wheelset_table_setting("speed"), Error);
}

// The nodes have zero roll: a rolled state is refused (the table would give the creepages of the
// roll on the contact points of zero roll: docs/WHEELSET_TABLE.md §5).
TEST(WheelsetTable, ARolledStateIsRefused) {
  WheelsetState rolled = moving_state(0.0);
  rolled.position.roll_rad = 10e-3;
  try {
    (void)table().evaluate(rolled, WheelLoads{100e3, 100e3, false}, kMu);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::invalid_input);
    EXPECT_NE(std::string(e.what()).find("the roll 10 mrad must be zero"), std::string::npos) << e.what();
  }
}

// A node whose wheelset cannot be solved (here: the flange climbing over the rail) is a gap that
// lookups next to it name.
TEST(WheelsetTable, AGapIsNamedByTheLookupsThatNeedIt) {
  const WheelsetTable t = build_wheelset_table(track(), {{-12e-3, -4e-3}, {0.0}, {100e3}}, coarse_table_options());
  ASSERT_EQ(t.node(0, 0, 0).status, WheelsetTableNodeStatus::failed);
  ASSERT_EQ(t.node(1, 0, 0).status, WheelsetTableNodeStatus::solved);
  EXPECT_NO_THROW((void)t.evaluate(moving_state(-4e-3), WheelLoads{100e3, 100e3, false}, kMu));
  try {
    (void)t.evaluate(moving_state(-5e-3), WheelLoads{100e3, 100e3, false}, kMu);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("the node at y = -12 mm, yaw 0 mrad, load 100 kN is a gap"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace railcontact

namespace railcontact {
namespace {

// A table saved and loaded gives the same forces to the last digit (doubles are written with 17
// significant digits), and keeps where it came from.
TEST(WheelsetTableFile, ARoundTripGivesTheSameForcesToTheLastDigit) {
  const WheelsetTable back = parse_wheelset_table(wheelset_table_json(table()), "round-trip.json");
  EXPECT_EQ(back.metadata().railcontact_version, table().metadata().railcontact_version);
  EXPECT_EQ(back.metadata().right_wheel_profile.fnv1a64, table().metadata().right_wheel_profile.fnv1a64);
  EXPECT_NE(back.metadata().right_wheel_profile.fnv1a64, 0u);
  EXPECT_NO_THROW(back.check_track(track()));
  const WheelsetState state = moving_state(-0.77e-3, 1e-3);
  const WheelsetResult a = table().evaluate(state, WheelLoads{93e3, 101e3, false}, kMu);
  const WheelsetResult b = back.evaluate(state, WheelLoads{93e3, 101e3, false}, kMu);
  for (int w = 0; w < 2; ++w)
    for (int i = 0; i < 3; ++i) EXPECT_EQ(a.wheels[w].force_track_N[i], b.wheels[w].force_track_N[i]);
}

// The table records the track's rail cant: a table on the rail as given (cant 0) has no key
// (files of builds before the key read as cant 0), refuses a canted track, and one whose file
// records a cant refuses the uncanted track, naming the cant.
TEST(WheelsetTableFile, TheRailCantIsRecordedAndChecked) {
  nlohmann::json j = nlohmann::json::parse(wheelset_table_json(table()));
  EXPECT_FALSE(j["track"].contains("rail_cant_rad"));
  TrackWheelsetParameters canted = track().parameters();
  canted.rail_cant_rad = 0.01;
  const WheelsetTrack canted_track(read_profile(default_wheel_profile_path()), read_profile(default_rail_profile_path()),
                                   canted);
  try {
    table().check_track(canted_track);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("rail cant 0 rad): this track's rail cant is 0.01 rad; rebuild the table"),
              std::string::npos)
        << e.what();
  }
  j["track"]["rail_cant_rad"] = 0.01;
  const WheelsetTable recorded = parse_wheelset_table(j.dump(), "canted.json");
  EXPECT_EQ(recorded.metadata().track.rail_cant_rad, 0.01);
  EXPECT_NO_THROW(recorded.check_track(canted_track));
  EXPECT_THROW(recorded.check_track(track()), Error);
  EXPECT_EQ(nlohmann::json::parse(wheelset_table_json(recorded))["track"]["rail_cant_rad"], 0.01);
}

TEST(WheelsetTableFile, MalformedFilesAreRefusedNamingTheKey) {
  const auto message = [](const std::string& text) {
    try {
      (void)parse_wheelset_table(text, "t.json");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("{"), "wheelset table t.json:1: malformed JSON (is it a wheelset table?)");
  EXPECT_NE(message(R"({"format": "railcontact flexibility table"})").find("not a wheelset table"), std::string::npos);
  std::string text = wheelset_table_json(table());
  const std::string key = "\"normal_force_N\":";
  text.replace(text.find(key), key.size(), key + "-");
  EXPECT_NE(message(text).find("nodes[0] wheel 0 patch 0: the normal force must lie in [0, 1e7] N"), std::string::npos)
      << message(text);
  // Implausible runtime patches (a fuzzer's: elements of 3e99 m, a pressure of 1e306 Pa overflowed
  // FastSim's forces to NaN).
  nlohmann::json huge = nlohmann::json::parse(wheelset_table_json(table()));
  huge["nodes"][1]["wheels"][0][0]["runtime_mesh"]["dx2_m"] = 3.3e99;
  EXPECT_NE(message(huge.dump()).find("nodes[1] wheel 0 patch 0: the runtime mesh's elements must be at most 0.05 m long"),
            std::string::npos)
      << message(huge.dump());
  huge = nlohmann::json::parse(wheelset_table_json(table()));
  huge["nodes"][1]["wheels"][1][0]["runtime_pressure_Pa"][3] = 1e306;
  EXPECT_NE(message(huge.dump()).find("the runtime pressures must lie in [0, 1e11] Pa"), std::string::npos)
      << message(huge.dump());
  // A creepage coupling beyond what a patch gives (ratios below 0.01, lengths below 1 mm measured) or
  // of the wrong length is refused, not marched.
  huge = nlohmann::json::parse(wheelset_table_json(table()));
  huge["nodes"][1]["wheels"][0][0]["creepage_coupling"][0] = 50.0;
  EXPECT_NE(message(huge.dump()).find("nodes[1] wheel 0 patch 0: the creepage coupling's ratios must lie within ±1"),
            std::string::npos)
      << message(huge.dump());
  huge["nodes"][1]["wheels"][0][0]["creepage_coupling"] = {0.0, 0.0};
  EXPECT_NE(message(huge.dump()).find("creepage_coupling must be a list of 4 numbers"), std::string::npos)
      << message(huge.dump());
  std::string unknown = wheelset_table_json(table());
  unknown.replace(unknown.find("\"area_m2\""), 9, "\"area_mm2\"");
  EXPECT_NE(message(unknown).find("missing key 'nodes[0].wheels[0][0].area_m2'"), std::string::npos) << message(unknown);
  // Format 3 names the slip direction; format 1-2 files evaluate with the radial one (Eq 8).
  // Format 4 records the nH-FastSim recipe; older files load with recipe 0 (not recorded).
  nlohmann::json slip = nlohmann::json::parse(wheelset_table_json(table()));
  EXPECT_EQ(slip["format_version"], 8);
  EXPECT_EQ(slip["contact_surface"], "planar");
  EXPECT_EQ(slip["patch_coupling"], nlohmann::json::array({0.006, 0.01}));
  nlohmann::json coupling = slip;
  coupling["patch_coupling"] = {0.006};
  EXPECT_NE(message(coupling.dump()).find("patch_coupling must be a list of 2 numbers"), std::string::npos)
      << message(coupling.dump());
  coupling["patch_coupling"] = {0.01, 0.006};
  EXPECT_NE(message(coupling.dump()).find("patch_coupling: wheelset: the patch coupling's distances 10 mm (full) and 6 mm"),
            std::string::npos)
      << message(coupling.dump());
  EXPECT_TRUE(slip["nodes"][0]["wheels"][0][0]["conformal"].is_null());
  nlohmann::json band = slip;
  band["contact_surface_switch"] = {0.03, 0.02};
  EXPECT_NE(message(band.dump()).find("contact_surface_switch: "), std::string::npos) << message(band.dump());
  band = slip;
  band["contact_surface"] = "curved";
  EXPECT_NE(message(band.dump()).find("contact_surface: unknown contact surface 'curved'"), std::string::npos)
      << message(band.dump());
  EXPECT_EQ(slip["reference_weighting"], "squared-gap");
  EXPECT_EQ(slip["creepage_point"], "undeformed wheel surface");
  EXPECT_EQ(slip["nh_fastsim_recipe"], kNhFastSimRecipe);
  EXPECT_EQ(parse_wheelset_table(slip.dump(), "t.json").metadata().nh_fastsim_recipe, kNhFastSimRecipe);
  nlohmann::json newer = slip;
  newer["nh_fastsim_recipe"] = kNhFastSimRecipe + 1;
  EXPECT_NE(message(newer.dump()).find("nh_fastsim_recipe = 5 must lie in [0, 4]"), std::string::npos)
      << message(newer.dump());
  slip = before_format_6(slip);
  slip.erase("nh_fastsim_recipe");
  slip.erase("reference_weighting");
  slip.erase("creepage_point");
  slip["format_version"] = 3;
  EXPECT_EQ(parse_wheelset_table(slip.dump(), "t.json").metadata().nh_fastsim_recipe, 0);
  EXPECT_EQ(slip["slip_direction"], slip_direction_name(table().bound().slip_direction));
  slip["slip_direction"] = "sideways";
  EXPECT_NE(message(slip.dump()).find("slip_direction: unknown slip direction 'sideways' (radial, flexibility-weighted, rigid-slip, elastic-slip)"),
            std::string::npos)
      << message(slip.dump());
  slip.erase("slip_direction");
  EXPECT_NE(message(slip.dump()).find("slip_direction"), std::string::npos) << message(slip.dump());
  slip["format_version"] = 2;
  EXPECT_EQ(parse_wheelset_table(slip.dump(), "t.json").bound().slip_direction, SlipDirection::radial);
}

}  // namespace
}  // namespace railcontact


namespace railcontact {
namespace {

using test::CommandResult;
using test::run_cli;
using test::scratch_directory;

// `railcontact wheelset-table build` writes the table the library builds, and `railcontact
// wheelset --table FILE --json` gives the library's lookup to the last digit.
// A table evaluates with the slip direction it was built with: format 3 names it, format 1-2 files
// use Eq 8's radial one; the JSON says which, and an explicit --slip-direction must agree.
TEST(WheelsetTableCli, EvaluatesWithTheTablesSlipDirection) {
  const std::string v3 = std::string(RAILCONTACT_SOURCE_DIR) + "/tests/data/wheelset_table_v3_weighted.json";
  nlohmann::json old_format = nlohmann::json::parse(std::ifstream(v3));
  old_format["format_version"] = 2;
  old_format.erase("slip_direction");
  const test::ScratchDirectory dir("wheelset_table_slip");
  const std::string v2 = (dir / "v2.json").string();
  std::ofstream(v2) << old_format.dump();
  const auto evaluate = [](const std::string& file, const std::string& extra) {
    const CommandResult r = run_cli("wheelset --table " + file +
                                    " --y-m -0.0053 --load-N 100000 --frictionless-balance --json --table-override recipe contact-definition patch-coupling" + extra);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return nlohmann::json::parse(r.out);
  };
  const nlohmann::json weighted = evaluate(v3, ""), radial = evaluate(v2, "");
  // A table of an older nH-FastSim recipe (format 3: not recorded) is refused unless the override
  // names it; then it is used with a note, and the JSON records the override.
  const CommandResult refused = run_cli("wheelset --table " + v3 + " --y-m -0.0053 --load-N 100000 --frictionless-balance --json");
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("recipe 4 (this railcontact's) differs from the table's 1 or 2, not recorded"),
            std::string::npos)
      << refused.err;
  EXPECT_EQ(weighted["wheelset_table_overrides"][0]["setting"], "recipe");
  const CommandResult noted = run_cli("wheelset --table " + v3 +
                                      " --y-m -0.0053 --load-N 100000 --frictionless-balance --json --table-override recipe contact-definition patch-coupling");
  EXPECT_NE(noted.err.find("note: " + v3 + ": the table was built with an older nH-FastSim recipe"), std::string::npos)
      << noted.err;
  EXPECT_EQ(weighted["nh_fastsim_slip_direction"], "flexibility-weighted");
  EXPECT_EQ(radial["nh_fastsim_slip_direction"], "radial");
  EXPECT_EQ(evaluate(v3, " --slip-direction flexibility-weighted")["wheels"], weighted["wheels"]);
  EXPECT_NE(weighted["wheels"][0]["force_track_N"], radial["wheels"][0]["force_track_N"]);
  EXPECT_EQ(run_cli("wheelset --table " + v3 + " --y-m -0.0053 --load-N 100000 --frictionless-balance --slip-direction radial").exit_code, 2);
}

// A small table built by the command (0.5 mm elements, y = -0.5, 0, 0.5 mm, 90 and 110 kN).
std::string built_table(const std::filesystem::path& dir) {
  const std::string file = (dir / "table.json").string();
  const CommandResult build =
      run_cli("wheelset-table build --y-m=-0.0005:0.0005:0.0005 --load-N 90000,110000 --element-size-m 0.0005 --out " + file);
  EXPECT_EQ(build.exit_code, 0) << build.err;
  return file;
}

// What the run asks for (a case file, options given) must be what the table was built with: the
// material of a case, an element size or coarsening given, a roll are refused with one message
// naming the setting, both values and the override; --table-override evaluates with the table's
// values and the JSON records them. Without a case, options not given take the table's values.
TEST(WheelsetTableCli, SettingsTheTableWasNotBuiltForAreRefusedUnlessOverridden) {
  const test::ScratchDirectory dir("wheelset_table_settings");
  const std::string file = built_table(dir.path());
  const std::string at = " --y-m 0.0002 --load-N 100000 --json";
  const CommandResult plain = run_cli("wheelset --table " + file + at);
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  const nlohmann::json j = nlohmann::json::parse(plain.out);
  EXPECT_EQ(j["element_size_m"], 0.5e-3);  // the table's, not the command's default 0.2 mm
  EXPECT_EQ(j["wheelset_table_overrides"], nlohmann::json::array());

  const std::string steel_case = (dir / "other_material.toml").string();
  std::ofstream(steel_case) << "[material]\nE_Pa = 1e11\nnu = 0.25\n[mesh]\nelement_size_mm = 0.5\n";
  const CommandResult material = run_cli("wheelset " + steel_case + " --table " + file + at);
  EXPECT_EQ(material.exit_code, 2);
  EXPECT_EQ(material.out, "");
  EXPECT_NE(material.err.find("railcontact: error: --table " + file +
                              ": material E = 1e+11 Pa, nu = 0.25 (the case's [material]) differs from the table's "
                              "E = 2.1e+11 Pa, nu = 0.3: rebuild the table for the run, or give --table-override "
                              "material to evaluate with the table's"),
            std::string::npos)
      << material.err;

  const CommandResult mesh = run_cli("wheelset --table " + file + at + " --element-size-m 0.002 --flexibility-coarsening 1");
  EXPECT_EQ(mesh.exit_code, 2);
  EXPECT_NE(mesh.err.find("element-size 2 mm (--element-size-m) differs from the table's 0.5 mm; flexibility-coarsening 1 "
                          "(--flexibility-coarsening) differs from the table's 0 (automatic)"),
            std::string::npos)
      << mesh.err;
  EXPECT_NE(mesh.err.find("--table-override element-size,flexibility-coarsening"), std::string::npos) << mesh.err;
  const CommandResult overridden = run_cli("wheelset --table " + file + at +
                                           " --element-size-m 0.002 --flexibility-coarsening 1 --table-override "
                                           "element-size,flexibility-coarsening");
  ASSERT_EQ(overridden.exit_code, 0) << overridden.err;
  const nlohmann::json o = nlohmann::json::parse(overridden.out);
  EXPECT_EQ(o["element_size_m"], 0.5e-3);
  EXPECT_EQ(o["flexibility_coarsening"], 0);
  EXPECT_EQ(o["wheels"], j["wheels"]);  // the same lookup (same code, same inputs)
  ASSERT_EQ(o["wheelset_table_overrides"].size(), 2u);
  EXPECT_EQ(o["wheelset_table_overrides"][0],
            (nlohmann::json{{"setting", "element-size"}, {"requested", "2 mm"}, {"used", "0.5 mm"}}));
  EXPECT_EQ(o["wheelset_table_overrides"][1]["setting"], "flexibility-coarsening");

  const CommandResult rolled = run_cli("wheelset --table " + file + at + " --roll-rad 0.01");
  EXPECT_EQ(rolled.exit_code, 2);
  EXPECT_NE(rolled.err.find("--roll-rad 0.01 rad cannot be evaluated from --table"), std::string::npos) << rolled.err;
  EXPECT_EQ(run_cli("wheelset --table " + file + at + " --table-override speed").exit_code, 2);
}

// --sweep-y-m with --table evaluates every position from the table: the CSV's forces are the
// table's point evaluations (to the CSV's 3 decimals); past the table's y range the sweep stops
// with the rows before it written.
TEST(WheelsetTableCli, SweepFromTheTableGivesItsPointEvaluations) {
  const test::ScratchDirectory dir("wheelset_table_sweep");
  const std::string file = built_table(dir.path());
  const std::string no_figures = "RAILCONTACT_SCRIPTS=/nonexistent-railcontact-scripts ";
  const CommandResult sweep = run_cli("wheelset --table " + file + " --sweep-y-m 0.0005:-0.0005:0.00025 --load-N 100000 --speed-m-per-s 30 "
                                      "--lateral-velocity-m-per-s 0.02 --out " + (dir / "a").string(), no_figures);
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  EXPECT_NE(sweep.out.find("Wrote 5 evaluations"), std::string::npos) << sweep.out;
  const WheelsetTable table = load_wheelset_table(file);
  std::ifstream csv(dir / "a" / "wheelset_sweep.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_NE(line.find("nh-fastsim_F1_N"), std::string::npos) << line;
  int rows = 0;
  while (std::getline(csv, line)) {
    std::vector<double> values;
    std::istringstream in(line);
    for (std::string cell; std::getline(in, cell, ',');) values.push_back(std::atof(cell.c_str()));
    WheelsetState state;
    state.position.lateral_displacement_m = values.front() * 1e-3;
    state.velocity.forward_speed_m_per_s = 30.0;
    state.velocity.lateral_velocity_m_per_s = 0.02;
    const WheelsetResult r = table.evaluate(state, WheelLoads{100e3, 100e3, false}, 0.3, true);  // as the command line balances
    const int side = line.find(",right,") != std::string::npos ? 0 : 1;
    for (int i = 0; i < 3; ++i)  // the last three columns: the wheel's force, printed to 1e-3 N
      EXPECT_NEAR(values[values.size() - 3 + i], r.wheels[side].force_track_N[i], 1e-3) << line;
    ++rows;
  }
  EXPECT_EQ(rows, 10);  // 5 positions, one tread patch on each wheel
  const CommandResult past = run_cli("wheelset --table " + file + " --sweep-y-m 0:0.001:0.0005 --load-N 100000 --out " +
                                     (dir / "b").string(), no_figures);
  EXPECT_EQ(past.exit_code, 2);
  EXPECT_NE(past.err.find("the sweep stopped at y = 1 mm after 2 evaluations (written): wheelset table: the lateral "
                          "displacement y = 1 mm lies outside the table's range [-0.5, 0.5] mm"),
            std::string::npos)
      << past.err;
}

// A table built with the depth-weighted reference point records it; a run evaluates it with that
// weighting only (the default, CONTACT's squared gap, is another contact definition).
TEST(WheelsetTableCli, ATableRecordsItsReferenceWeighting) {
  const test::ScratchDirectory dir("wheelset_table_weighting");
  const std::string file = (dir / "depth.json").string();
  const CommandResult build = run_cli("wheelset-table build --y-m=0:0:0.001 --load-N 98100 --element-size-m 0.0005 "
                                      "--reference-weighting depth --out " + file);
  ASSERT_EQ(build.exit_code, 0) << build.err;
  EXPECT_EQ(load_wheelset_table(file).metadata().reference_weighting, ReferenceWeighting::depth);
  const std::string state = " --y-m 0 --load-N 98100 --element-size-m 0.0005 --frictionless-balance --json";
  const CommandResult same = run_cli("wheelset --table " + file + state + " --reference-weighting depth");
  EXPECT_EQ(same.exit_code, 0) << same.err;
  const CommandResult other = run_cli("wheelset --table " + file + state);
  EXPECT_EQ(other.exit_code, 2);
  EXPECT_NE(other.err.find("contact-definition squared-gap reference point, creepages on the undeformed wheel surface "
                           "over V_ref (this railcontact's) differs from the table's depth reference point"),
            std::string::npos)
      << other.err;
}

TEST(WheelsetTableCli, BuildThenEvaluateGivesTheLibrarysLookup) {
  const test::ScratchDirectory dir("wheelset_table_cli");
  const std::string file = (dir / "table.json").string();
  const CommandResult build =
      run_cli("wheelset-table build --y-m=-0.0005:0.0005:0.0005 --load-N 90000,110000 --element-size-m 0.0005 --out " + file);
  ASSERT_EQ(build.exit_code, 0) << build.err;
  EXPECT_NE(build.out.find("nodes     6 (0 gaps)"), std::string::npos) << build.out;
  EXPECT_NE(build.err.find("[100 %] 6/6 nodes"), std::string::npos) << build.err;
  const WheelsetTable table = load_wheelset_table(file);
  const CommandResult run = run_cli("wheelset --table " + file + " --y-m 0.0002 --yaw-rad 0.0015 --load-N 97000 --speed-m-per-s 30 --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  WheelsetState state;
  state.position.lateral_displacement_m = 0.2e-3;
  state.position.yaw_rad = 1.5e-3;
  state.velocity.forward_speed_m_per_s = 30.0;
  const WheelsetResult r = table.evaluate(state, WheelLoads{97e3, 97e3, false}, 0.3, true);  // as the command line balances
  EXPECT_EQ(j["wheelset_table"], file);
  for (int w = 0; w < 2; ++w)
    for (int i = 0; i < 3; ++i) EXPECT_EQ(j["wheels"][w]["force_track_N"][i].get<double>(), r.wheels[w].force_track_N[i]);
}

// `wheelset-table build --contact-surface auto` records the surface; a lookup that asks for it
// gives the automatic wheelset's patches (the flange's conformal weight 1 in the JSON), one that
// asks for the planar surface is refused naming the setting, and an unknown name is refused.
TEST(WheelsetTableCli, ATableOnTheAutomaticSurface) {
  const test::ScratchDirectory dir("wheelset_table_cli_auto");
  const std::string file = (dir / "table.json").string();
  const CommandResult build = run_cli("wheelset-table build --y-m=-0.0066:-0.0064:0.0002 --load-N 90000,110000 "
                                      "--element-size-m 0.0005 --contact-surface auto --out " + file);
  ASSERT_EQ(build.exit_code, 0) << build.err;
  EXPECT_NE(build.err.find("auto surface"), std::string::npos) << build.err;
  EXPECT_EQ(load_wheelset_table(file).metadata().contact_surface, ContactSurface::automatic);
  const std::string at = " --y-m -0.0065 --load-N 100000 --element-size-m 0.0005 --json";
  const CommandResult run = run_cli("wheelset --table " + file + at + " --contact-surface auto");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  EXPECT_EQ(j["wheels"][0]["patches"][0]["conformal_weight"].get<double>(), 1.0);
  EXPECT_EQ(j["wheels"][0]["patches"][0]["contact_surface"], "conformal");
  const CommandResult planar = run_cli("wheelset --table " + file + at + " --contact-surface planar");
  EXPECT_EQ(planar.exit_code, 2);
  EXPECT_NE(planar.err.find("contact-surface planar (--contact-surface) differs from the table's auto"), std::string::npos)
      << planar.err;
  EXPECT_EQ(run_cli("wheelset-table build --contact-surface curved --out " + file).exit_code, 2);
}

// The measured worn wheel Car7358 on UIC60 snaps into flange contact between y = −6.95 and −7.0 mm
// (its lateral force jumps by several tens of kN within 0.05 mm). With nodes every 0.05 mm a lookup
// midway misses the wheelset on the fly by more than 4 % of μFz; with the refinement (nodes where the
// lateral normal force leaves the line between its neighbours by more than 1 % of the load, halved
// up to three times) by less than 2 %, with nodes added only around the snap-in. The refinement's
// settings are checked.
TEST(WheelsetTable, TheRefinementAddsNodesWhereTheFlangeSnapsIn) {
  const WheelRailSetup setup =
      read_wheel_rail_setup(std::string(RAILCONTACT_SOURCE_DIR) + "/data/wheel_rail/car7358_uic60.json");
  const WheelsetTrack track(read_profile(setup.wheel_profile, ProfileReadOptions{.role = ProfileKind::wheel}),
                            read_profile(setup.rail_profile, ProfileReadOptions{.role = ProfileKind::rail}), setup.track);
  const double load = 98.1e3;
  WheelsetTableGrid grid{{}, {0.0}, {load}};
  for (int k = 0; k <= 6; ++k) grid.y_m.push_back(-7.1e-3 + k * 0.05e-3);
  WheelsetTableOptions o;
  o.wheelset.tangential_forces_in_vertical_balance = false;
  const WheelsetTable plain = build_wheelset_table(track, grid, o);
  o.refinement.lateral_force_fraction = 0.01;
  const WheelsetTable refined = build_wheelset_table(track, grid, o);
  EXPECT_GT(refined.grid().y_m.size(), grid.y_m.size());
  EXPECT_LT(refined.grid().y_m.size(), grid.y_m.size() + 16);
  WheelsetOptions fly = o.wheelset;
  fly.loads = WheelLoads{load, load, false};
  const double y = -6.975e-3;
  WheelsetState state;
  state.position.lateral_displacement_m = y;
  const WheelsetResult expected = Wheelset(track, fly).evaluate(state);
  const auto miss = [&](const WheelsetTable& table) {
    const WheelsetResult got = table.evaluate(state, WheelLoads{load, load, false}, kMu);
    double largest = 0.0;
    for (int w = 0; w < 2; ++w)
      for (int i = 0; i < 3; ++i)
        largest = std::max(largest, std::abs(got.wheels[w].force_track_N[i] - expected.wheels[w].force_track_N[i]));
    return largest / (kMu * load);
  };
  EXPECT_GT(miss(plain), 0.04);
  EXPECT_LT(miss(refined), 0.02);
  o.refinement.lateral_force_fraction = 2.0;
  EXPECT_THROW((void)build_wheelset_table(track, grid, o), Error);
  o.refinement = {0.01, 0.0, 3};
  EXPECT_THROW((void)build_wheelset_table(track, grid, o), Error);
}

// Near flange climb with yaw the tangential forces pull the wheel down by a fifth of its load: the
// balance needs a table load beyond a narrow load grid and is refused with the loads named (it
// stopped at the grid's edge, 9 % of the load short, without a word); a wide grid meets the load.
TEST(WheelsetTable, ABalanceThatNeedsALoadOutsideTheGridIsRefused) {
  const WheelsetState state = moving_state(-6.6e-3, 0.01);
  const WheelsetTable narrow =
      build_wheelset_table(track(), {{-6.6e-3, -6.5e-3}, {0.0, 0.01}, {88.29e3, 107.91e3}}, coarse_table_options());
  const WheelsetResult frictionless = narrow.evaluate(state, WheelLoads{98.1e3, 98.1e3, false}, kMu);
  ASSERT_LT(frictionless.wheels[0].force_track_N[2], 0.85 * 98.1e3);  // the state is what the test is about
  try {
    (void)narrow.evaluate(state, WheelLoads{98.1e3, 98.1e3, false}, kMu, true);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::invalid_input);
    const std::string message = e.what();
    EXPECT_NE(message.find("the right wheel's load 98.1 kN, with its tangential forces in the vertical balance, needs "
                           "a table load of about "),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("kN (extrapolated), beyond the table's loads [88.29, 107.91] kN"), std::string::npos)
        << message;
    // The tangential forces pull the wheel down: the load it needs lies above the grid (the
    // extrapolation from the grid's last cell; the wide grid below meets the load).
    const auto at = message.find("of about ") + 9;
    const double needed_kN = std::stod(message.substr(at));
    EXPECT_GT(needed_kN, 107.91) << message;
    EXPECT_LT(needed_kN, 140.0) << message;
  }
  const WheelsetTable wide =
      build_wheelset_table(track(), {{-6.6e-3, -6.5e-3}, {0.0, 0.01}, {80e3, 140e3}}, coarse_table_options());
  const WheelsetResult met = wide.evaluate(state, WheelLoads{98.1e3, 98.1e3, false}, kMu, true);
  for (int w = 0; w < 2; ++w) EXPECT_NEAR(met.wheels[w].force_track_N[2], 98.1e3, 1e-6 * 98.1e3) << w;
}

}  // namespace
}  // namespace railcontact
