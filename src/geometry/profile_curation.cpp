// Curation of a measured profile's point list before the checks (docs/GEOMETRY.md §8 "Measured
// profiles"): the two faults a measurement brings that a z(y) contact search cannot take, repaired
// where the repair is unambiguous and reported, so that the profile that is used can be told from
// the one that was read.
//
// 1. Zig-zags: a point stitched twice with a small offset where two measured sections meet, seen as
//    two consecutive points at which the direction turns back by more than 150 degrees; the two
//    points are replaced by their mean (as Kalker's CONTACT does with its default threshold 5π/6).
// 2. Undercuts: parts of the profile that fold back laterally (a measured flange tip, the back face
//    of a flange, a wheel's field-side chamfer, an overhanging worn gauge corner). The contact search
//    sees a profile as a graph z(y); the other body approaches from one side (the rail from below
//    the wheel, the wheel from above the rail), so the surface it can touch is the profile's
//    envelope on that side: at each y the point nearest to it. The hidden points are dropped; where
//    the envelope jumps from one branch to another, a vertical step joins them.
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "geometry/profile_text.hpp"
#include "railcontact/error.hpp"
#include "railcontact/geometry.hpp"

namespace railcontact {

namespace {

constexpr double kMm = 1e-3;

// Replaces each zig-zag pair (points i and i+1 both turning back by more than the threshold) by
// the pair's mean; returns the number of pairs replaced.
int repair_zigzags(Profile& p) {
  int repaired = 0;
  std::size_t i = 1;
  while (p.size() >= 4 && i + 2 < p.size()) {
    if (geometry::turn_cosine(p, i) < ProfileLimits::min_turn_cosine && geometry::turn_cosine(p, i + 1) < ProfileLimits::min_turn_cosine) {
      p.y_m[i] = 0.5 * (p.y_m[i] + p.y_m[i + 1]);
      p.z_m[i] = 0.5 * (p.z_m[i] + p.z_m[i + 1]);
      p.y_m.erase(p.y_m.begin() + static_cast<std::ptrdiff_t>(i) + 1);
      p.z_m.erase(p.z_m.begin() + static_cast<std::ptrdiff_t>(i) + 1);
      ++repaired;
      i = std::max<std::size_t>(1, i - 1);
      continue;
    }
    ++i;
  }
  return repaired;
}

struct Segment {
  double y_lo, y_hi;
  std::size_t i;  // from point i to i+1
};

// z of segment s at y (y within its lateral range, the segment not vertical).
double z_on(const Profile& p, const Segment& s, double y) {
  const std::size_t a = s.i, b = s.i + 1;
  const double t = (y - p.y_m[a]) / (p.y_m[b] - p.y_m[a]);
  return p.z_m[a] + t * (p.z_m[b] - p.z_m[a]);
}

// The envelope's points, each marked when it is a point of the profile (not a value interpolated
// on a segment at another branch's y).
struct EnvelopePoints {
  std::vector<double> y_m, z_m;
  std::vector<bool> vertex;

