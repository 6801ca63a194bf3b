// The wheelset's exact solution against three published states of Kalker's CONTACT with its
// wheelset module (the field's reference program; issue #29 of the project): S1002 on UIC60 1:40,
// the left wheel, pure rolling at r0 = 460 mm, 20 m/s, 98.1 kN per wheel, μ = 0.3, 0.2 mm
// elements, exact solvers on both sides.
//
// CONTACT's frame and signs, mapped into railcontact's (docs/WHEEL_RAIL.md §12):
// - its track frame has y to the RIGHT and z down; its wheelset displacement y_ws puts the wheel's
//   centre at −y_ws in ours (y to the left), and its contact point y_cp is our −y;
// - its yaw turns x towards its +y (to the right): our yaw is minus its yaw;
// - its creepages are rail − wheel over V_ref: our ξ = −CKSI; its spin and ours are the same
//   physical quantity ω·n / V_ref with its n into the rail and our X3 into the wheel, both the
//   wheel's ω: our φ = CPHI;
// - its forces act on the rail: on the wheel F1 = −FX; its s runs across the rail towards its +y,
//   i.e. −X2, so on the wheel F2 = FS; F3 = FN.
// Targets (the issue's): F3 within 1 %, F1 and F2 within 1 % of μ F3, ξ within 2 % or 2e-5, φ within
// 2 %, the reference point within 0.3 mm, the contact angle within 2 mrad.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_run.hpp"
#include "railcontact/error.hpp"
#include "railcontact/wheelset.hpp"

namespace railcontact {
namespace {

struct ReferenceState {
  const char* name;
  double y_ws_m, yaw_rad;  // CONTACT's
  double y_cp_m, delta_rad, cksi, cphi_per_m, fn_N, fx_N, fs_N;
};

// The three public check states (CONTACT's frame and signs).
constexpr ReferenceState kStates[] = {
    {"centred", 0.0, 0.0, -750.385e-3, 0.0351005, -2.243e-5, -0.0762907, 98062.0, 65.2, 2801.5},
    {"y_ws = -3 mm", -3e-3, 0.0, -740.328e-3, 0.0904833, 1.60868e-3, -0.196277, 97909.0, -16854.0, 6546.7},
    {"y_ws = -3 mm, yaw +10 mrad", -3e-3, 10e-3, -740.400e-3, 0.0898916, 1.53811e-3, -0.194994, 101192.0, -4985.0,
     -29891.0},
};

const WheelsetTrack& track() {
  static const WheelsetTrack t = default_wheelset_track();
  return t;
}

TEST(WheelsetReferenceStates, ExactSolverMeetsKalkersContactInThreePublishedStates) {
  WheelsetOptions options;
  options.element_size_m = 0.2e-3;
  options.friction_coefficient = 0.3;
  options.solvers = {TangentialSolver::exact};
  options.loads = WheelLoads{98.1e3, 98.1e3};
  Wheelset wheelset(track(), options);
  for (const ReferenceState& ref : kStates) {
    SCOPED_TRACE(ref.name);
    WheelsetState state;
    state.position.lateral_displacement_m = -ref.y_ws_m;
    state.position.yaw_rad = -ref.yaw_rad;
    state.velocity.forward_speed_m_per_s = 20.0;  // pure rolling at r0 (the NaN default)
    const WheelsetResult result = wheelset.evaluate(state);
    const WheelResult& left = result.wheels[1];
    ASSERT_EQ(left.patches.size(), 1u);
    const WheelsetPatch& p = left.patches.front();
    const TangentialForces& f = p.forces();
    const double mu_fn = 0.3 * ref.fn_N;
    EXPECT_NEAR(p.region.reference_point_track_m[1], -ref.y_cp_m, 0.3e-3);
    EXPECT_NEAR(p.region.contact_angle_rad, ref.delta_rad, 2e-3);
    EXPECT_NEAR(p.creepage.xi, -ref.cksi, std::max(2e-5, 0.02 * std::abs(ref.cksi)));
    EXPECT_NEAR(p.creepage.phi, ref.cphi_per_m, 0.02 * std::abs(ref.cphi_per_m));
    EXPECT_NEAR(p.normal_force_N, ref.fn_N, 0.01 * ref.fn_N);
    EXPECT_NEAR(f.F1_N, -ref.fx_N, 0.01 * mu_fn);
    EXPECT_NEAR(f.F2_N, ref.fs_N, 0.01 * mu_fn);
  }
}

// The conformal surface against CONTACT's conformal mode (its curved reference surface, a frame
// per lateral grid column, the rigid slip per element) in two flange-root and flange states of
// issue #31: the left wheel at its y_ws = −5.0 and −6.5 mm (ours +5.0 and +6.5 mm), the same case
// as above. CONTACT's FY(TR), on the rail in its frame (y to the right), is the lateral force on
// the wheel in ours: −11776 N and −48633 N (its planar mode: −9126 N and −53192 N). Target: 1 % of
// μ Fz; measured −11712 N and −48903 N (0.22 % and 0.92 %).
TEST(WheelsetReferenceStates, ConformalSurfaceMeetsKalkersContactsConformalMode) {
  WheelsetOptions options;
  options.element_size_m = 0.2e-3;
  options.friction_coefficient = 0.3;
  options.solvers = {TangentialSolver::exact};
  options.loads = WheelLoads{98.1e3, 98.1e3};
  options.contact_surface = ContactSurface::conformal;
  Wheelset wheelset(track(), options);
  const struct {
    double y_ws_m, fy_tr_N;
  } states[] = {{-5.0e-3, -11776.0}, {-6.5e-3, -48633.0}};
  for (const auto& ref : states) {
    SCOPED_TRACE(ref.y_ws_m);
    WheelsetState state;
    state.position.lateral_displacement_m = -ref.y_ws_m;
    state.velocity.forward_speed_m_per_s = 20.0;
    const WheelsetResult result = wheelset.evaluate(state);
    EXPECT_NEAR(result.wheels[1].force_track_N[1], ref.fy_tr_N, 0.01 * 0.3 * 98.1e3);
  }
}

}  // namespace
}  // namespace railcontact

