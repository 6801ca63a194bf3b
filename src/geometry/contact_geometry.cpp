// The rigid contact geometry of a wheelset and the equivalent conicity (docs/CONTACT_GEOMETRY.md).
#include "railcontact/contact_geometry.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "geometry/wheelset_frames.hpp"
#include "railcontact/error.hpp"

namespace railcontact {

namespace {

constexpr double kMm = 1e-3;
// A contact on the flange beyond its steepest point where the slope has fallen by this much is the
// flange climbing over the rail (as in WheelsetTrack::contact_search).
constexpr double kFlangeRoundingAngle_rad = 5.0 * std::numbers::pi / 180.0;
// The roll is solved until the two wheels' touching heights agree to this (m).
constexpr double kHeightTolerance_m = 1e-11;
constexpr double kMaximumRoll_rad = 0.09;
constexpr long kMaximumSweepPositions = 100000;

// The point of first touch of one wheel at a position: the lowest point of the vertical gap along
// the wheel's contact locus.
struct FirstTouch {
  double wheel_parameter_m = 0.0;
  ContactLocusSample sample;
};

std::string where(WheelSide side, double y_m, double roll_rad) {
  return fmt::format("rigid contact, {} wheel at y = {:.3f} mm, roll = {:.3f} mrad", side_name(side), y_m / kMm,
                     roll_rad * 1e3);
}

FirstTouch first_touch(const WheelsetTrack& track, WheelSide side, const WheelsetPosition& position,
                       double step_m) {
  const geometry::WheelOnRail w(track, side, position);
  const double s0 = w.wheel().s_begin_m(), s1 = w.wheel().s_end_m();
  const auto count = static_cast<std::size_t>(std::ceil((s1 - s0) / step_m));
  const auto parameter = [&](std::size_t k) {
    return s0 + (s1 - s0) * static_cast<double>(k) / static_cast<double>(count);
  };
  std::vector<ContactLocusSample> locus(count + 1);
  std::vector<std::uint8_t> valid(count + 1, 0);
  std::size_t best = 0;
  double best_gap = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k <= count; ++k) {
    valid[k] = w.locus_sample(parameter(k), locus[k]) ? 1 : 0;
    if (valid[k] && locus[k].vertical_gap_m < best_gap) {
      best_gap = locus[k].vertical_gap_m;
      best = k;
    }
  }
  if (!std::isfinite(best_gap)) {
    throw Error(ErrorKind::no_contact,
                where(side, position.lateral_displacement_m, position.roll_rad) +
                    ": the wheel and rail profiles do not overlap laterally");
  }
  const bool open_before = best == 0 || !valid[best - 1];
  const bool open_after = best == count || !valid[best + 1];
  if (open_before || open_after) {
    throw Error(ErrorKind::invalid_input,
                fmt::format("{}: the first touch lies at the end of the wheel's contact locus (wheel profile y_p = "
                            "{:.2f} mm): the flange climbing over the rail or the wheel beyond the rail head",
                            where(side, position.lateral_displacement_m, position.roll_rad),
                            locus[best].wheel_profile_y_m / kMm));
  }
  // Refine between the neighbours: the gap is smooth along the locus.
  const auto gap = [&](double s) {
    ContactLocusSample sample;
    return w.locus_sample(s, sample) ? sample.vertical_gap_m : std::numeric_limits<double>::max();
  };
  const std::pair<double, double> refined =
      boost::math::tools::brent_find_minima(gap, parameter(best - 1), parameter(best + 1), 40);
  FirstTouch touch;
  touch.wheel_parameter_m = refined.first;
  if (!w.locus_sample(refined.first, touch.sample) || touch.sample.vertical_gap_m > best_gap) {
    touch.wheel_parameter_m = parameter(best);
    touch.sample = locus[best];
  }
  return touch;
}

void check_flange(const WheelsetTrack& track, WheelSide side, const FirstTouch& touch, double y_m, double roll_rad) {
  const SmoothProfile& wheel = track.pair(side).wheel();
  const ProfileCurvePoint p = wheel.at(touch.wheel_parameter_m);
  const double slope_rad = std::atan2(-p.dz_ds, p.dy_ds);
  if (touch.sample.wheel_profile_y_m < track.flange_steepest_point_y_m(side) &&
      slope_rad < track.flange_steepest_angle_rad(side) - kFlangeRoundingAngle_rad) {
    throw Error(ErrorKind::invalid_input,
                fmt::format("{}: the flange is climbing over the rail (contact at the wheel profile's y_p = {:.2f} "
                            "mm, beyond the flange's steepest point at {:.2f} mm): the lateral displacement lies "
                            "beyond flange contact",
                            where(side, y_m, roll_rad), touch.sample.wheel_profile_y_m / kMm,
                            track.flange_steepest_point_y_m(side) / kMm));
  }
}

RigidWheelContact wheel_contact(const WheelsetTrack& track, WheelSide side, const FirstTouch& touch) {
  RigidWheelContact c;
  c.side = side;
  c.wheel_profile_y_m = touch.sample.wheel_profile_y_m;
  c.wheel_profile_z_m = track.pair(side).wheel().at(touch.wheel_parameter_m).z_m;
  c.rail_profile_y_m = touch.sample.rail_profile_y_m;
  c.rail_profile_z_m = track.pair(side).rail().z(c.rail_profile_y_m);
  c.contact_angle_rad = touch.sample.contact_angle_rad;
  c.rolling_radius_m = touch.sample.rolling_radius_m;
  const double sign = geometry::side_sign(side);
  c.point_track_m = {touch.sample.point_track_m[0], track.rail_profile_origin_y_m(side) + sign * c.rail_profile_y_m,
                     -c.rail_profile_z_m};
  return c;
}

}  // namespace

