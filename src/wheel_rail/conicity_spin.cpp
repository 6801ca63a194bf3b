// Spin creepage from the conicity of the contact, paper Eq 24, signed (docs/WHEEL_RAIL.md §3).
#include "railcontact/wheel_rail.hpp"

#include <cmath>

#include "railcontact/error.hpp"

namespace railcontact {

std::array<double, 3> contact_normal_in_track_frame(double contact_angle_rad, WheelSide side) {
  require(std::isfinite(contact_angle_rad), "spin creepage: the contact angle must be finite");
  // The track centre lies at +y from the right rail and at -y from the left one.
  const double towards_centre = side == WheelSide::right ? 1.0 : -1.0;
  return {0.0, towards_centre * std::sin(contact_angle_rad), std::cos(contact_angle_rad)};
}

double spin_creepage_per_m(const std::array<double, 3>& x3_axis_track, double nominal_rolling_radius_m) {
  require(std::isfinite(nominal_rolling_radius_m) && nominal_rolling_radius_m > 0.0,
          "spin creepage: the rolling radius must be positive");
  // ω / V = (0, 1/r0, 0): rolling forward (+x) without slip, ω × (0, 0, -r0) = (-V, 0, 0) cancels
  // the axle's velocity at the contact.
  const std::array<double, 3> omega_per_speed{0.0, 1.0 / nominal_rolling_radius_m, 0.0};
  return omega_per_speed[0] * x3_axis_track[0] + omega_per_speed[1] * x3_axis_track[1] +
         omega_per_speed[2] * x3_axis_track[2];  // φ = ω·X3 / V
}

double conicity_spin_per_m(double contact_angle_rad, WheelSide side, double nominal_wheel_diameter_m) {
  require(std::isfinite(nominal_wheel_diameter_m) && nominal_wheel_diameter_m > 0.0,
          "spin creepage: the wheel diameter must be positive");
  // Eq 24: |φ| = 2 sin γ / d, the sign that of ω·X3.
  return spin_creepage_per_m(contact_normal_in_track_frame(contact_angle_rad, side), 0.5 * nominal_wheel_diameter_m);
}

}  // namespace railcontact
