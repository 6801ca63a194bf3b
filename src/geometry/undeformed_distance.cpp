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
#include "railcontact/error.hpp"
#include "railcontact/wheel_rail.hpp"

namespace railcontact {

namespace {

// The tangent-plane section of one contact: contact point C, tangent t (= X2) and normal n
// (= X3) in the rail profile frame (y_p, z_p), and the parameter ranges around the contact on
// which each profile's projection onto t is monotone.
struct Section {
  double cy = 0.0, cz = 0.0;  // C
  double ty = 0.0, tz = 0.0;  // t = (-cos γ, sin γ)
  double ny = 0.0, nz = 0.0;  // n = (-sin γ, -cos γ)
  double rail_s_lo = 0.0, rail_s_hi = 0.0, rail_s_contact = 0.0;
  double wheel_s_lo = 0.0, wheel_s_hi = 0.0, wheel_s_contact = 0.0;
};

// Parameter range around s_contact where the tangent's projection on t stays below
// -min_projection (the curve runs against t), limited by the ends of the profile.
std::pair<double, double> monotone_range(const SmoothProfile& profile, double s_contact, double ty, double tz) {
  const double step = 0.1e-3;
  const double min_projection = 0.05;  // |angle to the contact tangent| < about 87 degrees
  const auto runs_against_t = [&](double s) {
    const auto p = profile.at(s);
    return (p.dy_ds * ty + p.dz_ds * tz) / std::hypot(p.dy_ds, p.dz_ds) < -min_projection;
  };
  double lo = s_contact, hi = s_contact;
  while (lo > profile.s_begin_m() && runs_against_t(std::max(lo - step, profile.s_begin_m()))) {
    lo = std::max(lo - step, profile.s_begin_m());
  }
  while (hi < profile.s_end_m() && runs_against_t(std::min(hi + step, profile.s_end_m()))) {
    hi = std::min(hi + step, profile.s_end_m());
  }
  return {lo, hi};
}

Section make_section(const WheelRailPair& pair, const WheelRailContactPoint& c) {
  Section sec;
  const double g = c.contact_angle_rad;
  sec.cy = c.y_rail_m;
  sec.cz = c.z_rail_m;
  sec.ty = -std::cos(g);
  sec.tz = std::sin(g);
  sec.ny = -std::sin(g);
  sec.nz = -std::cos(g);
  sec.rail_s_contact = pair.rail().parameter_at(c.y_rail_m);
  sec.wheel_s_contact = pair.wheel().parameter_at(c.y_wheel_m);
  std::tie(sec.rail_s_lo, sec.rail_s_hi) = monotone_range(pair.rail(), sec.rail_s_contact, sec.ty, sec.tz);
  std::tie(sec.wheel_s_lo, sec.wheel_s_hi) = monotone_range(pair.wheel(), sec.wheel_s_contact, sec.ty, sec.tz);
  return sec;
}

[[noreturn]] void beyond_reach(const char* which, double x2) {
  throw Error(fmt::format("undeformed distance: the normal line through x2 = {:.4f} mm misses the {} profile "
                          "(beyond its reach in the tangent plane)",
                          x2 * 1e3, which));
}

// Normal coordinate of the rail surface on the line through x2, and its parameter.
std::pair<double, double> rail_crossing(const WheelRailPair& pair, const Section& sec, double x2, double guess) {
  const SmoothProfile& rail = pair.rail();
  const auto f = [&](double s) {
    const auto p = rail.at(s);
    return std::pair{(p.y_m - sec.cy) * sec.ty + (p.z_m - sec.cz) * sec.tz - x2, p.dy_ds * sec.ty + p.dz_ds * sec.tz};
  };
  const auto s = geometry::solve_bracketed(f, sec.rail_s_lo, sec.rail_s_hi, guess, 1e-15);
  if (!s) beyond_reach("rail", x2);
  const auto p = rail.at(*s);
  return {(p.y_m - sec.cy) * sec.ny + (p.z_m - sec.cz) * sec.nz, *s};
}

// Normal coordinate of the wheel surface (cross-section x1) on the line through x2.
std::pair<double, double> wheel_crossing(const WheelRailPair& pair, const WheelRailContactPoint& c, const Section& sec,
                                         double x1, double x2, double guess) {
  const SmoothProfile& wheel = pair.wheel();
  const double r_offset = pair.parameters().nominal_rolling_radius_m - pair.taping_line_z_m();
  const double x1_sq = x1 * x1;
  // Wheel point in the rail frame at parameter s and its derivative.
  const auto point = [&](double s, double& y, double& z, double& dy, double& dz) {
    const auto p = wheel.at(s);
    const double r = r_offset + p.z_m;
    if (!(r * r > x1_sq)) {
      throw Error(fmt::format("undeformed distance: x1 = {:.3f} mm exceeds the wheel radius", x1 * 1e3));
    }
    const double root = std::sqrt(r * r - x1_sq);
    const double lift = r - root;
    const double dlift = p.dz_ds * (1.0 - r / root);
    y = p.y_m + c.wheel_to_rail_offset_m;
    z = p.z_m + c.wheel_drop_m - lift;
    dy = p.dy_ds;
    dz = p.dz_ds - dlift;
  };
  const auto f = [&](double s) {
    double y, z, dy, dz;
    point(s, y, z, dy, dz);
    return std::pair{(y - sec.cy) * sec.ty + (z - sec.cz) * sec.tz - x2, dy * sec.ty + dz * sec.tz};
  };
  const auto s = geometry::solve_bracketed(f, sec.wheel_s_lo, sec.wheel_s_hi, guess, 1e-15);
  if (!s) beyond_reach("wheel", x2);
  double y, z, dy, dz;
  point(*s, y, z, dy, dz);
  return {(y - sec.cy) * sec.ny + (z - sec.cz) * sec.nz, *s};
}

}  // namespace

double WheelRailPair::undeformed_distance(const WheelRailContactPoint& contact, double x1_m, double x2_m) const {
  require(std::isfinite(x1_m) && std::isfinite(x2_m), "undeformed distance: x1 and x2 must be finite");
  const Section sec = make_section(*this, contact);
  const auto [zeta_rail, s_rail] = rail_crossing(*this, sec, x2_m, sec.rail_s_contact - x2_m);
  (void)s_rail;
  const auto [zeta_wheel, s_wheel] = wheel_crossing(*this, contact, sec, x1_m, x2_m, sec.wheel_s_contact - x2_m);
  (void)s_wheel;
  return zeta_wheel - zeta_rail;
}

std::vector<double> WheelRailPair::undeformed_distance(const WheelRailContactPoint& contact, const Mesh& mesh) const {
  validate(mesh);
  const Section sec = make_section(*this, contact);
  std::vector<double> h(mesh.size());
  for (int i2 = 0; i2 < mesh.n2; ++i2) {
    const double x2 = mesh.x2(i2);
    const auto [zeta_rail, s_rail] = rail_crossing(*this, sec, x2, sec.rail_s_contact - x2);
    (void)s_rail;
    double guess = sec.wheel_s_contact - x2;
    for (int i1 = 0; i1 < mesh.n1; ++i1) {
      const auto [zeta_wheel, s_wheel] = wheel_crossing(*this, contact, sec, mesh.x1(i1), x2, guess);
      guess = s_wheel;
      h[mesh.index(i1, i2)] = zeta_wheel - zeta_rail;
    }
  }
  return h;
}

}  // namespace railcontact
