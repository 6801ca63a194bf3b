// The conformal contact surface of an interpenetration region (docs/WHEELSET.md §4 "Conformal
// contact"): a mesh developed along the rail profile, one frame per strip, and the undeformed
// distance along each strip's normal.
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/conformal_surface.hpp"
#include "geometry/wheelset_frames.hpp"
#include "railcontact/error.hpp"
#include "railcontact/wheelset_geometry.hpp"

namespace railcontact {

namespace {

constexpr double kNotInContact_m = 1.0;  // the gap given to strips that cannot touch

// The strip at developed lateral coordinate s (rail arc length from the reference point, along X2).
ConformalStrip strip_at(const geometry::WheelOnRail& w, const InterpenetrationRegion& region, double s_m,
                        double& wheel_parameter) {
  ConformalStrip strip;
  strip.s_m = s_m;
  const SmoothProfile& rail = w.rail();
  // X2 runs towards −y_p on the right side and +y_p on the left (the profiles' parameters grow with y_p).
  const double u = rail.parameter_at(region.rail_profile_y_m) + w.sign() * s_m;
  if (!(u > rail.s_begin_m() && u < rail.s_end_m())) {
    strip.possible_contact = false;
    return strip;
  }
  const double rail_y = rail.at(u).y_m;
  geometry::WheelOnRail::SurfacePair pair;
  try {
    pair = w.surface_pair(region, u, wheel_parameter);
  } catch (const Error&) {  // the rail's normal line misses the wheel: no contact there
    strip.possible_contact = false;
    return strip;
  }
  strip.wheel_point_track_m = pair.wheel_point;
  const auto dot = [](const Vector3& a, const Vector3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  // The mean normal (the bisector of the two unit normals) and its turn from X3 about X1.
  const Vector3 mean{pair.rail_normal[0] + pair.wheel_normal[0], pair.rail_normal[1] + pair.wheel_normal[1],
                     pair.rail_normal[2] + pair.wheel_normal[2]};
  strip.angle_rad = std::atan2(-dot(mean, region.x2_axis), dot(mean, region.x3_axis));
  const Vector3 middle{0.5 * (pair.rail_point[0] + pair.wheel_point[0]) - region.reference_point_track_m[0],
                       0.5 * (pair.rail_point[1] + pair.wheel_point[1]) - region.reference_point_track_m[1],
                       0.5 * (pair.rail_point[2] + pair.wheel_point[2]) - region.reference_point_track_m[2]};
  strip.x2_m = dot(middle, region.x2_axis);
  const double between = std::acos(std::clamp(dot(pair.rail_normal, pair.wheel_normal), -1.0, 1.0));
  strip.possible_contact = between <= kConformalTurnAway_rad && rail_y >= region.rail_profile_y_lower_bound_m &&
                           rail_y <= region.rail_profile_y_upper_bound_m;
  return strip;
}

}  // namespace

namespace geometry {

void require_unfolded(const std::vector<ConformalStrip>& strips, WheelSide side, const WheelsetPosition& position) {
  double previous_x2 = -std::numeric_limits<double>::infinity(), previous_angle = 0.0;
  for (const ConformalStrip& strip : strips) {
    if (!strip.possible_contact) continue;
    require(strip.x2_m > previous_x2, [&] {
      return fmt::format(
          "conformal contact area of the {} wheel at y = {:.3f} mm, yaw {:.2f} mrad: the curved surface folds over "
          "(its normal turns from {:.3f} to {:.3f} rad from the reference's across one element); use the planar "
          "contact surface",
          side_name(side), position.lateral_displacement_m * 1e3, position.yaw_rad * 1e3, previous_angle,
          strip.angle_rad);
    });
    previous_x2 = strip.x2_m;
    previous_angle = strip.angle_rad;
  }
}

}  // namespace geometry

TangentPlaneArea WheelsetTrack::conformal_contact_area(const WheelsetPosition& position,
                                                       const InterpenetrationRegion& region, double element_size_m,
                                                       int border_elements) const {
  validate(position);
  const double d = element_size_m;
  require(std::isfinite(d) && d >= kMinimumTangentPlaneElement_m && d <= 0.01, [&] {
    return fmt::format("conformal contact area: the element size {:g} mm must lie in [{:g}, 10] mm", d * 1e3,
                       kMinimumTangentPlaneElement_m * 1e3);
  });
  require(border_elements >= 1 && border_elements <= 100,
          "conformal contact area: the border must be 1 to 100 elements wide");
  const geometry::WheelOnRail w(*this, region.side, position);
  // The tangent plane's bounding box of the overlap to start from: s ≥ |x2| on a curved surface.
  const geometry::GrowingArea growing{region, d, d, border_elements, "conformal contact area",
                                      "on the conformal surface"};
  return geometry::grown_area(growing, [&](const Mesh& mesh, TangentPlaneArea& area) {
    // The strips, from the reference point outwards (each wheel root starts from its neighbour's).
    std::vector<ConformalStrip>& strips = area.strips;
    strips.assign(static_cast<std::size_t>(mesh.n2), ConformalStrip{});
    const int centre = std::clamp(static_cast<int>(std::lround(-mesh.x2_first_m / d)), 0, mesh.n2 - 1);
    const double wheel_at_reference = w.wheel().parameter_at(region.wheel_profile_y_m);
    for (int direction : {+1, -1}) {
      double wheel_parameter = wheel_at_reference;
      for (int i2 = direction > 0 ? centre : centre - 1; i2 >= 0 && i2 < mesh.n2; i2 += direction)
        strips[static_cast<std::size_t>(i2)] = strip_at(w, region, mesh.x2(i2), wheel_parameter);
    }
    geometry::require_unfolded(strips, region.side, position);
    // h along X3 at each strip's tangent-plane point, times the cosine of its angle (the normal
    // distance between locally parallel surfaces); strips that cannot touch get a wide gap. Strip by
    // strip: a strip whose line along X3 misses the rail profile (far round a flange, at a large
    // angle from the tangent plane) cannot touch either.
    std::vector<double>& h = area.h_m;
    h.assign(mesh.size(), kNotInContact_m);
    std::vector<double> strip_x2(strips.size(), std::numeric_limits<double>::quiet_NaN());
    const geometry::StripRoots roots = geometry::strip_roots(mesh);
    for (std::size_t j = 0; j < strips.size(); ++j) {
      if (!strips[j].possible_contact) continue;
      strip_x2[j] = strips[j].x2_m;
      try {
        geometry::undeformed_distance_on_strips(w, region, mesh, strip_x2, h, &roots);
        const double cos_angle = std::cos(strips[j].angle_rad);
        for (int i1 = 0; i1 < mesh.n1; ++i1) h[mesh.index(i1, static_cast<int>(j))] *= cos_angle;
      } catch (const Error&) {
        strips[j].possible_contact = false;
        for (int i1 = 0; i1 < mesh.n1; ++i1) h[mesh.index(i1, static_cast<int>(j))] = kNotInContact_m;
      }
      strip_x2[j] = std::numeric_limits<double>::quiet_NaN();
    }
  });
}

}  // namespace railcontact
