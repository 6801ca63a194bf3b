// Plausibility of a profile's point list (docs/GEOMETRY.md §8, docs/RELIABILITY.md "Input files"):
// what every reader and every SmoothProfile checks before a spline is built, so that a shuffled,
// repeated, crossing, huge or tiny point list (or one in the wrong length unit) is refused with a
// message instead of giving a wrong contact or an endless computation.
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "geometry/profile_text.hpp"
#include "railcontact/error.hpp"
#include "railcontact/geometry.hpp"

namespace railcontact::geometry {

namespace {

constexpr double kMm = 1e-3;

std::string name_of(const Profile& profile) {
  return profile.source.empty() ? std::string("(unnamed)") : profile.source;
}

std::string point_at(const Profile& p, std::size_t i) {
  return fmt::format("y = {:.4f} mm, z = {:.4f} mm", p.y_m[i] / kMm, p.z_m[i] / kMm);
}

// "; metres read as millimetres? (hint)" when the span would be plausible in the other unit.
std::string unit_suggestion(double span_m, double low_m, double high_m, std::string_view unit_hint) {
  const std::string hint = unit_hint.empty() ? std::string() : fmt::format(" ({})", unit_hint);
  if (span_m * 1e3 >= low_m && span_m * 1e3 <= high_m) return "; are metres read as millimetres?" + hint;
  if (span_m * 1e-3 >= low_m && span_m * 1e-3 <= high_m) return "; are millimetres read as metres?" + hint;
  return hint;
}

double orientation(const Profile& p, std::size_t a, std::size_t b, std::size_t c) {
  return (p.y_m[b] - p.y_m[a]) * (p.z_m[c] - p.z_m[a]) - (p.z_m[b] - p.z_m[a]) * (p.y_m[c] - p.y_m[a]);
}

// Point c, collinear with segment a-b, lies within its bounding box.
bool within(const Profile& p, std::size_t a, std::size_t b, std::size_t c) {
  return std::min(p.y_m[a], p.y_m[b]) <= p.y_m[c] && p.y_m[c] <= std::max(p.y_m[a], p.y_m[b]) &&
         std::min(p.z_m[a], p.z_m[b]) <= p.z_m[c] && p.z_m[c] <= std::max(p.z_m[a], p.z_m[b]);
}

// Segments i-(i+1) and j-(j+1) touch or cross (collinear overlaps included).
bool segments_meet(const Profile& p, std::size_t i, std::size_t j) {
  const double d1 = orientation(p, j, j + 1, i), d2 = orientation(p, j, j + 1, i + 1);
  const double d3 = orientation(p, i, i + 1, j), d4 = orientation(p, i, i + 1, j + 1);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  return (d1 == 0 && within(p, j, j + 1, i)) || (d2 == 0 && within(p, j, j + 1, i + 1)) ||
         (d3 == 0 && within(p, i, i + 1, j)) || (d4 == 0 && within(p, i, i + 1, j + 1));
}

void check_extent(const Profile& p, const std::string& name, std::string_view unit_hint) {
  const auto y_range = std::minmax_element(p.y_m.begin(), p.y_m.end());
  const auto z_range = std::minmax_element(p.z_m.begin(), p.z_m.end());
  const double width = *y_range.second - *y_range.first, height = *z_range.second - *z_range.first;
  const auto i_top = static_cast<std::size_t>(z_range.first - p.z_m.begin());
  const auto i_bottom = static_cast<std::size_t>(z_range.second - p.z_m.begin());
  require(width >= ProfileLimits::min_lateral_extent_m && width <= ProfileLimits::max_lateral_extent_m, [&] {
    return fmt::format("profile {}: the points span {:.4g} mm laterally (y); a wheel or rail profile spans {:g} to {:g} mm{}",
                       name, width / kMm, ProfileLimits::min_lateral_extent_m / kMm,
                       ProfileLimits::max_lateral_extent_m / kMm,
                       unit_suggestion(width, ProfileLimits::min_lateral_extent_m, ProfileLimits::max_lateral_extent_m,
                                       unit_hint));
  });
  // (The lateral span is plausible here, so a wrong unit is not the cause: name the extremes.)
  require(height <= ProfileLimits::max_vertical_extent_m, [&] {
    return fmt::format(
        "profile {}: the points span {:.4g} mm vertically (z), from point {} ({}) to point {} ({}); a wheel or rail "
        "profile spans at most {:g} mm",
        name, height / kMm, i_top + 1, point_at(p, i_top), i_bottom + 1, point_at(p, i_bottom),
        ProfileLimits::max_vertical_extent_m / kMm);
  });
}

// Consecutive points: distinct, at most max_point_gap apart, a bounded length.
void check_spacing(const Profile& p, const std::string& name) {
  double length = 0.0;
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    const double gap = std::hypot(p.y_m[i + 1] - p.y_m[i], p.z_m[i + 1] - p.z_m[i]);
    require(gap > ProfileLimits::coincident_m, [&] {
      return fmt::format("profile {}: points {} and {} coincide ({}); remove the repeated point", name, i + 1, i + 2,
                         point_at(p, i));
    });
    require(gap <= ProfileLimits::max_point_gap_m, [&] {
      return fmt::format(
          "profile {}: points {} and {} are {:.4g} mm apart ({} and {}); consecutive points must be at most {:g} mm "
          "apart: are the points in order along the profile?",
          name, i + 1, i + 2, gap / kMm, point_at(p, i), point_at(p, i + 1), ProfileLimits::max_point_gap_m / kMm);
    });
    length += gap;
  }
  require(length <= ProfileLimits::max_length_m, [&] {
    return fmt::format("profile {}: the points make a curve {:.4g} mm long; a wheel or rail profile is at most {:g} mm "
                       "long: are the points in order along the profile?",
                       name, length / kMm, ProfileLimits::max_length_m / kMm);
  });
}

// No reversal of direction (more than 150 degrees) at a point.
void check_turns(const Profile& p, const std::string& name) {
  for (std::size_t i = 1; i + 1 < p.size(); ++i) {
    const double cosine = turn_cosine(p, i);
    require(cosine >= ProfileLimits::min_turn_cosine, [&] {
      return fmt::format(
          "profile {}: the points turn back at point {} ({}; the direction turns by {:.0f} degrees, at most {:.0f}): "
          "are the points in order along the profile?",
          name, i + 1, point_at(p, i), std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / M_PI,
          std::acos(ProfileLimits::min_turn_cosine) * 180.0 / M_PI);
    });
  }
}

// No two non-adjacent segments of the polyline meet: a sweep over the segments sorted by their
// smallest y, comparing each with those that overlap it laterally (a handful for a profile, which
// is nearly a graph z(y)); the number of comparisons is bounded.
void check_no_crossing(const Profile& p, const std::string& name) {
  struct Segment {
    double y_lo, y_hi;
    std::size_t i;
  };
  std::vector<Segment> segments;
  segments.reserve(p.size() - 1);
  for (std::size_t i = 0; i + 1 < p.size(); ++i)
    segments.push_back({std::min(p.y_m[i], p.y_m[i + 1]), std::max(p.y_m[i], p.y_m[i + 1]), i});
  std::sort(segments.begin(), segments.end(), [](const Segment& a, const Segment& b) { return a.y_lo < b.y_lo; });
  std::size_t comparisons = 0;
  for (std::size_t a = 0; a < segments.size(); ++a) {
    for (std::size_t b = a + 1; b < segments.size() && segments[b].y_lo <= segments[a].y_hi; ++b) {
      require(++comparisons <= ProfileLimits::max_crossing_comparisons, [&] {
        return fmt::format(
            "profile {}: {} points whose segments overlap laterally more than {} times: too convoluted for a wheel or "
            "rail profile (a simple curve)",
            name, p.size(), ProfileLimits::max_crossing_comparisons);
      });
      const std::size_t i = std::min(segments[a].i, segments[b].i), j = std::max(segments[a].i, segments[b].i);
      if (j - i < 2 || !segments_meet(p, i, j)) continue;
      throw Error(fmt::format(
          "profile {}: the profile crosses itself: the segment from point {} to {} meets the one from point {} to {} "
          "(near {}): are the points in order along the profile?",
          name, i + 1, i + 2, j + 1, j + 2, point_at(p, j)));
    }
  }
}

// The points go one way laterally (from the first point's y towards the last's), back by at most
// max_lateral_retreat_m: the contact search's graph z(y) (SmoothProfile::z) holds each y once, and
// the part of an undercut profile that overhangs would be missing from it (a wheel in contact there
// would seem to carry no load). The message names the overhang: the point where the points turn
// back laterally and the one furthest back (the largest y_j - y_i over j < i, direction-adjusted).
void check_single_valued(const Profile& p, const std::string& name) {
  const double direction = p.y_m.back() >= p.y_m.front() ? 1.0 : -1.0;
  std::size_t furthest = 0;  // the point furthest along so far
  double retreat = 0.0;
  std::size_t from = 0, to = 0;
  for (std::size_t i = 1; i < p.size(); ++i) {
    if (direction * (p.y_m[i] - p.y_m[furthest]) > 0.0) furthest = i;
    const double back = direction * (p.y_m[furthest] - p.y_m[i]);
    if (back > retreat) {
      retreat = back;
      from = furthest;
      to = i;
    }
  }
  require(retreat <= ProfileLimits::max_lateral_retreat_m, [&] {
    return fmt::format(
        "profile {}: the profile is undercut: between point {} ({}) and point {} ({}) it overhangs by {:.3g} mm "
        "laterally; the contact search takes a profile as z(y), each y once (an overhang of at most {:g} mm): remove "
        "the undercut part or give a profile that is not undercut",
        name, from + 1, point_at(p, from), to + 1, point_at(p, to), retreat / kMm, ProfileLimits::max_lateral_retreat_m / kMm);
  });
}

}  // namespace

