// Kinematic creepages of a contact from the wheelset's motion (railcontact/wheelset_kinematics.hpp,
// docs/WHEEL_RAIL.md §12): v_Q = v_C + ω × q at the creepage point Q (on the undeformed wheel
// surface), the rolling speed V_ref = (V + Ω r_Q)/2, then ξ = v_Q·X1 / V_ref, η = v_Q·X2 / V_ref,
// φ = ω·X3 / V_ref.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "railcontact/error.hpp"
#include "railcontact/wheelset_kinematics.hpp"

namespace railcontact {
namespace {

double dot(const Vector3& a, const Vector3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

Vector3 cross(const Vector3& a, const Vector3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

bool finite(const Vector3& v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

void require_finite(double value, const char* name) {
  require(std::isfinite(value), [&] { return fmt::format("wheelset motion: {} = {} must be finite", name, value); });
}

void validate(const WheelsetMotion& m) {
  require_finite(m.forward_speed_m_per_s, "the forward speed (m/s)");
  require(m.forward_speed_m_per_s > 0.0, [&] {
    return fmt::format(
        "wheelset motion: the forward speed V = {} m/s must be positive (creepages are velocities over the "
        "rolling speed; steady rolling at V = 0 has none)",
        m.forward_speed_m_per_s);
  });
  require_finite(m.lateral_velocity_m_per_s, "the lateral velocity (m/s)");
  require_finite(m.vertical_velocity_m_per_s, "the vertical velocity (m/s)");
  require_finite(m.roll_rad, "the roll angle (rad)");
  require_finite(m.yaw_rad, "the yaw angle (rad)");
  require_finite(m.roll_rate_rad_per_s, "the roll rate (rad/s)");
  require_finite(m.yaw_rate_rad_per_s, "the yaw rate (rad/s)");
  require_finite(m.wheel_angular_velocity_rad_per_s, "the wheel angular velocity (rad/s)");
}

void validate(const ContactFrame& c) {
  require(finite(c.point_from_wheelset_centre_m) && finite(c.x1) && finite(c.x2) && finite(c.x3),
          "contact frame: the contact point and the axes must be finite");
  constexpr double kTolerance = 1e-9;
  const bool orthonormal = std::abs(dot(c.x1, c.x1) - 1.0) < kTolerance && std::abs(dot(c.x2, c.x2) - 1.0) < kTolerance &&
                           std::abs(dot(c.x3, c.x3) - 1.0) < kTolerance && std::abs(dot(c.x1, c.x2)) < kTolerance &&
                           std::abs(dot(c.x1, c.x3)) < kTolerance && std::abs(dot(c.x2, c.x3)) < kTolerance;
  require(orthonormal, "contact frame: the axes X1, X2, X3 must be unit vectors, orthogonal to each other (to 1e-9)");
}

}  // namespace

double wheel_angular_velocity_for_rolling(double forward_speed_m_per_s, double nominal_rolling_radius_m,
                                          double extra_longitudinal_creepage) {
  require(std::isfinite(forward_speed_m_per_s) && forward_speed_m_per_s > 0.0, [&] {
    return fmt::format("rolling: the forward speed V = {} m/s must be positive and finite", forward_speed_m_per_s);
  });
  require(std::isfinite(nominal_rolling_radius_m) && nominal_rolling_radius_m > 0.0, [&] {
    return fmt::format("rolling: the nominal rolling radius r0 = {} m must be positive and finite", nominal_rolling_radius_m);
  });
  require(std::isfinite(extra_longitudinal_creepage) && std::abs(extra_longitudinal_creepage) <= kMaximumCreepage, [&] {
    return fmt::format("rolling: the extra longitudinal creepage {} must lie in [{:g}, {:g}]", extra_longitudinal_creepage,
                       -kMaximumCreepage, kMaximumCreepage);
  });
  // At the nominal radius below the axle, v·x = V − Ω r0 = ξ0 V_ref with V_ref = (V + Ω r0)/2.
  const double xi0 = extra_longitudinal_creepage;
  return forward_speed_m_per_s * (1.0 - 0.5 * xi0) / ((1.0 + 0.5 * xi0) * nominal_rolling_radius_m);
}

Vector3 wheelset_angular_velocity(const WheelsetMotion& m) {
  const Vector3 axle = axle_direction(m.roll_rad, m.yaw_rad);
  const double cy = std::cos(m.yaw_rad), sy = std::sin(m.yaw_rad);  // the yawed x axis (cos ψ, sin ψ, 0)
  const double W = m.wheel_angular_velocity_rad_per_s;
  return {m.roll_rate_rad_per_s * cy + W * axle[0], m.roll_rate_rad_per_s * sy + W * axle[1],
          m.yaw_rate_rad_per_s + W * axle[2]};
}

ContactFrame contact_frame(const Vector3& point_from_wheelset_centre_m, double contact_angle_rad, WheelSide side) {
  require(std::isfinite(contact_angle_rad) && std::abs(contact_angle_rad) < 0.5 * M_PI, [&] {
    return fmt::format("contact frame: the contact angle {} rad must be finite and below pi/2 in magnitude",
                       contact_angle_rad);
  });
  const double s = std::sin(contact_angle_rad), c = std::cos(contact_angle_rad);
  ContactFrame frame;
  frame.point_from_wheelset_centre_m = point_from_wheelset_centre_m;
  frame.x1 = {1.0, 0.0, 0.0};
  frame.x3 = side == WheelSide::right ? Vector3{0.0, s, c} : Vector3{0.0, -s, c};
  frame.x2 = cross(frame.x3, frame.x1);
  return frame;
}

WheelsetKinematics::WheelsetKinematics(const WheelsetMotion& motion) : motion_(motion) {
  validate(motion);
  axle_ = axle_direction(motion.roll_rad, motion.yaw_rad);
  omega_ = wheelset_angular_velocity(motion);
  centre_velocity_ = {motion.forward_speed_m_per_s, motion.lateral_velocity_m_per_s, motion.vertical_velocity_m_per_s};
}

double WheelsetKinematics::rolling_speed_m_per_s(const ContactFrame& contact) const {
  validate(contact);
  // The wheel's circumferential speed at the point: the wheels' rotation about the axle alone.
  const double W = motion_.wheel_angular_velocity_rad_per_s;
  const Vector3 turning = cross(Vector3{W * axle_[0], W * axle_[1], W * axle_[2]}, contact.point_from_wheelset_centre_m);
  const double circumferential = -dot(turning, contact.x1);
  // A wheel that does not turn forward does not roll (a locked wheel slides: ξ = 2).
  require(circumferential > 0.0, [&] {
    return fmt::format("wheelset motion: the wheels' rotation wheel_angular_velocity_rad_per_s = {:g} rad/s does not "
                       "roll the wheels forward at the forward speed V = {:g} m/s (the wheel's surface at the contact "
                       "moves at {:.3g} m/s about the axle; rolling forward is V / r0 = {:.4g} rad/s at r0 = {:.4g} m)",
                       W, motion_.forward_speed_m_per_s, circumferential,
                       motion_.forward_speed_m_per_s / std::hypot(contact.point_from_wheelset_centre_m[0],
                                                                   contact.point_from_wheelset_centre_m[2]),
                       std::hypot(contact.point_from_wheelset_centre_m[0], contact.point_from_wheelset_centre_m[2]));
  });
  return 0.5 * (motion_.forward_speed_m_per_s + circumferential);
}

Creepage WheelsetKinematics::creep_velocities(const ContactFrame& contact) const {
  const Vector3 spin_part = cross(omega_, contact.point_from_wheelset_centre_m);
  const Vector3 v{centre_velocity_[0] + spin_part[0], centre_velocity_[1] + spin_part[1],
                  centre_velocity_[2] + spin_part[2]};
  return {dot(v, contact.x1), dot(v, contact.x2), dot(omega_, contact.x3)};
}

WheelsetKinematics::AtContact WheelsetKinematics::at(const ContactFrame& contact) const {
  AtContact out;
  out.rolling_speed_m_per_s = rolling_speed_m_per_s(contact);  // validates the frame
  const Creepage v = creep_velocities(contact);
  const double V_ref = out.rolling_speed_m_per_s;
  out.creepage = {v.xi / V_ref, v.eta / V_ref, v.phi / V_ref};
  return out;
}

double rolling_speed_m_per_s(const WheelsetMotion& motion, const ContactFrame& contact) {
  return WheelsetKinematics(motion).rolling_speed_m_per_s(contact);
}

Creepage kinematic_creepage(const WheelsetMotion& motion, const ContactFrame& contact) {
  return WheelsetKinematics(motion).at(contact).creepage;
}

void check_kinematic_creepage(const Creepage& creepage, const WheelsetMotion& motion, const ContactFrame& contact,
                              WheelSide side) {
  const double values[3] = {creepage.xi, creepage.eta, creepage.phi};
  const double limits[3] = {kMaximumCreepage, kMaximumCreepage, kMaximumSpinCreepage_per_m};
  int component = -1;
  for (int k = 0; k < 3 && component < 0; ++k)
    if (!(std::abs(values[k]) <= limits[k])) component = k;
  if (component < 0) return;
  // The creep velocities are linear in the velocities: the share of each, over the motion's rolling
  // speed. The rolling part (V with the wheels' rotation at the roll and yaw angles) is the motion
  // without the rates; each rate's share is its velocity alone less that of no motion at all.
  const double V_ref = rolling_speed_m_per_s(motion, contact);
  const auto part = [&](const WheelsetMotion& m) {
    const Creepage c = WheelsetKinematics(m).creep_velocities(contact);
    return (component == 0 ? c.xi : component == 1 ? c.eta : c.phi) / V_ref;
  };
  WheelsetMotion rolling = motion;
  rolling.lateral_velocity_m_per_s = rolling.vertical_velocity_m_per_s = 0.0;
  rolling.roll_rate_rad_per_s = rolling.yaw_rate_rad_per_s = 0.0;
  WheelsetMotion still = rolling;
  still.wheel_angular_velocity_rad_per_s = 0.0;
  const double none = part(still);
  struct Share {
    std::string input;
    double value;
  };
  std::vector<Share> shares;
  shares.push_back({fmt::format("the wheels' rotation wheel_angular_velocity_rad_per_s = {:g} rad/s", motion.wheel_angular_velocity_rad_per_s),
                    part(rolling)});
  const auto rate = [&](double WheelsetMotion::*field, const char* name, const char* unit) {
    WheelsetMotion m = still;
    m.*field = motion.*field;
    shares.push_back({fmt::format("{} = {:g} {}", name, motion.*field, unit), part(m) - none});
  };
  rate(&WheelsetMotion::lateral_velocity_m_per_s, "the lateral velocity lateral_velocity_m_per_s", "m/s");
  rate(&WheelsetMotion::vertical_velocity_m_per_s, "the vertical velocity vertical_velocity_m_per_s", "m/s");
  rate(&WheelsetMotion::roll_rate_rad_per_s, "the roll rate roll_rate_rad_per_s", "rad/s");
  rate(&WheelsetMotion::yaw_rate_rad_per_s, "the yaw rate yaw_rate_rad_per_s", "rad/s");
  const Share& largest = *std::max_element(shares.begin(), shares.end(), [](const Share& a, const Share& b) {
    return std::abs(a.value) < std::abs(b.value);
  });
  constexpr const char* kNames[3] = {"a longitudinal creepage xi", "a lateral creepage eta", "a spin creepage phi"};
  constexpr const char* kUnits[3] = {"", "", " 1/m"};
  throw Error(fmt::format("wheelset: {} at the forward speed V = {:g} m/s gives the {} wheel's contact {} = {:.5g}{} "
                          "({:.5g}{} of it), beyond [{:g}, {:g}]{}: a contact slides rather than rolls (the same range "
                          "as a single patch's creepages)",
                          largest.input, motion.forward_speed_m_per_s, side_name(side), kNames[component],
                          values[component], kUnits[component], largest.value, kUnits[component], -limits[component],
                          limits[component], kUnits[component]));
}

}  // namespace railcontact
