// One wheel of a wheelset over its rail: contact locus, region reference point, and the normal
// lines of the tangent plane (docs/WHEELSET.md §2–4).
#include "geometry/wheelset_frames.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/root_finding.hpp"
#include "railcontact/error.hpp"

namespace railcontact::geometry {

namespace {

Vector3 add(const Vector3& a, const Vector3& b, double scale = 1.0) {
  return {a[0] + scale * b[0], a[1] + scale * b[1], a[2] + scale * b[2]};
}

// Each locus sample stands for a lateral strip of the overlap, |Δy| wide (half the distance between
// its neighbours on the rail profile), in which the wheel dips below the rail by e = −g (the
// vertical gap g < 0 at the locus point) and rises as x²/2r along the track (r: the nominal radius
// r0, as Kalker's CONTACT takes it). Its weight in the region's averages (docs/WHEELSET.md §4):
//   depth:        e |Δy|;
//   squared gap:  |Δy| ∫ (e − x²/2r)² dx over the strip's overlap |x| < sqrt(2 r e)
//                 = |Δy| (16/15) e² sqrt(2 r e).
// Both fall to zero continuously at the region's ends, so the averages move continuously with
// the position.
double sample_width_m(const std::vector<ContactLocusSample>& locus, std::size_t k) {
  return 0.5 * std::abs(locus[std::min(k + 1, locus.size() - 1)].rail_profile_y_m -
                        locus[k > 0 ? k - 1 : 0].rail_profile_y_m);
}

double sample_weight(const std::vector<ContactLocusSample>& locus, std::size_t k, ReferenceWeighting weighting,
                     double nominal_radius_m) {
  const double e = -locus[k].vertical_gap_m, width = sample_width_m(locus, k);
  return weighting == ReferenceWeighting::depth ? e * width
                                                : width * (16.0 / 15.0) * e * e * std::sqrt(2.0 * nominal_radius_m * e);
}

// The overlap's extent along the locus samples first..last: the lateral range on the rail profile,
// the deepest normal interpenetration, and the rail normal angle's range over the part of the
// overlap at least half as deep as its deepest point: for a Hertzian contact that part is as wide
// as the contact area (the rigid overlap is √2 wider), so the range is the contact's, not the
// overlap's.
void set_overlap_extent(const std::vector<ContactLocusSample>& locus, std::size_t first, std::size_t last,
                        InterpenetrationRegion& r) {
  r.max_interpenetration_m = 0.0;
  r.rail_profile_y_min_m = std::numeric_limits<double>::infinity();
  r.rail_profile_y_max_m = -std::numeric_limits<double>::infinity();
  r.contact_angle_min_rad = std::numeric_limits<double>::infinity();
  r.contact_angle_max_rad = -std::numeric_limits<double>::infinity();
  for (std::size_t k = first; k <= last; ++k) {
    const ContactLocusSample& s = locus[k];
    r.rail_profile_y_min_m = std::min(r.rail_profile_y_min_m, s.rail_profile_y_m);
    r.rail_profile_y_max_m = std::max(r.rail_profile_y_max_m, s.rail_profile_y_m);
    if (!(s.vertical_gap_m < 0.0)) continue;
    r.max_interpenetration_m = std::max(r.max_interpenetration_m, -s.vertical_gap_m * std::cos(s.contact_angle_rad));
  }
  double deepest = 0.0;
  for (std::size_t k = first; k <= last; ++k) deepest = std::max(deepest, -locus[k].vertical_gap_m);
  for (std::size_t k = first; k <= last; ++k) {
    if (!(-locus[k].vertical_gap_m >= 0.5 * deepest)) continue;
    r.contact_angle_min_rad = std::min(r.contact_angle_min_rad, locus[k].contact_angle_rad);
    r.contact_angle_max_rad = std::max(r.contact_angle_max_rad, locus[k].contact_angle_rad);
  }
}

// The averages over the overlapping samples with the reference weighting (profile positions,
// contact angle and its spread, rolling radius) and the depth weighting's total; returns the
// average x of the locus points, the reference point's.
double set_weighted_averages(const std::vector<ContactLocusSample>& locus, std::size_t first, std::size_t last,
                             ReferenceWeighting weighting, double nominal_radius_m, InterpenetrationRegion& r) {
  double sum_w = 0.0, sum_y = 0.0, sum_yw = 0.0, sum_angle = 0.0, sum_radius = 0.0, sum_x = 0.0, sum_depth = 0.0;
  for (std::size_t k = first; k <= last; ++k) {
    const ContactLocusSample& s = locus[k];
    if (!(s.vertical_gap_m < 0.0)) continue;
    const double e = -s.vertical_gap_m;
    const double w = sample_weight(locus, k, weighting, nominal_radius_m);
    sum_depth += e * sample_width_m(locus, k);
    sum_w += w;
    sum_y += w * s.rail_profile_y_m;
    sum_yw += w * s.wheel_profile_y_m;
    sum_angle += w * s.contact_angle_rad;
    sum_radius += w * s.rolling_radius_m;
    sum_x += w * s.point_track_m[0];
  }
  require(sum_w > 0.0, "contact search: an interpenetration region without overlap");
  r.interpenetration_area_m2 = sum_depth;
  r.rail_profile_y_m = sum_y / sum_w;
  r.wheel_profile_y_m = sum_yw / sum_w;
  r.contact_angle_rad = sum_angle / sum_w;
  // The angle's spread about it, with the same weights: it grows continuously as a second hump of
  // the overlap deepens (the half-depth range above jumps when one crosses half the depth).
  double sum_square = 0.0;
  for (std::size_t k = first; k <= last; ++k) {
    const ContactLocusSample& s = locus[k];
    if (!(s.vertical_gap_m < 0.0)) continue;
    const double d = s.contact_angle_rad - r.contact_angle_rad;
    sum_square += sample_weight(locus, k, weighting, nominal_radius_m) * d * d;
  }
  r.contact_angle_spread_rad = std::sqrt(sum_square / sum_w);
  r.rolling_radius_m = sum_radius / sum_w;
  return sum_x / sum_w;
}

}  // namespace

WheelOnRail::WheelOnRail(const WheelsetTrack& track, WheelSide side, const WheelsetPosition& position)
    : wheel_(&track.pair(side).wheel()),
      rail_(&track.pair(side).rail()),
      side_(side),
      sign_(side_sign(side)),
      wheel_offset_m_(wheel_origin_offset_m(track.parameters())),
      rail_offset_m_(rail_origin_offset_m(track.pair(side), track.parameters())),
      nominal_radius_m_(track.parameters().nominal_rolling_radius_m),
      radius_datum_z_m_(track.pair(side).nominal_radius_z_m()) {
  centre_ = {0.0, position.lateral_displacement_m, track.nominal_axle_height_m() + position.vertical_displacement_m};
  axle_ = axle_direction(position.roll_rad, position.yaw_rad);
  // down = (−e_z) minus its component along the axle, normalised.
  const Vector3 minus_z{0.0, 0.0, -1.0};
  down_ = add(minus_z, axle_, -dot(minus_z, axle_));
  const double norm = std::sqrt(dot(down_, down_));
  for (double& c : down_) c /= norm;
  ahead_ = cross(axle_, down_);
}

bool WheelOnRail::locus_sample(double wheel_parameter_m, ContactLocusSample& sample) const {
  const ProfileCurvePoint p = wheel_->at(wheel_parameter_m);
  const double radius = nominal_radius_m_ + p.z_m - radius_datum_z_m_;
  sample.wheel_profile_y_m = p.y_m;
  sample.rolling_radius_m = radius;
  if (!(std::abs(p.dy_ds) > 1e-3) || !(radius > 0.0)) return false;  // a vertical part of the profile
  // dr/ds along the axle (s = σ (W0 + y_w)).
  const double dr_ds = sign_ * p.dz_ds / p.dy_ds;
  // The wheel's outward normal at angle θ about the axle, e_ρ(θ) − dr/ds a, has no x component when
  // cos θ down_x + sin θ ahead_x = dr/ds a_x (docs/WHEELSET.md §2): the solution nearest the bottom.
  // With (A, B) = R (cos θ0, sin θ0) and C = R cos σ: θ = θ0 ± σ, the one with the larger cos θ
  // (θ0 + σ when sin θ0 ≤ 0), by the angle-addition formulas.
  const double A = down_[0], B = ahead_[0], C = dr_ds * axle_[0];
  const double R = std::hypot(A, B);
  if (!(std::abs(C) < R)) return false;
  const double cos_theta0 = A / R, sin_theta0 = B / R;
  const double cos_spread = C / R, sin_spread = std::sqrt(1.0 - cos_spread * cos_spread);
  const double turn = sin_theta0 <= 0.0 ? 1.0 : -1.0;  // θ = θ0 + turn σ
  const double cos_theta = cos_theta0 * cos_spread - turn * sin_theta0 * sin_spread;
  const double sin_theta = sin_theta0 * cos_spread + turn * cos_theta0 * sin_spread;
  if (!(cos_theta > 0.5)) return false;  // not on the lower half of the wheel
  const double axial = sign_ * (wheel_offset_m_ + p.y_m);
  Vector3 e_rho = add(Vector3{cos_theta * down_[0], cos_theta * down_[1], cos_theta * down_[2]}, ahead_, sin_theta);
  sample.point_track_m = add(add(centre_, axle_, axial), e_rho, radius);
  // The rail below the locus point.
  const double y_rail = sign_ * sample.point_track_m[1] - rail_offset_m_;
  if (!(y_rail > rail_->y_min_m() && y_rail < rail_->y_max_m())) return false;
  const double rail_parameter = rail_->parameter_at(y_rail);
  const ProfileCurvePoint q = rail_->at(rail_parameter);
  sample.rail_profile_y_m = y_rail;
  sample.rail_parameter_m = rail_parameter;
  sample.vertical_gap_m = sample.point_track_m[2] + q.z_m;  // locus z − (−z_p)
  sample.contact_angle_rad = std::atan2(-q.dz_ds, q.dy_ds);
  return true;
}

InterpenetrationRegion WheelOnRail::region(const std::vector<ContactLocusSample>& locus, std::size_t first,
                                           std::size_t last, ReferenceWeighting weighting) const {
  InterpenetrationRegion r;
  r.side = side_;
  r.first_sample = first;
  r.last_sample = last;
  set_overlap_extent(locus, first, last, r);
  const double x_reference_m = set_weighted_averages(locus, first, last, weighting, nominal_radius_m_, r);
  set_contact_frame(x_reference_m, r);
  set_tangent_plane_box(locus, first, last, x_reference_m, r);
  return r;
}

Vector3 WheelOnRail::rail_point_track_m(double x_m, double rail_profile_y_m) const {
  return rail_point_at_parameter_m(x_m, rail_->parameter_at(rail_profile_y_m));
}

Vector3 WheelOnRail::rail_point_at_parameter_m(double x_m, double rail_parameter_m) const {
  const ProfileCurvePoint q = rail_->at(rail_parameter_m);
  return {x_m, sign_ * (rail_offset_m_ + q.y_m), -q.z_m};
}

void WheelOnRail::set_contact_frame(double x_reference_m, InterpenetrationRegion& r) const {
  // The reference point on the rail surface below the average rail profile position; X3 the rail
  // normal at the average angle, X1 along the track.
  r.reference_point_track_m = rail_point_track_m(x_reference_m, r.rail_profile_y_m);
  const double sg = std::sin(r.contact_angle_rad), cg = std::cos(r.contact_angle_rad);
  r.x1_axis = {1.0, 0.0, 0.0};
  r.x3_axis = {0.0, -sign_ * sg, cg};
  r.x2_axis = cross(r.x3_axis, r.x1_axis);
}

void WheelOnRail::set_tangent_plane_box(const std::vector<ContactLocusSample>& locus, std::size_t first,
                                        std::size_t last, double x_reference_m, InterpenetrationRegion& r) const {
  // Bounding box of the overlap in the tangent plane: laterally from the separated samples on
  // both sides, along x1 from each overlapping locus point ± sqrt(2 r e / cos γ).
  r.x1_min_m = std::numeric_limits<double>::infinity();
  r.x1_max_m = -r.x1_min_m;
  r.x2_min_m = r.x1_min_m;
  r.x2_max_m = -r.x1_min_m;
  const std::size_t lo = first > 0 ? first - 1 : first, hi = std::min(last + 1, locus.size() - 1);
  for (std::size_t k = lo; k <= hi; ++k) {
    const ContactLocusSample& s = locus[k];
    // The rail point as locus_sample found it (its parameter kept), or from the profile position.
    const Vector3 rail_point = std::isnan(s.rail_parameter_m) ? rail_point_track_m(x_reference_m, s.rail_profile_y_m)
                                                               : rail_point_at_parameter_m(x_reference_m, s.rail_parameter_m);
    const double x2 = dot(add(rail_point, r.reference_point_track_m, -1.0), r.x2_axis);
    r.x2_min_m = std::min(r.x2_min_m, x2);
    r.x2_max_m = std::max(r.x2_max_m, x2);
    if (!(s.vertical_gap_m < 0.0)) continue;
    const double e = -s.vertical_gap_m * std::cos(s.contact_angle_rad);
    const double half = std::sqrt(2.0 * s.rolling_radius_m * e / std::max(std::cos(s.contact_angle_rad), 0.05));
    const double x1 = s.point_track_m[0] - x_reference_m;
    r.x1_min_m = std::min(r.x1_min_m, x1 - half);
    r.x1_max_m = std::max(r.x1_max_m, x1 + half);
  }
}

double WheelOnRail::rail_normal_m(const InterpenetrationRegion& region, double x2_m, double& rail_parameter) const {
  // The rail curve in the track's (y, z) plane: (σ (R0 + y(u)), −z(u)); its point on the normal
  // line has (point − O)·X2 = x2.
  const Vector3& o = region.reference_point_track_m;
  const Vector3& t = region.x2_axis;
  const auto f = [&](double u) {
    const ProfileCurvePoint q = rail_->at(u);
    const double y = sign_ * (rail_offset_m_ + q.y_m) - o[1], z = -q.z_m - o[2];
    return std::pair{y * t[1] + z * t[2] - x2_m, sign_ * q.dy_ds * t[1] - q.dz_ds * t[2]};
  };
  const double reach = 2.0 * std::abs(x2_m) + 5e-3;
  const double lo = std::max(rail_->s_begin_m(), rail_parameter - reach);
  const double hi = std::min(rail_->s_end_m(), rail_parameter + reach);
  const auto u = newton_root(f, lo, hi, std::clamp(rail_parameter, lo, hi), 1e-15, "the rail point on a normal line");
  if (!u) {
    throw Error(fmt::format("undeformed distance: the normal line through x2 = {:.3f} mm misses the {} rail profile",
                            x2_m * 1e3, side_name(side_)));
  }
  rail_parameter = *u;
  const ProfileCurvePoint q = rail_->at(*u);
  const double y = sign_ * (rail_offset_m_ + q.y_m) - o[1], z = -q.z_m - o[2];
  return y * region.x3_axis[1] + z * region.x3_axis[2];
}

double WheelOnRail::wheel_normal_m(const InterpenetrationRegion& region, double x1_m, double x2_m, double& t_m,
                                   double& wheel_parameter) const {
  // Unknowns t (along X3) and u (wheel profile parameter) with, for q = O + x1 X1 + x2 X2 + t X3:
  //   G1 = (q − C)·a − σ (W0 + y(u)) = 0     (the axial position of profile point u)
  //   G2 = |q − C − ((q − C)·a) a| − r(u) = 0 (on the surface of revolution there)
  // Newton's method from the previous element's solution (docs/WHEELSET.md §4).
  const Vector3 base = add(add(region.reference_point_track_m, region.x1_axis, x1_m), region.x2_axis, x2_m);
  const Vector3& n = region.x3_axis;
  const double axle_n = dot(axle_, n);
  double t = t_m, u = wheel_parameter;
  bool converged = false;
  for (int iteration = 0; iteration < 50 && !converged; ++iteration) {
    u = std::clamp(u, wheel_->s_begin_m(), wheel_->s_end_m());
    const ProfileCurvePoint p = wheel_->at(u);
    const Vector3 d = add(add(base, n, t), centre_, -1.0);
    const double axial = dot(d, axle_);
    const Vector3 radial = add(d, axle_, -axial);
    const double rho = std::sqrt(dot(radial, radial));
    const double G1 = axial - sign_ * (wheel_offset_m_ + p.y_m);
    const double G2 = rho - (nominal_radius_m_ + p.z_m - radius_datum_z_m_);
    if (std::abs(G1) < 1e-13 && std::abs(G2) < 1e-13) {
      converged = true;
      break;
    }
    // Jacobian [[a·n, −σ y'], [e_ρ·n, −z']].
    const double j11 = axle_n, j12 = -sign_ * p.dy_ds;
    const double j21 = dot(radial, n) / rho, j22 = -p.dz_ds;
    const double det = j11 * j22 - j12 * j21;
    if (!(std::abs(det) > 1e-12)) break;
    const double dt = (G1 * j22 - G2 * j12) / det;
    const double du = (j11 * G2 - j21 * G1) / det;
    t -= std::clamp(dt, -0.01, 0.01);
    u -= std::clamp(du, -0.01, 0.01);
    // Newton converges quadratically: after a step below 1e-9 m the error is of order
    // (1e-9 m)² × curvature (< 1e-16 m), so the step itself ends the iteration (one profile
    // evaluation per element with a good starting guess).
    if (std::abs(dt) < 1e-9 && std::abs(du) < 1e-9) {
      converged = true;
      break;
    }
  }
  if (!converged) {
    throw Error(ErrorKind::not_converged,
                fmt::format("undeformed distance: the normal line through ({:.3f}, {:.3f}) mm does not meet the {} "
                            "wheel (Newton's method did not converge)",
                            x1_m * 1e3, x2_m * 1e3, side_name(side_)));
  }
  require(u > wheel_->s_begin_m() && u < wheel_->s_end_m(), [&] {
    return fmt::format("undeformed distance: the normal line through ({:.3f}, {:.3f}) mm misses the {} wheel profile",
                       x1_m * 1e3, x2_m * 1e3, side_name(side_));
  });
  t_m = t;
  wheel_parameter = u;
  return t;
}

WheelOnRail::SurfacePair WheelOnRail::surface_pair(const InterpenetrationRegion& region, double rail_parameter,
                                                   double& wheel_parameter) const {
  SurfacePair pair;
  const ProfileCurvePoint q = rail_->at(rail_parameter);
  pair.rail_point = {region.reference_point_track_m[0], sign_ * (rail_offset_m_ + q.y_m), -q.z_m};
  // The rail's tangent in the track frame is (0, σ y', −z'); its normal out of the rail (up on the
  // crown) is (0, σ z', y').
  const double rail_norm = std::hypot(q.dy_ds, q.dz_ds);
  pair.rail_normal = {0.0, sign_ * q.dz_ds / rail_norm, q.dy_ds / rail_norm};
  // The wheel on the rail's normal line: the line of a region at the rail point with X3 that normal.
  InterpenetrationRegion line = region;
  line.reference_point_track_m = pair.rail_point;
  line.x3_axis = pair.rail_normal;
  double t = 0.0;
  (void)wheel_normal_m(line, 0.0, 0.0, t, wheel_parameter);
  pair.wheel_point = add(pair.rail_point, pair.rail_normal, t);
  // The surface of revolution's tangent along the profile is σ y' a + z' e_ρ (a the axle, e_ρ the
  // radial direction); its normal into the wheel is σ z' a − y' e_ρ.
  const ProfileCurvePoint p = wheel_->at(wheel_parameter);
  const Vector3 d = add(pair.wheel_point, centre_, -1.0);
  const Vector3 radial = add(d, axle_, -dot(d, axle_));
  const double rho = std::sqrt(dot(radial, radial));
  const Vector3 inward = add(Vector3{sign_ * p.dz_ds * axle_[0], sign_ * p.dz_ds * axle_[1], sign_ * p.dz_ds * axle_[2]},
                             radial, -p.dy_ds / rho);
  const double wheel_norm = std::sqrt(dot(inward, inward));
  pair.wheel_normal = {inward[0] / wheel_norm, inward[1] / wheel_norm, inward[2] / wheel_norm};
  return pair;
}

}  // namespace railcontact::geometry
