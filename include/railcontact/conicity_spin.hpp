#pragma once
// Spin creepage of a wheel rolling forward on its rail, from the conicity of the contact
// (paper Eq 24, |φ| = 2 sin γ / d) with its sign (docs/WHEEL_RAIL.md §3).
//
// Track frame: x along the track in the direction of travel, y to the LEFT, z UP. A wheelset
// rolling forward at speed V without slip at the nominal radius r0 = d/2 turns with
// ω = (0, V/r0, 0) (both wheels: one axle). The contact normal into the wheel leans towards the
// track centre by the contact angle γ: X3 = (0, +sin γ, cos γ) on the right wheel and
// (0, −sin γ, cos γ) on the left one (the mirror image). The rigid slip of the wheel relative
// to the rail, w = (ξ − φ x2, η + φ x1) (METHOD.md §6), contains the rotation of the wheel about
// X3, so φ = ω·X3 / V:
//   right wheel φ = +2 sin γ / d,   left wheel φ = −2 sin γ / d.
#include <array>

namespace railcontact {

enum class WheelSide { right, left };

// Unit contact normal into the wheel, in the track frame, for contact angle γ (rad; positive
// when the normal leans towards the track centre, docs/GEOMETRY.md §3).
std::array<double, 3> contact_normal_in_track_frame(double contact_angle_rad, WheelSide side);

// φ = ω·X3 / V (1/m) for a wheelset rolling forward, ω / V = (0, 1/r0, 0); x3_axis_track is the
// contact normal into the wheel in the track frame (e.g. WheelRailContactPoint::x3_axis_track).
double spin_creepage_per_m(const std::array<double, 3>& x3_axis_track, double nominal_rolling_radius_m);

// Eq 24 with its sign: φ = ±2 sin γ / d (+ right wheel, − left wheel). Throws Error unless γ is
// finite and d > 0.
double conicity_spin_per_m(double contact_angle_rad, WheelSide side, double nominal_wheel_diameter_m = 0.92);

}  // namespace railcontact
