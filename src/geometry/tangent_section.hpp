#pragma once
// The tangent-plane section of one wheel–rail contact (docs/GEOMETRY.md §4): evaluates the
// exact undeformed distance h(x1, x2) by 1-D root finds on the two profiles. Built once per
// contact and reused for many (x1, x2).
#include <utility>

#include "railcontact/geometry.hpp"

namespace railcontact::geometry {

class TangentPlaneSection {
 public:
  TangentPlaneSection(const WheelRailPair& pair, const WheelRailContactPoint& contact);

  // Normal coordinate (along X3, from the contact point) of the rail surface on the normal line
  // through x2; throws Error when the line misses the rail.
  [[nodiscard]] double rail_normal_m(double x2_m) const;
  // Same for the wheel surface in the cross-section x1. `parameter` is the wheel profile
  // parameter of the previous call (a starting guess) and receives the new one.
  [[nodiscard]] double wheel_normal_m(double x1_m, double x2_m, double& parameter) const;
  [[nodiscard]] double wheel_parameter_guess(double x2_m) const { return wheel_s_contact_ - x2_m; }

  [[nodiscard]] double undeformed_distance_m(double x1_m, double x2_m) const;

  // The x2 interval in which the normal line meets both profiles (in the cross-section x1 = 0).
  [[nodiscard]] double x2_min_m() const { return x2_min_m_; }
  [[nodiscard]] double x2_max_m() const { return x2_max_m_; }

 private:
  const WheelRailPair* pair_;
  WheelRailContactPoint contact_;
  double cy_ = 0.0, cz_ = 0.0;  // contact point C in the rail profile frame
  double ty_ = 0.0, tz_ = 0.0;  // X2 = t = (-cos γ, sin γ)
  double ny_ = 0.0, nz_ = 0.0;  // X3 = n = (-sin γ, -cos γ)
  double rail_s_lo_ = 0.0, rail_s_hi_ = 0.0, rail_s_contact_ = 0.0;
  double wheel_s_lo_ = 0.0, wheel_s_hi_ = 0.0, wheel_s_contact_ = 0.0;
  double x2_min_m_ = 0.0, x2_max_m_ = 0.0;
};

}  // namespace railcontact::geometry
