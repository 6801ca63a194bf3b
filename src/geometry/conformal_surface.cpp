// The conformal contact surface of an interpenetration region (docs/WHEELSET.md §4 "Conformal
// contact"): a mesh developed along the rail profile, one frame per strip, and the undeformed
// distance along each strip's normal.
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/wheelset_frames.hpp"
#include "railcontact/error.hpp"
#include "railcontact/wheelset_geometry.hpp"

namespace railcontact {

namespace {

constexpr int kMaximumGrowthSteps = 8;
constexpr double kNotInContact_m = 1.0;  // the gap given to strips that cannot touch

// The strip at developed lateral coordinate s (rail arc length from the reference point, along X2).
ConformalStrip strip_at(const geometry::WheelOnRail& w, const InterpenetrationRegion& region, double s_m,
                        double& wheel_parameter) {
  ConformalStrip strip;
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
  strip.rail_point_track_m = pair.rail_point;
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
  int lo1 = static_cast<int>(std::floor(region.x1_min_m / d)) - border_elements;
  int hi1 = static_cast<int>(std::ceil(region.x1_max_m / d)) + border_elements;
  int lo2 = static_cast<int>(std::floor(region.x2_min_m / d)) - border_elements;
  int hi2 = static_cast<int>(std::ceil(region.x2_max_m / d)) + border_elements;
  for (int step = 0;; ++step) {
    // Whole granules, as the planar area (the extra elements to +x1 and to the gauge side).
    if (const int extra = geometry::round_up_to_granule(hi1 - lo1 + 1) - (hi1 - lo1 + 1); extra > 0) hi1 += extra;
    if (const int extra = geometry::round_up_to_granule(hi2 - lo2 + 1) - (hi2 - lo2 + 1); extra > 0)
      (region.side == WheelSide::right ? hi2 : lo2) += region.side == WheelSide::right ? extra : -extra;
    Mesh mesh;
    mesh.n1 = hi1 - lo1 + 1;
    mesh.n2 = hi2 - lo2 + 1;
    mesh.dx1_m = d;
    mesh.dx2_m = d;
    mesh.x1_first_m = lo1 * d;
    mesh.x2_first_m = lo2 * d;
    const double elements = static_cast<double>(mesh.n1) * static_cast<double>(mesh.n2);
    require(elements <= kMaximumPotentialAreaElements, [&] {
      return fmt::format("{} {} x {} = {:.3g} elements of {:.3g} mm on the conformal surface of the {} wheel; at most "
                         "{:.3g} elements are allowed: use larger elements",
                         kPotentialAreaTooLarge, mesh.n1, mesh.n2, elements, d * 1e3, side_name(region.side),
                         kMaximumPotentialAreaElements);
    });
    validate(mesh);
    // The strips, from the reference point outwards (each wheel root starts from its neighbour's).
    std::vector<ConformalStrip> strips(static_cast<std::size_t>(mesh.n2));
    const int centre = std::clamp(-lo2, 0, mesh.n2 - 1);
    const double wheel_at_reference = w.wheel().parameter_at(region.wheel_profile_y_m);
    for (int direction : {+1, -1}) {
      double wheel_parameter = wheel_at_reference;
      for (int i2 = direction > 0 ? centre : centre - 1; i2 >= 0 && i2 < mesh.n2; i2 += direction)
        strips[static_cast<std::size_t>(i2)] = strip_at(w, region, mesh.x2(i2), wheel_parameter);
    }
    // The developed surface must not fold over in the tangent plane: the strips' points in order.
    double previous_x2 = -std::numeric_limits<double>::infinity(), previous_angle = 0.0;
    for (const ConformalStrip& strip : strips) {
      if (!strip.possible_contact) continue;
      require(strip.x2_m > previous_x2, [&] {
        return fmt::format(
            "conformal contact area of the {} wheel at y = {:.3f} mm, yaw {:.2f} mrad: the curved surface folds over "
            "(its normal turns from {:.3f} to {:.3f} rad from the reference's across one element); use the planar "
            "contact surface",
            side_name(region.side), position.lateral_displacement_m * 1e3, position.yaw_rad * 1e3, previous_angle,
            strip.angle_rad);
      });
      previous_x2 = strip.x2_m;
      previous_angle = strip.angle_rad;
    }
    // h along X3 at each strip's tangent-plane point, times the cosine of its angle (the normal
    // distance between locally parallel surfaces); strips that cannot touch get a wide gap.
    // Strip by strip: a strip whose line along X3 misses the rail profile (far round a flange, at
    // a large angle from the tangent plane) cannot touch either.
    std::vector<double> h(mesh.size(), kNotInContact_m);
    std::vector<double> strip_x2(strips.size(), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t j = 0; j < strips.size(); ++j) {
      if (!strips[j].possible_contact) continue;
      strip_x2[j] = strips[j].x2_m;
      try {
        geometry::undeformed_distance_on_strips(w, region, mesh, strip_x2, h);
      } catch (const Error&) {
        strips[j].possible_contact = false;
        for (int i1 = 0; i1 < mesh.n1; ++i1) h[mesh.index(i1, static_cast<int>(j))] = kNotInContact_m;
      }
      strip_x2[j] = std::numeric_limits<double>::quiet_NaN();
    }
    for (int i2 = 0; i2 < mesh.n2; ++i2) {
      const ConformalStrip& strip = strips[static_cast<std::size_t>(i2)];
      if (!strip.possible_contact) continue;
      for (int i1 = 0; i1 < mesh.n1; ++i1) h[mesh.index(i1, i2)] *= std::cos(strip.angle_rad);
    }
    bool low1 = false, high1 = false, low2 = false, high2 = false;
    for (int i2 = 0; i2 < mesh.n2; ++i2) {
      for (int i1 = 0; i1 < mesh.n1; ++i1) {
        if (!(h[mesh.index(i1, i2)] < 0.0)) continue;
        low1 = low1 || i1 < border_elements;
        high1 = high1 || i1 >= mesh.n1 - border_elements;
        low2 = low2 || i2 < border_elements;
        high2 = high2 || i2 >= mesh.n2 - border_elements;
      }
    }
    if (!(low1 || high1 || low2 || high2)) return TangentPlaneArea{mesh, std::move(h), step, std::move(strips)};
    require(step < kMaximumGrowthSteps, [&] {
      return fmt::format(
          "conformal contact area of the {} wheel: the overlap still reaches the border of a {} x {} mesh after {} "
          "enlargements",
          side_name(region.side), mesh.n1, mesh.n2, step);
    });
    const int grow1 = std::max(border_elements, mesh.n1 / 4), grow2 = std::max(border_elements, mesh.n2 / 4);
    if (low1) lo1 -= grow1;
    if (high1) hi1 += grow1;
    if (low2) lo2 -= grow2;
    if (high2) hi2 += grow2;
  }
}

}  // namespace railcontact
