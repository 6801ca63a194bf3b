// Wheelset on the track and the point of first touch of one wheel–rail pair (the right wheel on
// the right rail): docs/GEOMETRY.md §2–3.
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "geometry/root_finding.hpp"
#include "railcontact/error.hpp"
#include "railcontact/geometry.hpp"

namespace railcontact {

namespace {

constexpr double kScanStep_m = 0.05e-3;        // lateral scan of the vertical gap
constexpr double kSecondaryDistance_m = 1e-3;  // a second minimum must lie this far away

// Lowest z_p (highest point) of a profile, sampled then refined on the slope dz/ds = 0.
double lowest_z_parameter(const SmoothProfile& profile) {
  const int samples = 4000;
  const double s0 = profile.s_begin_m(), s1 = profile.s_end_m();
  const double ds = (s1 - s0) / samples;
  int best = 0;
  double best_z = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= samples; ++k) {
    const double z = profile.at(s0 + k * ds).z_m;
    if (z < best_z) {
      best_z = z;
      best = k;
    }
  }
  if (best == 0 || best == samples) return s0 + best * ds;
  const auto root = geometry::bracketed_root([&](double s) { return profile.at(s).dz_ds; }, s0 + (best - 1) * ds,
                                             s0 + (best + 1) * ds, "the highest point of a profile");
  return root ? *root : s0 + best * ds;
}

// First parameter, searching from the start of the curve (from_start) or from its end, where the
// curve rises to z_p = level (z_p points down); nothing if it never gets that high.
std::optional<double> crossing_from_end(const SmoothProfile& profile, double level, bool from_start) {
  const int samples = 4000;
  const double s0 = profile.s_begin_m(), s1 = profile.s_end_m();
  const double ds = (s1 - s0) / samples;
  const auto s_at = [&](int k) { return from_start ? s0 + k * ds : s1 - k * ds; };
  if (profile.at(s_at(0)).z_m < level) return std::nullopt;
  for (int k = 1; k <= samples; ++k) {
    if (profile.at(s_at(k)).z_m <= level) {
      return geometry::bracketed_root([&](double s) { return profile.at(s).z_m - level; }, s_at(k - 1), s_at(k),
                                      "the crossing of a profile with a level");
    }
  }
  return std::nullopt;
}

}  // namespace

const char* nominal_radius_datum_name(NominalRadiusDatum datum) {
  return datum == NominalRadiusDatum::profile_origin ? "profile-origin" : "taping-line";
}

NominalRadiusDatum parse_nominal_radius_datum(const std::string& name) {
  for (NominalRadiusDatum d : {NominalRadiusDatum::profile_origin, NominalRadiusDatum::taping_line})
    if (name == nominal_radius_datum_name(d)) return d;
  throw Error(fmt::format("nominal_radius_at = \"{}\" is not a datum of the nominal rolling radius (allowed: "
                          "\"profile-origin\", the default, as in CONTACT; \"taping-line\")",
                          name));
}

void validate_rail_cant(double cant_rad, std::string_view name) {
  if (std::isfinite(cant_rad) && std::abs(cant_rad) <= kMaximumRailCant_rad) return;
  // A rail inclination is quoted as a ratio 1:n: a value n in [10, 100] is such a denominator, a
  // value up to 0.1 rad in degrees (5.73) an angle in degrees.
  const double magnitude = std::abs(cant_rad);
  constexpr double kDegree_rad = 0.017453292519943295;
  std::string hint;
  if (std::isfinite(magnitude) && magnitude >= 10.0 && magnitude <= 100.0) {
    hint = fmt::format("; the value is an angle in radians: an inclination 1:{0:g} is atan(1/{0:g}) = {1:.6g} rad",
                       magnitude, std::copysign(std::atan(1.0 / magnitude), cant_rad));
  } else if (std::isfinite(magnitude) && magnitude * kDegree_rad <= kMaximumRailCant_rad) {
    hint = fmt::format("; the value is in radians: {:g} degrees would be {:.6g} rad", cant_rad, cant_rad * kDegree_rad);
  } else {
    hint = "; 1:40 is atan(1/40) = 0.0249948 rad";
  }
  throw Error(fmt::format("{} = {:g} rad must lie in [{:g}, {:g}] rad (the rail inclinations in use are 0, 1:40, 1:30 "
                          "and 1:20; positive leans the rail's top towards the track centre){}",
                          name, cant_rad, -kMaximumRailCant_rad, kMaximumRailCant_rad, hint));
}

