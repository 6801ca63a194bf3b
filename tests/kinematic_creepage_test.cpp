// Kinematic creepages from the wheelset's motion (railcontact/wheelset.hpp): analytic cases worked
// out by hand from v_P = v_C + ω × p, and the mirror symmetry of the two wheels.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "railcontact/error.hpp"
#include "railcontact/wheel_rail.hpp"
#include "railcontact/wheelset.hpp"

namespace railcontact {
namespace {

constexpr double kV = 20.0;     // m/s
constexpr double kR0 = 0.46;    // m
constexpr double kL = 0.7465;   // half the contact distance (m)

WheelsetMotion rolling(double extra_xi = 0.0) {
  WheelsetMotion m;
  m.forward_speed_m_per_s = kV;
  m.wheel_angular_velocity_rad_per_s = wheel_angular_velocity_for_rolling(kV, kR0, extra_xi);
  return m;
}

TEST(KinematicCreepage, PureRollingAtTheNominalRadiusHasOnlyTheConicitySpin) {
  for (double gamma : {0.0, 0.03, 0.5}) {
    const Creepage right = kinematic_creepage(rolling(), contact_frame({0, -kL, -kR0}, gamma, WheelSide::right));
    const Creepage left = kinematic_creepage(rolling(), contact_frame({0, kL, -kR0}, gamma, WheelSide::left));
    EXPECT_NEAR(right.xi, 0.0, 1e-15);
    EXPECT_NEAR(right.eta, 0.0, 1e-15);
    // φ = ω·X3 / V = sin γ / r0: Eq 24 with its sign (+ right, − left wheel).
    EXPECT_NEAR(right.phi, conicity_spin_per_m(gamma, WheelSide::right, 2 * kR0), 1e-14);
    EXPECT_NEAR(left.phi, conicity_spin_per_m(gamma, WheelSide::left, 2 * kR0), 1e-14);
    EXPECT_NEAR(right.phi, std::sin(gamma) / kR0, 1e-14);
  }
}

// A conical wheel touching below the nominal radius: its surface is slower than the axle,
// V − Ω r = V (1 − r/r0) over V_ref = V (1 + r/r0)/2: ξ = 2 (r0 − r)/(r0 + r).
TEST(KinematicCreepage, RollingRadiusDifferenceGivesLongitudinalCreepage) {
  for (double r : {0.455, 0.46, 0.4637}) {
    const Creepage c = kinematic_creepage(rolling(), contact_frame({0, -kL, -r}, 0.05, WheelSide::right));
    EXPECT_NEAR(c.xi, 2.0 * (kR0 - r) / (kR0 + r), 1e-15) << r;
    EXPECT_NEAR(c.eta, 0.0, 1e-15);
  }
}

// Yaw ψ at pure rolling, contact under the yawed axle: v_Q = V (1 − cos ψ, −sin ψ, 0), and the
// wheel's circumferential speed along x is V cos ψ, so V_ref = V (1 + cos ψ)/2,
// η = −2 sin ψ cos γ / (1 + cos ψ) (≈ −ψ) and ξ = 2 (1 − cos ψ)/(1 + cos ψ).
TEST(KinematicCreepage, YawAnglePureRollingGivesLateralCreepageMinusPsi) {
  for (double psi : {-0.01, 0.002, 0.01}) {
    for (double gamma : {0.0, 0.04}) {
      WheelsetMotion m = rolling();
      m.yaw_rad = psi;
      const Vector3 p{kL * std::sin(psi), -kL * std::cos(psi), -kR0};  // Rz(ψ) (0, −l, −r0)
      const Creepage c = kinematic_creepage(m, contact_frame(p, gamma, WheelSide::right));
      EXPECT_NEAR(c.eta, -2.0 * std::sin(psi) * std::cos(gamma) / (1.0 + std::cos(psi)), 1e-15);
      EXPECT_NEAR(c.xi, 2.0 * (1.0 - std::cos(psi)) / (1.0 + std::cos(psi)), 1e-15);
      if (gamma == 0.0) EXPECT_NEAR(c.eta, -psi, 2e-7);
    }
  }
}

TEST(KinematicCreepage, LateralVelocityGivesLateralCreepage) {
  WheelsetMotion m = rolling();
  m.lateral_velocity_m_per_s = 0.05;
  const Creepage c = kinematic_creepage(m, contact_frame({0, -kL, -kR0}, 0.0, WheelSide::right));
  EXPECT_NEAR(c.eta, 0.05 / kV, 1e-16);
  // Tilted contact: the lateral velocity projects on X2 = (0, cos γ, −sin γ).
  const Creepage tilted = kinematic_creepage(m, contact_frame({0, -kL, -kR0}, 0.3, WheelSide::right));
  EXPECT_NEAR(tilted.eta, 0.05 * std::cos(0.3) / kV, 1e-16);
}

// Yaw rate: the right wheel (y = −l) moves forward faster by ψ' l, the left one slower.
TEST(KinematicCreepage, YawRateGivesOppositeLongitudinalCreepagesOnTheTwoWheels) {
  WheelsetMotion m = rolling();
  m.yaw_rate_rad_per_s = 0.1;
  const Creepage right = kinematic_creepage(m, contact_frame({0, -kL, -kR0}, 0.0, WheelSide::right));
  const Creepage left = kinematic_creepage(m, contact_frame({0, kL, -kR0}, 0.0, WheelSide::left));
  EXPECT_NEAR(right.xi, 0.1 * kL / kV, 1e-15);
  EXPECT_NEAR(left.xi, -0.1 * kL / kV, 1e-15);
  // The yaw rate also spins the contact about the vertical: φ = ψ' cos γ / V on both wheels.
  EXPECT_NEAR(right.phi, 0.1 / kV, 1e-15);
}

TEST(KinematicCreepage, DrivenWheelsetHasTheExtraLongitudinalCreepage) {
  const Creepage c = kinematic_creepage(rolling(-0.002), contact_frame({0, -kL, -kR0}, 0.02, WheelSide::right));
  EXPECT_NEAR(c.xi, -0.002, 1e-15);
}

// The left wheel is the right wheel mirrored about the track centre plane (y → −y): with the motion
// mirrored too (ẏ, roll, yaw and their rates change sign), ξ stays, η and φ change sign.
TEST(KinematicCreepage, LeftWheelIsTheMirroredRightWheel) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 50; ++k) {
    WheelsetMotion m = rolling(0.003 * u(rng));
    m.lateral_velocity_m_per_s = 0.2 * u(rng);
    m.vertical_velocity_m_per_s = 0.01 * u(rng);
    m.roll_rad = 0.01 * u(rng);
    m.yaw_rad = 0.01 * u(rng);
    m.roll_rate_rad_per_s = 0.1 * u(rng);
    m.yaw_rate_rad_per_s = 0.1 * u(rng);
    const double gamma = 0.3 * std::abs(u(rng));
    const Vector3 p{0.01 * u(rng), -kL + 0.01 * u(rng), -kR0 + 0.005 * u(rng)};
    WheelsetMotion mirrored = m;
    mirrored.lateral_velocity_m_per_s = -m.lateral_velocity_m_per_s;
    mirrored.roll_rad = -m.roll_rad;
    mirrored.yaw_rad = -m.yaw_rad;
    mirrored.roll_rate_rad_per_s = -m.roll_rate_rad_per_s;
    mirrored.yaw_rate_rad_per_s = -m.yaw_rate_rad_per_s;
    const Creepage right = kinematic_creepage(m, contact_frame(p, gamma, WheelSide::right));
    const Creepage left = kinematic_creepage(mirrored, contact_frame({p[0], -p[1], p[2]}, gamma, WheelSide::left));
    EXPECT_NEAR(left.xi, right.xi, 1e-15);
    EXPECT_NEAR(left.eta, -right.eta, 1e-15);
    EXPECT_NEAR(left.phi, -right.phi, 1e-14);
  }
}