namespace railcontact {
namespace {

WheelsetOptions exact_at(double element_size_m) {
  WheelsetOptions o;
  o.element_size_m = element_size_m;
  o.solvers = {TangentialSolver::exact};
  return o;
}

// Free rolling: the wheels turn at the angular velocity where the moment of both wheels' tangential
// forces about the axle vanishes. Centred, the two wheels are mirror images, so each wheel's F1
// vanishes with the moment (target: below 0.1 % of μ F_z); pure rolling at r0 brakes the wheelset
// instead (the contact's radius is not r0), by about 65 N per wheel in CONTACT (above). Off centre
// the wheels' F1 form a couple: equal and opposite to the radii's ratio.
TEST(WheelsetFreeRolling, TheWheelsTangentialForcesHaveNoMomentAboutTheAxle) {
  Wheelset wheelset(track(), exact_at(0.5e-3));
  for (double y : {0.0, 3e-3}) {
    SCOPED_TRACE(y);
    WheelsetState state;
    state.position.lateral_displacement_m = y;
    state.velocity.free_rolling = true;
    const WheelsetResult r = wheelset.evaluate(state);
    EXPECT_GT(r.free_rolling_iterations, 1);
    const double omega = r.state.velocity.wheel_angular_velocity_rad_per_s;
    ASSERT_TRUE(std::isfinite(omega));
    EXPECT_NE(omega, state.velocity.forward_speed_m_per_s / track().parameters().nominal_rolling_radius_m);
    const double mu_fz = 0.3 * 98.1e3;
    const WheelsetPatch& right = r.wheels[0].patches.front();
    const WheelsetPatch& left = r.wheels[1].patches.front();
    double moment = 0.0;
    for (const WheelResult& w : r.wheels)
      for (const WheelsetPatch& p : w.patches) moment += p.forces().F1_N * p.rolling_radius_m;
    EXPECT_LT(std::abs(moment), 1e-4 * mu_fz * 0.46);
    if (y == 0.0) {
      EXPECT_LT(std::abs(right.forces().F1_N), 1e-3 * mu_fz);
      EXPECT_LT(std::abs(left.forces().F1_N), 1e-3 * mu_fz);
    } else {
      EXPECT_GT(std::abs(left.forces().F1_N), 0.05 * mu_fz);  // the flange-side wheel rolls on a larger radius
      EXPECT_NEAR(right.forces().F1_N, -left.forces().F1_N, 0.01 * std::abs(left.forces().F1_N));
    }
    // Given that angular velocity, the same forces (the same code path: to rounding).
    WheelsetState given = state;
    given.velocity.free_rolling = false;
    given.velocity.wheel_angular_velocity_rad_per_s = omega;
    const WheelsetResult again = Wheelset(track(), exact_at(0.5e-3)).evaluate(given);
    EXPECT_NEAR(again.wheels[1].patches.front().forces().F1_N, left.forces().F1_N, 1e-6 * mu_fz);
  }
}

TEST(WheelsetFreeRolling, RefusesAGivenRotationBesideIt) {
  Wheelset wheelset(track(), exact_at(0.5e-3));
  WheelsetState state;
  state.velocity.free_rolling = true;
  state.velocity.wheel_angular_velocity_rad_per_s = 43.0;
  try {
    (void)wheelset.evaluate(state);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::invalid_input);
    EXPECT_NE(std::string(e.what()).find("free_rolling"), std::string::npos) << e.what();
  }
}

// The load balance uses the solver named: nH-FastSim's normal forces are the same whether it runs
// alone or after the exact solver with --balance-solver nh-fastsim (the same heights to the load
// tolerance), and differ when the exact solver balances (its tangential forces' vertical parts).
TEST(WheelsetBalanceSolver, TheNamedSolverMeetsTheLoad) {
  WheelsetOptions alone;
  alone.element_size_m = 0.5e-3;
  alone.solvers = {TangentialSolver::nh_fastsim};
  // Not the elastic slip: with it nH-FastSim's flange patch in full slip is the exact solver's to
  // 0.7 N of Fz, too close for the two balances to be told apart.
  alone.nh_fastsim.bound.slip_direction = SlipDirection::rigid_slip;
  WheelsetOptions both = alone;
  both.solvers = {TangentialSolver::exact, TangentialSolver::nh_fastsim};
  both.balance_solver = TangentialSolver::nh_fastsim;
  WheelsetState state;
  state.position.lateral_displacement_m = 5e-3;  // flange contact: large F2 with a vertical part
  const WheelsetResult a = Wheelset(track(), alone).evaluate(state);
  const WheelsetResult b = Wheelset(track(), both).evaluate(state);
  ASSERT_EQ(b.solver_force_track_N.size(), 2u);
  // Vertical force of nH-FastSim on each wheel meets the load in both runs (the load tolerance 1e-6
  // and the tangential balance's 1e-5 of the load).
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_NEAR(a.wheels[k].solver_force_track_N[0][2], 98.1e3, 2e-5 * 98.1e3);
    EXPECT_NEAR(b.wheels[k].solver_force_track_N[1][2], 98.1e3, 2e-5 * 98.1e3);
  }
  // The exact solver's totals are there too, and its vertical force is not the balanced one.
  EXPECT_GT(std::abs(b.wheels[1].solver_force_track_N[0][2] - 98.1e3), 1.0);
  WheelsetOptions wrong = alone;
  wrong.balance_solver = TangentialSolver::exact;
  EXPECT_THROW(Wheelset(track(), wrong), Error);
}

}  // namespace
}  // namespace railcontact