double turn_cosine(const Profile& p, std::size_t i) {
  const double ay = p.y_m[i] - p.y_m[i - 1], az = p.z_m[i] - p.z_m[i - 1];
  const double by = p.y_m[i + 1] - p.y_m[i], bz = p.z_m[i + 1] - p.z_m[i];
  const double norms = std::hypot(ay, az) * std::hypot(by, bz);
  return norms > 0.0 ? (ay * by + az * bz) / norms : 1.0;
}

double largest_lateral_retreat_m(const Profile& p) {
  const double direction = p.y_m.back() >= p.y_m.front() ? 1.0 : -1.0;
  std::size_t furthest = 0;
  double retreat = 0.0;
  for (std::size_t i = 1; i < p.size(); ++i) {
    if (direction * (p.y_m[i] - p.y_m[furthest]) > 0.0) furthest = i;
    retreat = std::max(retreat, direction * (p.y_m[furthest] - p.y_m[i]));
  }
  return retreat;
}

void check_profile(const Profile& profile, std::string_view unit_hint, ProfileCheckScope scope) {
  const std::string name = name_of(profile);
  require(profile.y_m.size() == profile.z_m.size(), [&] {
    return fmt::format("profile {}: {} y values but {} z values", name, profile.y_m.size(), profile.z_m.size());
  });
  require(profile.size() >= 4,
          [&] { return fmt::format("profile {}: {} points; at least 4 are needed", name, profile.size()); });
  require(profile.size() <= ProfileLimits::max_points, [&] {
    return fmt::format("profile {}: {} points; at most {} are accepted (a wheel or rail profile needs a few thousand)",
                       name, profile.size(), ProfileLimits::max_points);
  });
  for (std::size_t i = 0; i < profile.size(); ++i) {
    require(std::isfinite(profile.y_m[i]) && std::isfinite(profile.z_m[i]),
            [&] { return fmt::format("profile {}: point {} is not finite", name, i + 1); });
  }
  check_extent(profile, name, unit_hint);
  check_spacing(profile, name);
  check_no_crossing(profile, name);
  if (scope == ProfileCheckScope::points) return;
  check_turns(profile, name);
  check_single_valued(profile, name);
}

std::string length_unit_hint(double length_unit_m) {
  if (length_unit_m == 1e-3) return "the numbers are read as millimetres";
  if (length_unit_m == 1.0) return "the numbers are read as metres";
  return fmt::format("the numbers are read in units of {:g} m", length_unit_m);
}

}  // namespace railcontact::geometry