std::string error_of(const WheelsetMotion& m, const ContactFrame& f) {
  try {
    (void)kinematic_creepage(m, f);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::invalid_input);
    return e.what();
  }
  return "no error";
}

TEST(KinematicCreepage, BadMotionIsRefusedWithTheQuantityNamed) {
  const ContactFrame f = contact_frame({0, -kL, -kR0}, 0.02, WheelSide::right);
  WheelsetMotion standing = rolling();
  standing.forward_speed_m_per_s = 0.0;
  EXPECT_NE(error_of(standing, f).find("forward speed V = 0 m/s must be positive"), std::string::npos);
  WheelsetMotion nan_yaw = rolling();
  nan_yaw.yaw_rad = std::nan("");
  EXPECT_NE(error_of(nan_yaw, f).find("yaw angle"), std::string::npos);
  ContactFrame skew = f;
  skew.x2 = {0.1, 1.0, 0.0};
  EXPECT_NE(error_of(rolling(), skew).find("orthogonal"), std::string::npos);
  EXPECT_THROW((void)wheel_angular_velocity_for_rolling(kV, 0.0), Error);
  EXPECT_THROW((void)contact_frame({0, 0, 0}, 2.0, WheelSide::right), Error);
}

}  // namespace
}  // namespace railcontact