void validate(const TrackWheelsetParameters& p, std::string_view prefix) {
  const auto check = [&](double value, const char* field, double low, double high, const char* reason) {
    if (std::isfinite(value) && value >= low && value <= high) return;
    const bool in_mm = value > high && value * 1e-3 >= low && value * 1e-3 <= high;
    throw Error(fmt::format("{}{} = {:g} m must lie in [{:g}, {:g}] m ({}){}", prefix, field, value, low, high, reason,
                            in_mm ? fmt::format("; the value is in metres: {:g} mm would be {:g} m", value, value * 1e-3)
                                  : std::string()));
  };
  check(p.track_gauge_m, "track_gauge_m", kMinimumTrackGauge_m, kMaximumTrackGauge_m,
        "from the 15-inch minimum gauge to Brunel's broad gauge; 1.435 standard");
  check(p.gauge_measuring_depth_m, "gauge_measuring_depth_m", kMinimumGaugeMeasuringDepth_m,
        kMaximumGaugeMeasuringDepth_m, "within the rail head's gauge corner; 0.014 in EN 13848");
  check(p.flange_back_distance_m, "flange_back_distance_m", kMinimumFlangeBackDistance_m, kMaximumFlangeBackDistance_m,
        "between the wheels' flange backs; 1.360 on standard gauge");
  check(p.flange_back_y_m, "flange_back_y_m", -kMaximumFlangeBackPosition_m, kMaximumFlangeBackPosition_m,
        "a position in the wheel profile frame, within the profile");
  check(p.taping_line_from_flange_back_m, "taping_line_from_flange_back_m", kMinimumTapingLineFromFlangeBack_m,
        kMaximumTapingLineFromFlangeBack_m, "on the wheel's tread; 0.070 on a UIC wheel");
  check(p.nominal_rolling_radius_m, "nominal_rolling_radius_m", kMinimumNominalRollingRadius_m,
        kMaximumNominalRollingRadius_m, "from a scale roller-rig wheel to a locomotive's driving wheel; 0.46 for a UIC wheel");
  validate_rail_cant(p.rail_cant_rad, fmt::format("{}rail_cant_rad", prefix));
  const double play = p.track_gauge_m - p.flange_back_distance_m;
  require(play >= kMinimumGaugeMinusFlangeBack_m && play <= kMaximumGaugeMinusFlangeBack_m, [&] {
    return fmt::format("{}track_gauge_m - flange_back_distance_m = {:g} - {:g} = {:g} m must lie in [{:g}, {:g}] m (two "
                       "flanges and their play: 0.075 on standard gauge)",
                       prefix, p.track_gauge_m, p.flange_back_distance_m, play, kMinimumGaugeMinusFlangeBack_m,
                       kMaximumGaugeMinusFlangeBack_m);
  });
}

Profile canted_rail_profile(Profile rail, double cant_rad) {
  validate_rail_cant(cant_rad, "rail cant");
  if (cant_rad == 0.0) return rail;
  const double c = std::cos(cant_rad), s = std::sin(cant_rad);
  for (std::size_t i = 0; i < rail.y_m.size() && i < rail.z_m.size(); ++i) {
    const double y = rail.y_m[i], z = rail.z_m[i];
    rail.y_m[i] = c * y + s * z;
    rail.z_m[i] = -s * y + c * z;
  }
  return rail;
}

namespace {

// The rail profile as the pair uses it: the parameters checked first (a bad cant is named as the
// parameter, not as the profile), then canted.
Profile rail_on_track(const Profile& rail, const TrackWheelsetParameters& parameters) {
  validate(parameters);
  return canted_rail_profile(rail, parameters.rail_cant_rad);
}

}  // namespace