void validate(const RigidContactOptions& o) {
  require(std::isfinite(o.locus_step_m) && o.locus_step_m >= 1e-6 && o.locus_step_m <= 1e-3, [&] {
    return fmt::format("rigid contact: the locus step {:g} mm must lie in [0.001, 1] mm", o.locus_step_m / kMm);
  });
}

RigidContactGeometry rigid_contact_geometry(const WheelsetTrack& track, double y_m,
                                            const RigidContactOptions& options) {
  validate(options);
  require(std::isfinite(y_m) && std::abs(y_m) <= 0.1, [&] {
    return fmt::format("rigid contact: the lateral displacement y = {:g} mm must be finite and at most 100 mm in size",
                       y_m / kMm);
  });
  // The height at which each wheel touches, at roll φ (vertical displacement 0): minus its smallest gap.
  FirstTouch right, left;
  const auto height_difference = [&](double roll) {
    WheelsetPosition p;
    p.lateral_displacement_m = y_m;
    p.roll_rad = roll;
    right = first_touch(track, WheelSide::right, p, options.locus_step_m);
    left = first_touch(track, WheelSide::left, p, options.locus_step_m);
    // Touching heights z_side = −gap_side: the right wheel's minus the left wheel's. Rolling to the
    // left (φ > 0) lifts the left wheel, so the left wheel's touching height falls and the
    // difference grows with φ by about the distance between the contact points.
    return left.sample.vertical_gap_m - right.sample.vertical_gap_m;
  };
  // Illinois (modified regula falsi) on the roll, from φ = 0 and a step by the slope estimate.
  double a = 0.0, fa = height_difference(0.0);
  double roll = 0.0;
  if (std::abs(fa) > kHeightTolerance_m) {
    const double slope = std::max(0.5, std::abs(right.sample.point_track_m[1]) + std::abs(left.sample.point_track_m[1]));
    double b = -fa / slope, fb = height_difference(b);
    // Expand until the roll is bracketed.
    while ((fa > 0.0) == (fb > 0.0) && std::abs(fb) > kHeightTolerance_m) {
      const double step = b - a;
      a = b;
      fa = fb;
      b = a + 2.0 * step;
      if (!(std::abs(b) <= kMaximumRoll_rad)) {
        throw Error(ErrorKind::invalid_input,
                    fmt::format("rigid contact at y = {:.3f} mm: no roll angle within {:g} mrad lets both wheels touch "
                                "their rails",
                                y_m / kMm, kMaximumRoll_rad * 1e3));
      }
      fb = height_difference(b);
    }
    int iterations = 0;
    while (std::abs(fb) > kHeightTolerance_m && std::abs(b - a) > 1e-13) {
      if (++iterations > 200) {
        throw Error(ErrorKind::not_converged,
                    fmt::format("rigid contact at y = {:.3f} mm: the roll angle did not converge (bracket [{:.6g}, "
                                "{:.6g}] mrad)",
                                y_m / kMm, a * 1e3, b * 1e3));
      }
      const double c = b - fb * (b - a) / (fb - fa);
      const double fc = height_difference(c);
      if ((fc > 0.0) == (fb > 0.0)) {
        fa *= 0.5;
      } else {
        a = b;
        fa = fb;
      }
      b = c;
      fb = fc;
    }
    roll = b;  // right and left hold the last evaluation, which is at b
  }
  check_flange(track, WheelSide::right, right, y_m, roll);
  check_flange(track, WheelSide::left, left, y_m, roll);

  RigidContactGeometry g;
  g.lateral_displacement_m = y_m;
  g.roll_rad = roll;
  // Both gaps are (nearly) equal at the solution: lower the wheelset by the mean.
  g.vertical_displacement_m = -0.5 * (right.sample.vertical_gap_m + left.sample.vertical_gap_m);
  g.right = wheel_contact(track, WheelSide::right, right);
  g.left = wheel_contact(track, WheelSide::left, left);
  g.rolling_radius_difference_m = g.left.rolling_radius_m - g.right.rolling_radius_m;
  return g;
}