  void push(double y, double z, bool is_vertex) {
    if (!y_m.empty() && y_m.back() == y && std::abs(z_m.back() - z) <= 1e-12) {
      vertex.back() = vertex.back() || is_vertex;
      return;
    }
    y_m.push_back(y);
    z_m.push_back(z);
    vertex.push_back(is_vertex);
  }
};

// The polyline seen from the side `sign` (+1: from +z, the largest z; −1: from −z), with y
// increasing: at every point's y the nearest branch, from the left and from the right (two points,
// a vertical step, where they differ). A sweep over y with the segments active at each.
EnvelopePoints envelope_points(const Profile& p, double sign) {
  std::vector<Segment> segments;
  for (std::size_t i = 0; i + 1 < p.size(); ++i)
    if (p.y_m[i] != p.y_m[i + 1])
      segments.push_back({std::min(p.y_m[i], p.y_m[i + 1]), std::max(p.y_m[i], p.y_m[i + 1]), i});
  std::sort(segments.begin(), segments.end(), [](const Segment& a, const Segment& b) { return a.y_lo < b.y_lo; });
  std::vector<double> ys = p.y_m;
  std::sort(ys.begin(), ys.end());
  ys.erase(std::unique(ys.begin(), ys.end()), ys.end());

  EnvelopePoints e;
  std::vector<std::size_t> active;
  std::size_t next = 0;
  const auto ends_at = [&](const Segment& s, double y) { return p.y_m[s.i] == y || p.y_m[s.i + 1] == y; };
  for (const double y : ys) {
    while (next < segments.size() && segments[next].y_lo <= y) active.push_back(next++);
    std::erase_if(active, [&](std::size_t k) { return segments[k].y_hi < y; });
    // The nearest branch arriving from the left (y_lo < y) and leaving to the right (y_hi > y).
    const Segment* left = nullptr;
    const Segment* right = nullptr;
    double z_left = 0.0, z_right = 0.0;
    for (const std::size_t k : active) {
      const Segment& s = segments[k];
      const double z = ends_at(s, y) ? (p.y_m[s.i] == y ? p.z_m[s.i] : p.z_m[s.i + 1]) : z_on(p, s, y);
      if (s.y_lo < y && (left == nullptr || sign * (z - z_left) > 0.0)) left = &s, z_left = z;
      if (s.y_hi > y && (right == nullptr || sign * (z - z_right) > 0.0)) right = &s, z_right = z;
    }
    if (left != nullptr) e.push(y, z_left, ends_at(*left, y));
    if (right != nullptr) e.push(y, z_right, ends_at(*right, y));
  }
  return e;
}

// The envelope as a profile: the profile's points on it, its ends and the two points of each step
// (a step longer than 1 mm sampled every millimetre: the checks bound the gap between points).
// Points inside one of its straight pieces are not kept.
Profile kept_envelope(const Profile& p, const EnvelopePoints& e) {
  Profile kept;
  kept.kind = p.kind;
  kept.source = p.source;
  const std::vector<double>&ey = e.y_m, &ez = e.z_m;
  for (std::size_t j = 0; j < ey.size(); ++j) {
    const bool end = j == 0 || j + 1 == ey.size();
    const bool step = (j > 0 && ey[j - 1] == ey[j]) || (j + 1 < ey.size() && ey[j + 1] == ey[j]);
    if (!(end || step || e.vertex[j])) continue;
    if (!kept.y_m.empty() && kept.y_m.back() == ey[j]) {
      const double z0 = kept.z_m.back(), rise = ez[j] - z0;
      const int pieces = static_cast<int>(std::ceil(std::abs(rise) / kMm));
      for (int k = 1; k < pieces; ++k) {
        kept.y_m.push_back(ey[j]);
        kept.z_m.push_back(z0 + rise * k / pieces);
      }
    }
    kept.y_m.push_back(ey[j]);
    kept.z_m.push_back(ez[j]);
  }
  return kept;
}

// The profile's points hidden behind the envelope (further from the viewer than it at their y),
// and the y range they span.
struct HiddenPoints {
  std::size_t count = 0;
  double from_y_m = std::numeric_limits<double>::infinity();
  double to_y_m = -std::numeric_limits<double>::infinity();
};
HiddenPoints hidden_points(const Profile& p, const Profile& kept, double sign) {
  HiddenPoints hidden;
  std::size_t j = 0;
  std::vector<std::size_t> order(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return p.y_m[a] < p.y_m[b]; });
  for (const std::size_t i : order) {
    const double y = p.y_m[i];
    while (j + 1 < kept.size() && kept.y_m[j + 1] < y) ++j;
    // The envelope's nearest value at y (both values of a step at y).
    double nearest = -sign * std::numeric_limits<double>::infinity();
    for (std::size_t k = j; k < kept.size() && kept.y_m[k] <= y; ++k) {
      if (kept.y_m[k] == y) nearest = sign > 0 ? std::max(nearest, kept.z_m[k]) : std::min(nearest, kept.z_m[k]);
      if (k + 1 < kept.size() && kept.y_m[k] < y && y < kept.y_m[k + 1]) {
        const double t = (y - kept.y_m[k]) / (kept.y_m[k + 1] - kept.y_m[k]);
        const double z = kept.z_m[k] + t * (kept.z_m[k + 1] - kept.z_m[k]);
        nearest = sign > 0 ? std::max(nearest, z) : std::min(nearest, z);
      }
    }
    if (sign * (nearest - p.z_m[i]) > 1e-9) {
      ++hidden.count;
      hidden.from_y_m = std::min(hidden.from_y_m, y);
      hidden.to_y_m = std::max(hidden.to_y_m, y);
    }
  }
  return hidden;
}

// The envelope of the polyline seen from the side `sign`, and the points it hides.
Profile envelope(const Profile& p, double sign, std::size_t& hidden_count, double& hidden_from_y_m,
                 double& hidden_to_y_m) {
  Profile kept = kept_envelope(p, envelope_points(p, sign));
  const HiddenPoints hidden = hidden_points(p, kept, sign);
  hidden_count = hidden.count;
  hidden_from_y_m = hidden.from_y_m;
  hidden_to_y_m = hidden.to_y_m;
  return kept;
}

}  // namespace

Profile curated(Profile profile, ProfileKind role, const ProfileCurationOptions& options) {
  ProfileCuration& report = profile.curation;
  if (profile.size() < 4) return profile;  // the checks name it
  for (std::size_t i = 0; i < profile.size(); ++i)
    if (!std::isfinite(profile.y_m[i]) || !std::isfinite(profile.z_m[i])) return profile;  // the checks name it
  if (options.repair_zigzags) report.zigzags_repaired += repair_zigzags(profile);
  const ProfileKind kind = role != ProfileKind::unknown ? role : profile.kind;
  if (!options.hide_undercuts || kind == ProfileKind::unknown || profile.size() < 4) return profile;
  report.largest_overhang_m = geometry::largest_lateral_retreat_m(profile);
  if (report.largest_overhang_m <= ProfileLimits::max_lateral_retreat_m) return profile;
  // The wheel is seen by its rail from +z (below it, z pointing down), the rail by its wheel from −z.
  const double sign = kind == ProfileKind::wheel ? 1.0 : -1.0;
  const std::size_t points = profile.size();
  std::size_t hidden = 0;
  double from = 0.0, to = 0.0;
  Profile visible = envelope(profile, sign, hidden, from, to);
  require(static_cast<double>(hidden) <= options.max_hidden_fraction * static_cast<double>(points), [&] {
    return fmt::format(
        "profile {}: {} of its {} points ({:.0f} %) lie behind the part that faces the {} (undercut, overhanging by up "
        "to {:.3g} mm); at most {:.0f} % may be hidden: is it a {} profile, and is z pointing down (mirror it)?",
        profile.source.empty() ? std::string("(unnamed)") : profile.source, hidden, points,
        100.0 * static_cast<double>(hidden) / static_cast<double>(points), kind == ProfileKind::wheel ? "rail" : "wheel",
        report.largest_overhang_m / kMm, 100.0 * options.max_hidden_fraction,
        kind == ProfileKind::wheel ? "wheel" : "rail");
  });
  visible.curation = report;
  visible.curation.hidden_points = hidden;
  visible.curation.hidden_from_y_m = from;
  visible.curation.hidden_to_y_m = to;
  return visible;
}

}  // namespace railcontact
