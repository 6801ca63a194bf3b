// Exact undeformed distance h(x1, x2) in the tangent plane of a wheel–rail contact
// (docs/GEOMETRY.md §4). In the cross-section x = x1 the rail is its profile (prismatic) and the
// wheel is its profile raised by r(s) - sqrt(r(s)^2 - x1^2) (a body of revolution, zero yaw and
// roll). The line through the tangent-plane point (x1, x2) along the contact normal n stays in
// that cross-section; h is the distance along n from where it meets the rail to where it meets
// the wheel. Each meeting point is a 1-D root find on the profile parameter.
#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "geometry/root_finding.hpp"
#include "geometry/tangent_section.hpp"
#include "railcontact/error.hpp"

namespace railcontact {

namespace geometry {

namespace {

// Parameter range around s_contact on which the curve runs against t (its tangent makes an
// angle of less than about 87 degrees with -t), limited by the ends of the profile. Walks in at
// most kMaximumSteps steps of 0.1 mm (longer ones on a longer profile), so it ends on any input.
std::pair<double, double> monotone_range(const SmoothProfile& profile, double s_contact, double ty, double tz) {
  constexpr double kMaximumSteps = 100000;
  const double s_begin = profile.s_begin_m(), s_end = profile.s_end_m();
  require(std::isfinite(s_contact) && std::isfinite(s_begin) && std::isfinite(s_end) && s_begin <= s_contact &&
              s_contact <= s_end,
          [&] {
            return fmt::format("undeformed distance: the contact parameter {} lies outside the profile {} [{}, {}]",
                               s_contact, profile.source(), s_begin, s_end);
          });
  const double step = std::max(0.1e-3, (s_end - s_begin) / kMaximumSteps);
  const double min_projection = 0.05;
  const auto runs_against_t = [&](double s) {
    const auto p = profile.at(s);
    return (p.dy_ds * ty + p.dz_ds * tz) / std::hypot(p.dy_ds, p.dz_ds) < -min_projection;
  };
  // Steps k * step from s_contact (not repeated additions, which stall where step is below the
  // spacing of doubles): at most kMaximumSteps + 1 each way.
  const auto walk = [&](double direction, double limit) {
    double reached = s_contact;
    for (double k = 1; k <= kMaximumSteps + 1 && reached != limit; ++k) {
      const double s = direction < 0 ? std::max(s_contact - k * step, limit) : std::min(s_contact + k * step, limit);
      if (!runs_against_t(s)) break;
      reached = s;
    }
    return reached;
  };
  return {walk(-1.0, s_begin), walk(+1.0, s_end)};
}

[[noreturn]] void beyond_reach(const char* which, double x2) {
  throw Error(fmt::format("undeformed distance: the normal line through x2 = {:.4f} mm misses the {} profile "
                          "(beyond its reach in the tangent plane)",
                          x2 * 1e3, which));
}

}  // namespace

TangentPlaneSection::TangentPlaneSection(const WheelRailPair& pair, const WheelRailContactPoint& contact)
    : pair_(&pair), contact_(contact) {
  const double g = contact.contact_angle_rad;
  cy_ = contact.y_rail_m;
  cz_ = contact.z_rail_m;
  ty_ = -std::cos(g);
  tz_ = std::sin(g);
  ny_ = -std::sin(g);
  nz_ = -std::cos(g);
  rail_s_contact_ = pair.rail().parameter_at(contact.y_rail_m);
  wheel_s_contact_ = pair.wheel().parameter_at(contact.y_wheel_m);
  std::tie(rail_s_lo_, rail_s_hi_) = monotone_range(pair.rail(), rail_s_contact_, ty_, tz_);
  std::tie(wheel_s_lo_, wheel_s_hi_) = monotone_range(pair.wheel(), wheel_s_contact_, ty_, tz_);
  // The projection on t decreases along both curves.
  const auto rail_x2 = [&](double s) {
    const auto p = pair.rail().at(s);
    return (p.y_m - cy_) * ty_ + (p.z_m - cz_) * tz_;
  };
  const auto wheel_x2 = [&](double s) {
    const auto p = pair.wheel().at(s);
    return (p.y_m + contact.wheel_to_rail_offset_m - cy_) * ty_ + (p.z_m + contact.wheel_drop_m - cz_) * tz_;
  };
  x2_min_m_ = std::max(rail_x2(rail_s_hi_), wheel_x2(wheel_s_hi_));
  x2_max_m_ = std::min(rail_x2(rail_s_lo_), wheel_x2(wheel_s_lo_));
}

double TangentPlaneSection::rail_normal_m(double x2_m) const {
  const SmoothProfile& rail = pair_->rail();
  const auto f = [&](double s) {
    const auto p = rail.at(s);
    return std::pair{(p.y_m - cy_) * ty_ + (p.z_m - cz_) * tz_ - x2_m, p.dy_ds * ty_ + p.dz_ds * tz_};
  };
  const auto s =
      newton_root(f, rail_s_lo_, rail_s_hi_, rail_s_contact_ - x2_m, 1e-15, "the rail point on the normal line");
  if (!s) beyond_reach("rail", x2_m);
  const auto p = rail.at(*s);
  return (p.y_m - cy_) * ny_ + (p.z_m - cz_) * nz_;
}

double TangentPlaneSection::wheel_normal_m(double x1_m, double x2_m, double& parameter) const {
  const SmoothProfile& wheel = pair_->wheel();
  const double r_offset = pair_->parameters().nominal_rolling_radius_m - pair_->nominal_radius_z_m();
  const double x1_sq = x1_m * x1_m;
  // Wheel surface point in the cross-section x1 (rail profile frame) at parameter s, and its
  // derivative: the profile point raised by r - sqrt(r^2 - x1^2), r = wheel radius there.
  struct Point {
    double y, z, dy, dz;
  };
  const auto point = [&](double s) {
    const auto p = wheel.at(s);
    const double r = r_offset + p.z_m;
    if (!(r * r > x1_sq)) {
      throw Error(fmt::format("undeformed distance: |x1| = {:.3f} mm exceeds the wheel radius", std::abs(x1_m) * 1e3));
    }
    const double root = std::sqrt(r * r - x1_sq);
    return Point{p.y_m + contact_.wheel_to_rail_offset_m, p.z_m + contact_.wheel_drop_m - (r - root), p.dy_ds,
                 p.dz_ds - p.dz_ds * (1.0 - r / root)};
  };
  const auto f = [&](double s) {
    const Point w = point(s);
    return std::pair{(w.y - cy_) * ty_ + (w.z - cz_) * tz_ - x2_m, w.dy * ty_ + w.dz * tz_};
  };
  const auto s = newton_root(f, wheel_s_lo_, wheel_s_hi_, parameter, 1e-15, "the wheel point on the normal line");
  if (!s) beyond_reach("wheel", x2_m);
  parameter = *s;
  const Point w = point(*s);
  return (w.y - cy_) * ny_ + (w.z - cz_) * nz_;
}

double TangentPlaneSection::undeformed_distance_m(double x1_m, double x2_m) const {
  double parameter = wheel_parameter_guess(x2_m);
  return wheel_normal_m(x1_m, x2_m, parameter) - rail_normal_m(x2_m);
}

}  // namespace geometry

double WheelRailPair::undeformed_distance(const WheelRailContactPoint& contact, double x1_m, double x2_m) const {
  require(std::isfinite(x1_m) && std::isfinite(x2_m), "undeformed distance: x1 and x2 must be finite");
  return geometry::TangentPlaneSection(*this, contact).undeformed_distance_m(x1_m, x2_m);
}

std::vector<double> WheelRailPair::undeformed_distance(const WheelRailContactPoint& contact, const Mesh& mesh) const {
  validate(mesh);
  const geometry::TangentPlaneSection section(*this, contact);
  std::vector<double> h(mesh.size());
  for (int i2 = 0; i2 < mesh.n2; ++i2) {
    const double x2 = mesh.x2(i2);
    const double rail = section.rail_normal_m(x2);
    double parameter = section.wheel_parameter_guess(x2);
    for (int i1 = 0; i1 < mesh.n1; ++i1) {
      h[mesh.index(i1, i2)] = section.wheel_normal_m(mesh.x1(i1), x2, parameter) - rail;
    }
  }
  return h;
}

}  // namespace railcontact