std::vector<RigidContactGeometry> rigid_contact_sweep(const WheelsetTrack& track, double y_from_m, double y_to_m,
                                                      double y_step_m, const RigidContactOptions& options) {
  require(std::isfinite(y_from_m) && std::isfinite(y_to_m) && y_from_m < y_to_m, [&] {
    return fmt::format("rigid contact sweep: y from {:g} mm to {:g} mm must be finite and increasing", y_from_m / kMm,
                       y_to_m / kMm);
  });
  require(std::isfinite(y_step_m) && y_step_m > 0.0 && y_step_m <= y_to_m - y_from_m, [&] {
    return fmt::format("rigid contact sweep: the y step {:g} mm must lie in (0, {:g}] mm (the range)", y_step_m / kMm,
                       (y_to_m - y_from_m) / kMm);
  });
  const double span = (y_to_m - y_from_m) / y_step_m;
  require(span < static_cast<double>(kMaximumSweepPositions), [&] {
    return fmt::format("rigid contact sweep: {:.0f} positions asked for (at most {}); use a larger step", span + 1,
                       kMaximumSweepPositions);
  });
  const auto steps = static_cast<long>(std::floor(span + 1e-6));
  std::vector<RigidContactGeometry> sweep;
  sweep.reserve(static_cast<std::size_t>(steps) + 1);
  for (long k = 0; k <= steps; ++k) {
    const double y = k == steps && std::abs(span - static_cast<double>(steps)) < 1e-6
                         ? y_to_m
                         : y_from_m + static_cast<double>(k) * y_step_m;
    sweep.push_back(rigid_contact_geometry(track, y, options));
  }
  return sweep;
}

// --- Δr(y) and the equivalent conicity ---

RollingRadiusDifference::RollingRadiusDifference(std::vector<double> y_m, std::vector<double> delta_r_m)
    : y_m_(std::move(y_m)), delta_r_m_(std::move(delta_r_m)) {
  require(y_m_.size() == delta_r_m_.size() && y_m_.size() >= 3, [&] {
    return fmt::format("rolling-radius difference: {} positions and {} values (at least 3 of each, as many)",
                       y_m_.size(), delta_r_m_.size());
  });
  for (std::size_t k = 0; k < y_m_.size(); ++k) {
    require(std::isfinite(y_m_[k]) && std::isfinite(delta_r_m_[k]) && (k == 0 || y_m_[k] > y_m_[k - 1]), [&] {
      return fmt::format("rolling-radius difference: sample {} (y = {:g} mm, Δr = {:g} mm) must be finite, y "
                         "increasing",
                         k, y_m_[k] / kMm, delta_r_m_[k] / kMm);
    });
  }
  integral_m2_.assign(y_m_.size(), 0.0);
  for (std::size_t k = 1; k < y_m_.size(); ++k)
    integral_m2_[k] = integral_m2_[k - 1] + 0.5 * (delta_r_m_[k] + delta_r_m_[k - 1]) * (y_m_[k] - y_m_[k - 1]);
}

namespace {
std::vector<double> sweep_y(const std::vector<RigidContactGeometry>& sweep) {
  std::vector<double> y;
  y.reserve(sweep.size());
  for (const RigidContactGeometry& g : sweep) y.push_back(g.lateral_displacement_m);
  return y;
}
std::vector<double> sweep_delta_r(const std::vector<RigidContactGeometry>& sweep) {
  std::vector<double> d;
  d.reserve(sweep.size());
  for (const RigidContactGeometry& g : sweep) d.push_back(g.rolling_radius_difference_m);
  return d;
}
}  // namespace