WheelRailPair::WheelRailPair(const Profile& wheel, const Profile& rail, const TrackWheelsetParameters& parameters,
                             const SmoothingOptions& smoothing)
    : wheel_(wheel, smoothing), rail_(rail_on_track(rail, parameters), smoothing), parameters_(parameters) {
  require(wheel.kind != ProfileKind::rail,
          [&] { return fmt::format("wheel profile {} is a rail profile", wheel.source); });
  require(rail.kind != ProfileKind::wheel,
          [&] { return fmt::format("rail profile {} is a wheel profile", rail.source); });

  // Wheel: taping line, and the flange on the side of negative y.
  taping_y_m_ = parameters_.flange_back_y_m + parameters_.taping_line_from_flange_back_m;
  require(taping_y_m_ > wheel_.y_min_m() && taping_y_m_ < wheel_.y_max_m(), [&] {
    // A measured profile (MiniProf) has its origin at the flange back, where it starts.
    return fmt::format(
        "wheel profile {}: the taping line y = {:.3f} mm (flange_back_y_m {:g} m + taping_line_from_flange_back_m {:g} "
        "m) lies outside the profile [{:.3f}, {:.3f}] mm; flange_back_y_m is where the flange back lies in the "
        "profile's coordinates: a profile measured from its flange back (MiniProf) has flange_back_y_m = 0, one drawn "
        "from its taping line -0.070",
        wheel.source, taping_y_m_ * 1e3, parameters_.flange_back_y_m, parameters_.taping_line_from_flange_back_m,
        wheel_.y_min_m() * 1e3, wheel_.y_max_m() * 1e3);
  });
  taping_z_m_ = wheel_.z(taping_y_m_);
  {
    const auto flange_tip = std::max_element(wheel.z_m.begin(), wheel.z_m.end());
    const double flange_tip_y = wheel.y_m[static_cast<std::size_t>(flange_tip - wheel.z_m.begin())];
    require(flange_tip_y<taping_y_m_&& * flange_tip> taping_z_m_, [&] {
      return fmt::format(
          "wheel profile {}: the flange (largest z, z pointing down) must lie at y < {:.1f} mm; "
          "mirror the profile (y -> -y or z -> -z; in a SIMPACK file: mirror.y = 1 or mirror.z = 1; in a "
          "text profile: negate that column)",
          wheel.source, taping_y_m_ * 1e3);
    });
  }

  // Rail: top (lowest z_p), gauge point on the side of negative y.
  const double s_top = lowest_z_parameter(rail_);
  require(s_top > rail_.s_begin_m() && s_top < rail_.s_end_m(), [&] {
    return fmt::format(
        "rail profile {}: the highest point lies at an end of the profile; z must point down "
        "(mirror z: in a SIMPACK file mirror.z = 1; in a text profile negate the z column)",
        rail.source);
  });
  const auto top = rail_.at(s_top);
  rail_top_z_m_ = top.z_m;
  const double gauge_level = rail_top_z_m_ + parameters_.gauge_measuring_depth_m;
  const auto s_gauge = crossing_from_end(rail_, gauge_level, true);
  require(s_gauge.has_value(), [&] {
    return fmt::format("rail profile {}: the gauge side (y < top) does not reach {:.1f} mm below the top of the rail",
                       rail.source, parameters_.gauge_measuring_depth_m * 1e3);
  });
  rail_gauge_y_m_ = rail_.at(*s_gauge).y_m;
  // Rails are inclined towards the track centre, which moves their highest point towards the
  // field side of the head (on the R300 crown by 7.5 mm at 1:40, 10 mm at 1:30, 15 mm at 1:20): a
  // top clearly on the gauge side means a mirrored profile. Side wear on the gauge face moves the
  // head's centre at the gauge depth towards the field side by half the wear, so that the top of
  // an upright worn rail lies on the gauge side of it (1.0 mm with 2 mm of side wear): up to
  // kLargestTopToGaugeSide_m (8 mm of side wear) is accepted, and a mirrored rail inclined 1:40
  // (its top 7.9 mm on the gauge side) is refused unless it was worn by more than 7.7 mm.
  constexpr double kLargestTopToGaugeSide_m = 4e-3;
  if (const auto s_field = crossing_from_end(rail_, gauge_level, false)) {
    const double head_centre_y = 0.5 * (rail_gauge_y_m_ + rail_.at(*s_field).y_m);
    require(top.y_m > head_centre_y - kLargestTopToGaugeSide_m, [&] {
      return fmt::format(
          "rail profile {}: the top lies {:.1f} mm on the -y side of the head centre; the gauge side "
          "must be at -y (mirror y: in a SIMPACK file mirror.y = 1; in a text profile negate the y column)",
          rail.source, (head_centre_y - top.y_m) * 1e3);
    });
  }

  wheel_origin_lateral_m_ = 0.5 * parameters_.flange_back_distance_m - parameters_.flange_back_y_m;
  rail_origin_lateral_m_ = 0.5 * parameters_.track_gauge_m - rail_gauge_y_m_;
}

double WheelRailPair::wheel_radius_m(double y_wheel_m) const {
  return parameters_.nominal_rolling_radius_m + wheel_.z(y_wheel_m) - nominal_radius_z_m();
}

