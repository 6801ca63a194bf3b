#pragma once
// Stage: wheel–rail contact, the wheelset's kinematics (docs/WHEEL_RAIL.md §12). The wheelset's motion on
// the track and the kinematic creepages of a contact: the rigid velocity of the wheel's material
// point at the contact, on the undeformed wheel surface, over the rolling speed, in the contact
// frame (as Kalker's CONTACT defines them, with the opposite sign: CONTACT's are rail − wheel).
//
// Frames (docs/GEOMETRY.md §1-3): the track frame x along the track in the direction of travel,
// y lateral to the LEFT, z UP; the wheelset's axle points along +y when roll and yaw are zero. A
// contact frame has X1 along the rolling direction, X3 the contact normal into the wheel and
// X2 = X3 × X1. Creepages as everywhere in railcontact (docs/CONVENTIONS.md): the rigid slip of the
// wheel relative to the rail is V_ref (ξ − φ x2, η + φ x1), so for the wheel's material point Q at
// the contact, moving with velocity v_Q in the track frame (the rail is at rest),
//   ξ = v_Q·X1 / V_ref,   η = v_Q·X2 / V_ref,   φ = ω·X3 / V_ref   (1/m),
// with ω the wheelset's angular velocity and V_ref = (V + Ω r_Q) / 2 the rolling speed: the mean of
// the forward speed V and the wheel's circumferential speed at Q (Ω about the axle, r_Q the
// distance of Q from it). A wheel rolling forward without slip at radius r0 turns with
// ω = (0, V/r0, 0), and then V_ref = V. In a wheelset, Q lies on the undeformed wheel surface:
// the reference point P on the rail surface moved into the rail along the normal by the patch's
// approach (its largest rigid overlap), Q = P − approach X3 (docs/WHEEL_RAIL.md §12).
#include <array>
#include <cstdint>
#include <limits>

#include "railcontact/contact_patch.hpp"
#include "railcontact/wheel_rail.hpp"

namespace railcontact {

// The wheelset's orientation and velocities (SI units; angles in rad, rates in rad/s).
struct WheelsetMotion {
  double forward_speed_m_per_s = 0.0;   // V: speed of the wheelset centre along +x, > 0 (the rolling speed)
  double lateral_velocity_m_per_s = 0.0;   // dy/dt of the wheelset centre (+ to the left)
  double vertical_velocity_m_per_s = 0.0;  // dz/dt of the wheelset centre (+ up)
  double roll_rad = 0.0;                // rotation about x (positive: the left wheel rises)
  double yaw_rad = 0.0;                 // rotation about z (positive: the axle's left end moves backwards)
  double roll_rate_rad_per_s = 0.0;     // about x
  double yaw_rate_rad_per_s = 0.0;      // about z
  // Angular velocity of the wheels about their axle (the wheelset is one rigid body), positive
  // when rolling forward: V / r0 for pure rolling at the nominal radius r0.
  double wheel_angular_velocity_rad_per_s = 0.0;
};

// The common rolling shortcut: pure rolling at the nominal radius r0 plus an extra longitudinal
// creepage ξ0 (a driven wheelset: ξ0 < 0 for traction, > 0 for braking) at r0, over the rolling
// speed: V − Ω r0 = ξ0 (V + Ω r0)/2, i.e. Ω = V (1 − ξ0/2) / ((1 + ξ0/2) r0). Throws Error unless
// V > 0, r0 > 0 and all values finite.
double wheel_angular_velocity_for_rolling(double forward_speed_m_per_s, double nominal_rolling_radius_m,
                                          double extra_longitudinal_creepage = 0.0);

// The wheelset's angular velocity in the track frame: yaw rate about z, roll rate about the
// yawed x axis, and the wheels' rotation about the axle.
Vector3 wheelset_angular_velocity(const WheelsetMotion& motion);

// A contact on a wheel: its creepage point (the wheel's material point whose velocity gives the
// creepages) relative to the wheelset centre and its frame (unit axes), all in the track frame.
struct ContactFrame {
  Vector3 point_from_wheelset_centre_m{};
  Vector3 x1{1.0, 0.0, 0.0};
  Vector3 x2{0.0, 1.0, 0.0};
  Vector3 x3{0.0, 0.0, 1.0};
};

// The contact frame of a contact at contact angle γ on the right or left wheel with X1 = +x
// (docs/WHEEL_RAIL.md §3): X3 = (0, ±sin γ, cos γ) (+ on the right wheel, leaning towards the
// track centre), X2 = X3 × X1.
ContactFrame contact_frame(const Vector3& point_from_wheelset_centre_m, double contact_angle_rad, WheelSide side);

// The rolling speed V_ref = (V + Ω r)/2 at the contact's point (see the top of this header): the
// divisor of its creepages. Throws Error (invalid_input) when it is not positive (the wheels
// turning backwards), and as kinematic_creepage.
double rolling_speed_m_per_s(const WheelsetMotion& motion, const ContactFrame& contact);

// ξ, η, φ of the contact for the wheelset's motion (see the top of this header). Throws Error
// (invalid_input) unless V > 0 and every input is finite, and unless the frame's axes are unit
// and orthogonal to 1e-9.
Creepage kinematic_creepage(const WheelsetMotion& motion, const ContactFrame& contact);

// Throws Error (invalid_input) unless the kinematic creepage of a contact (kinematic_creepage of
// motion and contact) lies in the range of a contact: |ξ|, |η| <= kMaximumCreepage and |φ| <=
// kMaximumSpinCreepage_per_m (contact_patch.hpp), as for a single patch. The message names the
// wheel, the creepage and the velocity of the motion that contributes most to it (the creepages are
// linear in the velocities), e.g. "wheelset: the yaw rate yaw_rate_rad_per_s = 1000 rad/s at the
// forward speed V = 20 m/s gives the right wheel's contact a longitudinal creepage xi = 37.5, …".
void check_kinematic_creepage(const Creepage& creepage, const WheelsetMotion& motion, const ContactFrame& contact,
                              WheelSide side);

// The wheelset's motion prepared for many contacts (a time step's patches, a conformal patch's
// strips): its axle, angular velocity and centre velocity computed once. Its numbers are those of
// rolling_speed_m_per_s and kinematic_creepage (which use it), with the same checks.
class WheelsetKinematics {
 public:
  // Throws Error (invalid_input) unless V > 0 and every value of the motion is finite.
  explicit WheelsetKinematics(const WheelsetMotion& motion);
  [[nodiscard]] const WheelsetMotion& motion() const { return motion_; }
  // The contact's rolling speed V_ref and its creepages (each over V_ref).
  struct AtContact {
    double rolling_speed_m_per_s = 0.0;
    Creepage creepage{0.0, 0.0, 0.0};
  };
  [[nodiscard]] AtContact at(const ContactFrame& contact) const;
  [[nodiscard]] double rolling_speed_m_per_s(const ContactFrame& contact) const;
  // The wheel's velocity at the contact's point along X1 and X2 (m/s) and its angular velocity
  // along X3 (rad/s): the creepages times V_ref, also where the wheels do not roll.
  [[nodiscard]] Creepage creep_velocities(const ContactFrame& contact) const;

 private:
  WheelsetMotion motion_;
  Vector3 axle_{}, omega_{}, centre_velocity_{};
};

}  // namespace railcontact