RollingRadiusDifference::RollingRadiusDifference(const std::vector<RigidContactGeometry>& sweep)
    : RollingRadiusDifference(sweep_y(sweep), sweep_delta_r(sweep)) {}

std::size_t RollingRadiusDifference::segment(double y) const {
  require(y >= y_m_.front() - 1e-12 && y <= y_m_.back() + 1e-12, [&] {
    return fmt::format("rolling-radius difference: y = {:g} mm outside the table [{:g}, {:g}] mm", y / kMm,
                       y_m_.front() / kMm, y_m_.back() / kMm);
  });
  const auto it = std::upper_bound(y_m_.begin(), y_m_.end(), y);
  const auto k = static_cast<std::size_t>(std::distance(y_m_.begin(), it));
  return std::clamp<std::size_t>(k, 1, y_m_.size() - 1) - 1;
}

double RollingRadiusDifference::operator()(double y) const {
  const std::size_t k = segment(y);
  const double t = (y - y_m_[k]) / (y_m_[k + 1] - y_m_[k]);
  return delta_r_m_[k] + t * (delta_r_m_[k + 1] - delta_r_m_[k]);
}

double RollingRadiusDifference::integral_m2(double y) const {
  const std::size_t k = segment(y);
  const double d = y - y_m_[k];
  return integral_m2_[k] + 0.5 * (delta_r_m_[k] + (*this)(y)) * d;
}

double RollingRadiusDifference::centre_m() const {
  double best = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t k = 0; k + 1 < y_m_.size(); ++k) {
    const double a = delta_r_m_[k], b = delta_r_m_[k + 1];
    if (!(a <= 0.0 && b > 0.0)) continue;
    const double y = y_m_[k] + (y_m_[k + 1] - y_m_[k]) * (-a) / (b - a);
    if (std::isnan(best) || std::abs(y) < std::abs(best)) best = y;
  }
  if (std::isnan(best)) {
    throw Error(fmt::format("rolling-radius difference: Δr does not rise through zero in y = [{:g}, {:g}] mm (no "
                            "centred running position; the equivalent conicity needs one)",
                            y_m_.front() / kMm, y_m_.back() / kMm));
  }
  return best;
}

namespace {

// The turning points of the kinematic motion of amplitude ŷ: y_low, y_high = y_low + 2ŷ with equal
// potential V; false when they do not lie in the table.
bool turning_points(const RollingRadiusDifference& d, double centre, double amplitude, double& low, double& high) {
  const double span = 2.0 * amplitude;
  const double hi = std::min(centre + span, d.y_max_m());
  double lo = std::max(centre, d.y_min_m() + span);
  if (!(lo <= hi + 1e-12)) return false;  // (rounding of y_min + 2ŷ at the largest amplitude)
  lo = std::min(lo, hi);
  const auto g = [&](double y_high) {
    return d.integral_m2(y_high) - d.integral_m2(std::max(y_high - span, d.y_min_m()));
  };
  double a = lo, b = hi, ga = g(a), gb = g(b);
  // Rounding: the potential differences of a symmetric Δr at the largest amplitude are zero only
  // to a few ulp of the potential.
  const double tolerance = 1e-9 * (std::abs(d.integral_m2(centre)) + std::abs(d.integral_m2(d.y_max_m())));
  if (ga > tolerance || gb < -tolerance) return false;
  if (ga > 0.0) b = a;
  if (gb < 0.0) a = b;
  for (int i = 0; i < 200 && b - a > 1e-13; ++i) {
    const double m = 0.5 * (a + b), gm = g(m);
    if (gm < 0.0) {
      a = m;
      ga = gm;
    } else {
      b = m;
      gb = gm;
    }
  }
  high = 0.5 * (a + b);
  low = high - span;
  return true;
}

bool regression_fits(const RollingRadiusDifference& d, double centre, double amplitude) {
  return centre - amplitude >= d.y_min_m() - 1e-12 && centre + amplitude <= d.y_max_m() + 1e-12;
}

}  // namespace

double largest_conicity_amplitude_m(const RollingRadiusDifference& d) {
  double centre = 0.0;
  try {
    centre = d.centre_m();
  } catch (const Error&) {
    return 0.0;
  }
  const auto fits = [&](double amplitude) {
    double low = 0.0, high = 0.0;
    return regression_fits(d, centre, amplitude) && turning_points(d, centre, amplitude, low, high);
  };
  double a = 0.0, b = 0.5 * (d.y_max_m() - d.y_min_m());
  if (fits(b)) return b;
  for (int i = 0; i < 60; ++i) {
    const double m = 0.5 * (a + b);
    (fits(m) ? a : b) = m;
  }
  return a;
}