// The command: every solver's totals and the balance solver in the JSON, a rigid axle's roll, free
// rolling's angular velocity, the depth weighting on request.
namespace railcontact {
namespace {

nlohmann::json wheelset_json(const std::string& options) {
  const test::CommandResult r = test::run_cli("wheelset --json --element-size-m 0.0005 " + options);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return nlohmann::json::parse(r.out);
}

TEST(WheelsetCli, NamesTheBalanceSolverGivesEveryTotalTheRigidAxleAndFreeRolling) {
  const nlohmann::json both =
      wheelset_json("--y-m -0.005 --solver exact --solver nh-fastsim --balance-solver nh-fastsim");
  EXPECT_EQ(both["load_balance"]["solver"], "nh-fastsim");
  EXPECT_EQ(both["load_balance"]["axle"], "independent wheels");
  ASSERT_TRUE(both["solver_force_track_N"].contains("exact"));
  ASSERT_TRUE(both["solver_force_track_N"].contains("nh-fastsim"));
  // nH-FastSim's vertical forces meet the loads (it balances); the first solver's totals are
  // force_track_N, as before.
  for (const auto& w : both["wheels"])
    EXPECT_NEAR(w["solver_force_track_N"]["nh-fastsim"][2].get<double>(), 98100.0, 2e-5 * 98100.0);
  EXPECT_EQ(both["force_track_N"], both["solver_force_track_N"]["exact"]);
  const nlohmann::json alone = wheelset_json("--y-m -0.005");
  EXPECT_NEAR(alone["wheels"][0]["patches"][0]["normal_force_N"].get<double>(),
              both["wheels"][0]["patches"][0]["normal_force_N"].get<double>(), 1e-5 * 98100.0);

  // A rigid axle: both wheels at one height (its balance's tolerance, 1e-8 m), the roll found.
  // Off centre the two contacts differ (flange side and field side), so the roll is not zero.
  const nlohmann::json rigid = wheelset_json("--y-m 0.003 --rigid-axle");
  EXPECT_EQ(rigid["load_balance"]["axle"], "rigid axle");
  EXPECT_NEAR(rigid["wheels"][0]["vertical_displacement_m"].get<double>(),
              rigid["wheels"][1]["vertical_displacement_m"].get<double>(), 1e-7);
  EXPECT_GT(std::abs(rigid["state"]["roll_rad"].get<double>()), 1e-6);
  for (const auto& w : rigid["wheels"]) EXPECT_NEAR(w["force_track_N"][2].get<double>(), 98100.0, 2e-5 * 98100.0);

  const nlohmann::json free = wheelset_json("--free-rolling --solver exact");
  EXPECT_TRUE(free["state"]["free_rolling"].get<bool>());
  EXPECT_GT(free["state"]["free_rolling_iterations"].get<int>(), 1);
  EXPECT_NE(free["state"]["wheel_angular_velocity_rad_per_s"].get<double>(), 20.0 / 0.46);
  EXPECT_LT(std::abs(free["wheels"][0]["force_track_N"][0].get<double>()), 1e-3 * 0.3 * 98100.0);

  // The depth weighting moves the centred patch's reference point (CONTACT's squared-gap one is
  // 10.15 mm on the rail's gauge side, the depth-weighted 10.09 mm).
  const nlohmann::json depth = wheelset_json("--reference-weighting depth");
  const nlohmann::json squared = wheelset_json("");
  EXPECT_NEAR(squared["wheels"][0]["patches"][0]["rail_profile_y_m"].get<double>(), -10.15e-3, 0.03e-3);
  EXPECT_NEAR(depth["wheels"][0]["patches"][0]["rail_profile_y_m"].get<double>(), -10.09e-3, 0.03e-3);
}

// A rotation given on the command line replaces the case file's, whichever it is: the measured-wheel
// example runs in free rolling; with --extra-creepage 0 it rolls purely at r0 (Ω = V / r0 to
// rounding), as a wheelset table needs.
TEST(WheelsetCli, ARotationOnTheCommandLineReplacesTheCaseFiles) {
  const std::string example = std::string(RAILCONTACT_SOURCE_DIR) + "/examples/wheelset_measured_wheel.toml";
  const nlohmann::json free = wheelset_json(example);
  EXPECT_TRUE(free["state"]["free_rolling"].get<bool>());
  const nlohmann::json pure = wheelset_json(example + " --extra-creepage 0");
  EXPECT_FALSE(pure["state"]["free_rolling"].get<bool>());
  EXPECT_NEAR(pure["state"]["wheel_angular_velocity_rad_per_s"].get<double>(), 20.0 / 0.46, 1e-12 * 20.0 / 0.46);
}

}  // namespace
}  // namespace railcontact