WheelRailContactPoint WheelRailPair::contact_point(double lateral_displacement_m) const {
  require(std::isfinite(lateral_displacement_m), "wheel-rail contact: the lateral displacement must be finite");
  const double offset = wheel_origin_lateral_m_ - rail_origin_lateral_m_ - lateral_displacement_m;
  const double y_lo = std::max(rail_.y_min_m(), wheel_.y_min_m() + offset);
  const double y_hi = std::min(rail_.y_max_m(), wheel_.y_max_m() + offset);
  const auto never_touch = [&](const std::string& why) {
    return Error(ErrorKind::no_contact, fmt::format("wheel-rail contact: the wheel and rail profiles never touch at lateral displacement "
                             "y = {:.3f} mm ({})",
                             lateral_displacement_m * 1e3, why));
  };
  if (!(y_hi - y_lo > 4 * kScanStep_m)) throw never_touch("they do not overlap laterally");

  const auto gap = [&](double y) { return rail_.z(y) - wheel_.z(y - offset); };
  const auto gap_slope = [&](double y) { return rail_.dz_dy(y) - wheel_.dz_dy(y - offset); };

  const int n = static_cast<int>(std::floor((y_hi - y_lo) / kScanStep_m));
  const double step = (y_hi - y_lo) / n;
  std::vector<double> g(static_cast<std::size_t>(n) + 1);
  for (int k = 0; k <= n; ++k) g[static_cast<std::size_t>(k)] = gap(y_lo + k * step);
  const auto g_min_it = std::min_element(g.begin(), g.end());
  const auto k_min = static_cast<int>(g_min_it - g.begin());
  if (k_min == 0 || k_min == n) {
    throw never_touch(fmt::format("first touch at the end of a profile, y_rail = {:.3f} mm, without a common tangent",
                                  (y_lo + k_min * step) * 1e3));
  }

  // Refine the local minima of the scan near the lowest one: common tangent, g'(y) = 0.
  struct Minimum {
    double y_m;
    double gap_m;
  };
  std::vector<Minimum> minima;
  const double candidate_band = *g_min_it + 2e-3;
  for (int k = 1; k < n; ++k) {
    const auto i = static_cast<std::size_t>(k);
    if (!(g[i] <= g[i - 1] && g[i] <= g[i + 1] && g[i] < candidate_band)) continue;
    const double a = y_lo + (k - 1) * step, b = y_lo + (k + 1) * step;
    double y = y_lo + k * step;
    if (const auto root = geometry::bracketed_root(gap_slope, a, b, "the common tangent (gap slope zero)")) {
      y = *root;
    }
    minima.push_back({y, gap(y)});
  }
  const auto best = std::min_element(minima.begin(), minima.end(),
                                     [](const Minimum& p, const Minimum& q) { return p.gap_m < q.gap_m; });
  const double y_c = best->y_m;
  const double drop = best->gap_m;

  WheelRailContactPoint c;
  c.lateral_displacement_m = lateral_displacement_m;
  c.wheel_to_rail_offset_m = offset;
  c.wheel_drop_m = drop;
  c.y_rail_m = y_c;
  c.z_rail_m = rail_.z(y_c);
  c.y_wheel_m = y_c - offset;
  c.z_wheel_m = wheel_.z(c.y_wheel_m);
  c.y_track_m = -(rail_origin_lateral_m_ + y_c);
  c.contact_angle_rad = std::atan(-rail_.dz_dy(y_c));
  c.rolling_radius_m = parameters_.nominal_rolling_radius_m + c.z_wheel_m - nominal_radius_z_m();
  c.rail_curvature_per_m = rail_.curvature_per_m(y_c);
  c.wheel_curvature_per_m = wheel_.curvature_per_m(c.y_wheel_m);
  const double cos_g = std::cos(c.contact_angle_rad), sin_g = std::sin(c.contact_angle_rad);
  c.A_per_m = cos_g / (2.0 * c.rolling_radius_m);
  c.B_per_m = 0.5 * (c.rail_curvature_per_m - c.wheel_curvature_per_m);
  c.x2_axis_track = {0.0, cos_g, -sin_g};
  c.x3_axis_track = {0.0, sin_g, cos_g};
  c.secondary_gap_m = std::numeric_limits<double>::infinity();
  c.secondary_y_rail_m = std::numeric_limits<double>::quiet_NaN();
  for (const auto& m : minima) {
    if (std::abs(m.y_m - y_c) > kSecondaryDistance_m && m.gap_m - drop < c.secondary_gap_m) {
      c.secondary_gap_m = m.gap_m - drop;
      c.secondary_y_rail_m = m.y_m;
    }
  }
  return c;
}

}  // namespace railcontact