EquivalentConicity equivalent_conicity(const RollingRadiusDifference& d, double amplitude_m,
                                       const EquivalentConicityOptions& options) {
  require(options.integration_points >= 100 && options.integration_points <= 10000000, [&] {
    return fmt::format("equivalent conicity: {} integration points (allowed: 100 to 10000000)",
                       options.integration_points);
  });
  const double largest = largest_conicity_amplitude_m(d);
  // The largest amplitude is found by bisection to rounding: an amplitude within 1 nm above it (e.g.
  // 6 mm on a sweep of ±6 mm, whose bisection may end a few ulp short of 6 mm without FMA) is that
  // amplitude.
  constexpr double kAmplitudeTolerance_m = 1e-9;
  require(std::isfinite(amplitude_m) && amplitude_m > 0.0 && amplitude_m <= largest + kAmplitudeTolerance_m, [&] {
    return fmt::format("equivalent conicity: the amplitude {:g} mm must lie in (0, {:.3f}] mm (the motion must stay "
                       "within the tabulated Δr, y = [{:g}, {:g}] mm)",
                       amplitude_m / kMm, largest / kMm, d.y_min_m() / kMm, d.y_max_m() / kMm);
  });
  EquivalentConicity e;
  e.amplitude_m = amplitude_m;
  e.centre_m = d.centre_m();
  const int n = options.integration_points;
  amplitude_m = std::min(amplitude_m, largest);

  // The wavelength: y = m + ŷ sin θ over the half-wave θ in (−π/2, π/2); the integrand
  // ŷ cos θ / sqrt(E − V(y)) stays finite at the turning points (where V' = Δr ≠ 0).
  double low = 0.0, high = 0.0;
  if (!turning_points(d, e.centre_m, amplitude_m, low, high)) {
    throw Error(fmt::format("equivalent conicity: no kinematic motion of amplitude {:g} mm within the tabulated Δr",
                            amplitude_m / kMm));
  }
  e.turning_point_low_m = low;
  e.turning_point_high_m = high;
  const double middle = 0.5 * (low + high);
  const double energy = 0.5 * (d.integral_m2(low) + d.integral_m2(high));
  double integral = 0.0;
  const double h = std::numbers::pi / n;
  for (int k = 0; k < n; ++k) {
    const double theta = -0.5 * std::numbers::pi + (k + 0.5) * h;
    const double y = middle + amplitude_m * std::sin(theta);
    const double kinetic = energy - d.integral_m2(y);
    if (!(kinetic > 0.0)) {
      throw Error(fmt::format("equivalent conicity at amplitude {:g} mm: Δr(y) is not increasing enough between the "
                              "turning points {:.3f} and {:.3f} mm (the kinematic motion has no single wavelength)",
                              amplitude_m / kMm, low / kMm, high / kMm));
    }
    integral += amplitude_m * std::cos(theta) / std::sqrt(kinetic) * h;
  }
  e.tan_gamma_e_wavelength = std::numbers::pi * std::numbers::pi / (integral * integral);

  // The regression over one cycle, uniform in phase.
  double sum_y = 0.0, sum_d = 0.0, sum_yy = 0.0, sum_yd = 0.0;
  const double h2 = 2.0 * std::numbers::pi / n;
  for (int k = 0; k < n; ++k) {
    const double y = std::clamp(e.centre_m + amplitude_m * std::sin((k + 0.5) * h2), d.y_min_m(), d.y_max_m());
    const double delta = d(y);
    sum_y += y;
    sum_d += delta;
    sum_yy += y * y;
    sum_yd += y * delta;
  }
  const double mean_y = sum_y / n, mean_d = sum_d / n;
  const double slope = (sum_yd / n - mean_y * mean_d) / (sum_yy / n - mean_y * mean_y);
  e.tan_gamma_e_regression = 0.5 * slope;
  return e;
}

double klingel_wavelength_m(double tan_gamma_e, double half_contact_distance_m, double rolling_radius_m) {
  require(tan_gamma_e > 0.0 && half_contact_distance_m > 0.0 && rolling_radius_m > 0.0,
          "Klingel wavelength: tan γe, e0 and r0 must be positive");
  return 2.0 * std::numbers::pi * std::sqrt(half_contact_distance_m * rolling_radius_m / tan_gamma_e);
}

}  // namespace railcontact
