// Both wheels of a wheelset on their rails in 3-D: placement of the profiles, the contact locus of
// a yawed and rolled wheel, and its interpenetration regions with their smooth reference points
// (docs/WHEELSET.md §1–4).
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "geometry/wheel_locus.hpp"
#include "geometry/wheelset_frames.hpp"
#include "railcontact/error.hpp"
#include "railcontact/wheelset_geometry.hpp"

namespace railcontact {

namespace {

constexpr double kMm = 1e-3;
// Largest roll, yaw and displacements a wheelset on its track can have (validate(WheelsetPosition)).
constexpr double kMaximumAngle_rad = 0.1;
constexpr double kMaximumDisplacement_m = 0.1;
// A contact on the flange beyond its steepest point where the slope has fallen by this much: the
// flange climbing over the rail.
constexpr double kFlangeRoundingAngle_rad = 5.0 * M_PI / 180.0;

// A run of overlapping samples of a contact locus (vertical gap < 0), first..last.
struct LocusRun {
  std::size_t first, last;
};

// The runs of overlapping samples, each bounded by separated samples of the locus on both sides;
// an overlap that reaches the end of the wheel profile, or a part of the wheel without a locus or
// rail below it, is refused (`where` names the wheel and its position).
std::vector<LocusRun> overlap_runs(const std::vector<ContactLocusSample>& locus, const std::vector<std::uint8_t>& valid,
                                   const std::string& where) {
  const std::size_t n = locus.size();
  std::vector<LocusRun> runs;
  for (std::size_t k = 0; k < n;) {
    if (!(valid[k] && locus[k].vertical_gap_m < 0.0)) {
      ++k;
      continue;
    }
    std::size_t last = k;
    while (last + 1 < n && valid[last + 1] && locus[last + 1].vertical_gap_m < 0.0) ++last;
    const bool open_before = k == 0 || !valid[k - 1];
    const bool open_after = last + 1 == n || !valid[last + 1];
    if (open_before || open_after) {
      const bool at_profile_end = (open_before && k == 0) || (open_after && last + 1 == n);
      const ContactLocusSample& edge = locus[open_before ? k : last];
      if (at_profile_end) {
        throw Error(ErrorKind::invalid_input,
                    fmt::format("contact search, {}: the overlap of wheel and rail reaches the end of the wheel "
                                "profile at y_p = {:.2f} mm (the flange climbing over the rail, or the wheel "
                                "beyond the rail head)",
                                where, edge.wheel_profile_y_m / kMm));
      }
      throw Error(ErrorKind::no_contact,
                  fmt::format("contact search, {}: the overlap of wheel and rail near the wheel profile's y_p = "
                              "{:.2f} mm reaches a part of the wheel without a contact locus or without rail "
                              "below it (a yaw too large for the flange, or the end of the rail profile)",
                              where, edge.wheel_profile_y_m / kMm));
    }
    runs.push_back({k, last});
    k = last + 1;
  }
  return runs;
}

// How far a neck must rise above the shallower of the two humps it parts for the humps to be
// pieces of their own (docs/WHEELSET.md §3): of the order of a loaded patch's elastic approach
// (0.073 mm at 98.1 kN), so that the contact's own deformation does not bridge it. S1002 on UIC60
// has necks of at most 0.017 mm between its flange and flange root (at +10 mrad, y = −6.54 …
// −6.60 mm); Car7358 on upright UIC60 one of 0.14–0.17 mm (+10 mrad, y = −7.0 … −7.1 mm).
constexpr double kNeckProminence_m = 0.05e-3;

// Each run cut at its necks: an interior sample whose vertical gap is higher than its neighbours'
// (a local maximum, though still overlapping) and at least kNeckProminence_m higher than the
// deepest sample of the shallower hump on either side of it (up to the next such neck or the run's
// end) parts two humps of the overlap, which may lie on different parts of the profile (a flange
// root and a flange that have met). The humps are pieces for merged_runs, which joins them again
// unless their contact angles differ. Lowering the wheel moves every gap alike, so a neck and its
// prominence stay as they are while the wheel settles into the rail: the pieces, and so the
// patches, do not change with the height at which the load is met.
std::vector<LocusRun> cut_at_necks(const std::vector<LocusRun>& runs, const std::vector<ContactLocusSample>& locus) {
  const auto gap = [&](std::size_t k) { return locus[k].vertical_gap_m; };
  std::vector<LocusRun> pieces;
  for (const LocusRun& r : runs) {
    // The run's local maxima of the gap, in order.
    std::vector<std::size_t> maxima;
    for (std::size_t k = r.first + 1; k < r.last; ++k)
      if (gap(k) > gap(k - 1) && gap(k) >= gap(k + 1)) maxima.push_back(k);
    std::size_t first = r.first;
    for (std::size_t m = 0; m < maxima.size(); ++m) {
      const std::size_t k = maxima[m];
      // The deepest gap before k (since the last cut) and after it (up to the next maximum that
      // would be a cut, or the run's end: the hump beyond k as far as it goes).
      double before = gap(first), after = gap(k + 1);
      for (std::size_t i = first; i < k; ++i) before = std::min(before, gap(i));
      for (std::size_t i = k + 1; i <= r.last; ++i) {
        if (gap(i) > gap(k)) break;  // beyond a higher neck
        after = std::min(after, gap(i));
      }
      if (gap(k) - std::max(before, after) >= kNeckProminence_m) {
        pieces.push_back({first, k});
        first = k + 1;
      }
    }
    pieces.push_back({first, r.last});
  }
  return pieces;
}

// Neighbouring pieces closer along the rail than the merge distance (0 for the two humps at a neck)
// and closer in contact angle than the merge angle (ContactSearchOptions) as one (docs/WHEELSET.md
// §3). The angles compared are the pieces' own contact angles, averaged as their regions' are
// (`angle_of(first, last)`), as Kalker's CONTACT compares its patches'.
template <class AngleOf>
std::vector<LocusRun> merged_runs(const std::vector<LocusRun>& runs, const std::vector<ContactLocusSample>& locus,
                                  const ContactSearchOptions& options, const AngleOf& angle_of) {
  std::vector<LocusRun> merged;
  for (const LocusRun& r : cut_at_necks(runs, locus)) {
    if (!merged.empty()) {
      const ContactLocusSample& a = locus[merged.back().last];
      const ContactLocusSample& b = locus[r.first];
      if (std::abs(b.rail_profile_y_m - a.rail_profile_y_m) < options.merge_distance_m &&
          std::abs(angle_of(r.first, r.last) - angle_of(merged.back().first, merged.back().last)) <
              options.merge_angle_rad) {
        merged.back().last = r.last;
        continue;
      }
    }
    merged.push_back(r);
  }
  return merged;
}

// The contact locus of a wheel from one end of its profile to the other: sample k of `count`
// intervals at the wheel profile parameter s0 + (s1 − s0) k / count, and a flag per sample: false
// where it has no locus point or no rail below it (geometry::WheelOnRail::locus_sample).
std::size_t locus_intervals(const geometry::WheelOnRail& w, double step_m) {
  return static_cast<std::size_t>(std::ceil((w.wheel().s_end_m() - w.wheel().s_begin_m()) / step_m));
}

double locus_parameter(const geometry::WheelOnRail& w, std::size_t count, std::size_t k) {
  const double s0 = w.wheel().s_begin_m(), s1 = w.wheel().s_end_m();
  return s0 + (s1 - s0) * static_cast<double>(k) / static_cast<double>(count);
}

void compute_sample(const geometry::WheelOnRail& w, std::size_t k, detail::WheelLocus& locus) {
  ContactLocusSample sample;
  locus.valid[k] = w.locus_sample(locus_parameter(w, locus.samples.size() - 1, k), sample) ? 1 : 0;
  locus.samples[k] = sample;
}

// Samples a locus (all of it, or its coarse samples: every coarse_every-th and the last).
void sample_locus(const geometry::WheelOnRail& w, detail::WheelLocus& locus) {
  const std::size_t count = locus_intervals(w, locus.step_m), n = count + 1;
  if (locus.coarse_every <= 1) {
    locus.computed.clear();
    locus.samples.clear();
    locus.valid.clear();
    locus.samples.reserve(n);
    locus.valid.reserve(n);
    for (std::size_t k = 0; k < n; ++k) {
      ContactLocusSample sample;
      locus.valid.push_back(w.locus_sample(locus_parameter(w, count, k), sample) ? 1 : 0);
      locus.samples.push_back(sample);
    }
    return;
  }
  locus.samples.assign(n, ContactLocusSample{});
  locus.valid.assign(n, 1);
  locus.computed.assign(n, 0);
  const auto c = static_cast<std::size_t>(locus.coarse_every);
  const auto coarse = [&](std::size_t k) {
    compute_sample(w, k, locus);
    locus.computed[k] = 1;
  };
  for (std::size_t k = 0; k < n - 1; k += c) coarse(k);
  coarse(n - 1);
  for (std::size_t k = 0; k < n; ++k)
    if (!locus.computed[k]) locus.samples[k].vertical_gap_m = std::numeric_limits<double>::infinity();
}

// An on-demand locus's samples between the coarse samples around k (k itself coarse: the interval
// after it).
void fill_interval(const geometry::WheelOnRail& w, std::size_t k, detail::WheelLocus& locus) {
  const auto c = static_cast<std::size_t>(locus.coarse_every);
  const std::size_t a = k / c * c, b = std::min(a + c, locus.samples.size() - 1);
  for (std::size_t i = a + 1; i < b; ++i) {
    if (locus.computed[i]) continue;
    compute_sample(w, i, locus);
    locus.computed[i] = 1;
  }
}

// The margin of refine_locus: above the level, the gap at a coarse sample is known to keep clear
// of it between coarse samples when it exceeds it by this and by eight times what the gap's
// curvature there (its second difference over the coarse samples) lets it dip.
constexpr double kLocusMargin_m = 0.05e-3;

}  // namespace

namespace detail {

void refine_locus(const WheelsetTrack& track, WheelLocus& locus, double level_m) {
  if (locus.computed.empty()) return;
  const geometry::WheelOnRail w(track, locus.side, locus.position);
  const std::size_t n = locus.samples.size();
  const auto c = static_cast<std::size_t>(locus.coarse_every);
  // The second difference of the gap at coarse sample k over its coarse neighbours; infinite where
  // one is missing or has no locus point.
  const auto bend = [&](std::size_t k) {
    if (k < c || k + c > n - 1 || k % c != 0) return std::numeric_limits<double>::infinity();
    if (!locus.valid[k - c] || !locus.valid[k] || !locus.valid[k + c]) return std::numeric_limits<double>::infinity();
    const double g0 = locus.samples[k - c].vertical_gap_m, g1 = locus.samples[k].vertical_gap_m,
                 g2 = locus.samples[k + c].vertical_gap_m;
    return std::abs(g0 - 2.0 * g1 + g2);
  };
  for (std::size_t a = 0; a + 1 < n; a += c) {
    const std::size_t b = std::min(a + c, n - 1);
    if (b == a + 1 || locus.computed[a + 1]) continue;
    if (!locus.valid[a] && !locus.valid[b]) {
      // Between two samples without a locus point or rail below it (beyond the rail head, the
      // flange beside it): none either.
      for (std::size_t k = a + 1; k < b; ++k) locus.valid[k] = 0;
      continue;
    }
    const double lowest = std::min(locus.samples[a].vertical_gap_m, locus.samples[b].vertical_gap_m);
    const double margin = kLocusMargin_m + std::max(bend(a), bend(b));
    if (locus.valid[a] && locus.valid[b] && lowest - margin >= level_m) continue;
    fill_interval(w, a, locus);
  }
}

}  // namespace detail

const char* side_name(WheelSide side) { return side == WheelSide::right ? "right" : "left"; }

const char* reference_weighting_name(ReferenceWeighting weighting) {
  return weighting == ReferenceWeighting::squared_gap ? "squared-gap" : "depth";
}

ReferenceWeighting parse_reference_weighting(const std::string& name) {
  for (ReferenceWeighting w : {ReferenceWeighting::squared_gap, ReferenceWeighting::depth})
    if (name == reference_weighting_name(w)) return w;
  throw Error(fmt::format("unknown reference-point weighting '{}' (allowed: squared-gap, the default of CONTACT; "
                          "depth)",
                          name));
}

void validate(const WheelsetPosition& p) {
  const auto check = [](double value, double limit, const char* name, const char* unit, double scale) {
    require(std::isfinite(value) && std::abs(value) <= limit, [&] {
      return fmt::format("wheelset position: {} = {:g} {} must be finite and at most {:g} {} in size", name,
                         value * scale, unit, limit * scale, unit);
    });
  };
  check(p.lateral_displacement_m, kMaximumDisplacement_m, "the lateral displacement y", "mm", 1e3);
  check(p.vertical_displacement_m, kMaximumDisplacement_m, "the vertical displacement z", "mm", 1e3);
  check(p.roll_rad, kMaximumAngle_rad, "the roll angle", "mrad", 1e3);
  check(p.yaw_rad, kMaximumAngle_rad, "the yaw angle", "mrad", 1e3);
}

void validate(const ContactSearchOptions& o) {
  require(std::isfinite(o.locus_step_m) && o.locus_step_m >= 1e-6 && o.locus_step_m <= 1e-3, [&] {
    return fmt::format("contact search: the locus step {:g} mm must lie in [0.001, 1] mm", o.locus_step_m / kMm);
  });
  require(std::isfinite(o.merge_distance_m) && o.merge_distance_m >= 0.0 && o.merge_distance_m <= 0.05, [&] {
    return fmt::format("contact search: the merge distance {:g} mm must lie in [0, 50] mm", o.merge_distance_m / kMm);
  });
  require(std::isfinite(o.merge_angle_rad) && o.merge_angle_rad >= 0.0 && o.merge_angle_rad <= 1.5, [&] {
    return fmt::format("contact search: the merge angle {:g} rad must lie in [0, 1.5] rad", o.merge_angle_rad);
  });
}

Vector3 axle_direction(double roll_rad, double yaw_rad) {
  // Rx(roll) (0, 1, 0) = (0, cos φ, sin φ), then Rz(yaw).
  const double cr = std::cos(roll_rad), sr = std::sin(roll_rad), cy = std::cos(yaw_rad), sy = std::sin(yaw_rad);
  return {-sy * cr, cy * cr, sr};
}

WheelsetTrack::WheelsetTrack(const Profile& wheel, const Profile& rail, const TrackWheelsetParameters& parameters,
                             const SmoothingOptions& smoothing)
    : WheelsetTrack(WheelsetProfiles{wheel, wheel, rail, rail}, parameters, smoothing) {}

WheelsetTrack::WheelsetTrack(const WheelsetProfiles& profiles, const TrackWheelsetParameters& parameters,
                             const SmoothingOptions& smoothing)
    : right_(profiles.right_wheel, profiles.right_rail, parameters, smoothing),
      left_(profiles.left_wheel, profiles.left_rail, parameters, smoothing),
      parameters_(parameters) {
  place_wheelset();
}

WheelsetTrack::WheelsetTrack(const WheelRailPair& pair) : right_(pair), left_(pair), parameters_(pair.parameters()) {
  place_wheelset();
}

void WheelsetTrack::place_wheelset() {
  // H0: lower the wheelset (zero displacement, roll and yaw) from H = 0 until the first wheel touches.
  nominal_axle_height_m_ = 0.0;
  double height = -std::numeric_limits<double>::infinity();
  for (WheelSide side : {WheelSide::right, WheelSide::left}) {
    const detail::WheelLocus locus =
        detail::sample_wheel_locus(*this, side, WheelsetPosition{}, ContactSearchOptions{}.locus_step_m);
    for (std::size_t k = 0; k < locus.samples.size(); ++k)
      if (locus.valid[k]) height = std::max(height, -locus.samples[k].vertical_gap_m);
  }
  require(std::isfinite(height), "wheelset: the wheel and rail profiles do not overlap laterally at y = 0");
  nominal_axle_height_m_ = height;

  for (WheelSide side : {WheelSide::right, WheelSide::left}) {
    const SmoothProfile& wheel = pair(side).wheel();
    const double taping = pair(side).taping_line_y_m();
    const int k = side == WheelSide::right ? 0 : 1;
    flange_steepest_angle_rad_[k] = -1.0;
    const int samples = 4000;
    for (int i = 0; i <= samples; ++i) {
      const ProfileCurvePoint p = wheel.at(wheel.s_begin_m() + (wheel.s_end_m() - wheel.s_begin_m()) * i / samples);
      if (p.y_m >= taping) break;
      const double angle = std::atan2(-p.dz_ds, p.dy_ds);  // the slope angle, positive on the flange flank
      if (angle > flange_steepest_angle_rad_[k]) {
        flange_steepest_angle_rad_[k] = angle;
        flange_steepest_y_m_[k] = p.y_m;
      }
    }
  }
}

double WheelsetTrack::touching_vertical_displacement_m(WheelSide side, const WheelsetPosition& position) const {
  WheelsetPosition at_nominal = position;
  at_nominal.vertical_displacement_m = 0.0;
  validate(at_nominal);
  detail::WheelLocus locus = detail::sample_wheel_locus(*this, side, at_nominal, ContactSearchOptions{}.locus_step_m);
  return detail::touching_vertical_displacement_m(*this, locus);
}

double WheelsetTrack::wheel_profile_origin_y_m(WheelSide side) const {
  return geometry::side_sign(side) * geometry::wheel_origin_offset_m(parameters_);
}

double WheelsetTrack::rail_profile_origin_y_m(WheelSide side) const {
  return geometry::side_sign(side) * geometry::rail_origin_offset_m(pair(side), parameters_);
}

WheelContactSearch WheelsetTrack::contact_search(WheelSide side, const WheelsetPosition& position,
                                                 const ContactSearchOptions& options) const {
  validate(position);
  validate(options);
  detail::WheelLocus locus = detail::sample_wheel_locus(*this, side, position, options.locus_step_m);
  return detail::contact_search(*this, locus, position, options);
}

namespace detail {

WheelLocus sample_wheel_locus(const WheelsetTrack& track, WheelSide side, const WheelsetPosition& position,
                              double step_m, int coarse_every) {
  WheelLocus locus;
  locus.side = side;
  locus.position = position;
  locus.position.vertical_displacement_m = 0.0;
  locus.step_m = step_m;
  locus.coarse_every = std::max(1, coarse_every);
  sample_locus(geometry::WheelOnRail(track, side, locus.position), locus);
  return locus;
}

double touching_vertical_displacement_m(const WheelsetTrack& track, WheelLocus& locus) {
  if (!locus.computed.empty()) {
    double coarse = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < locus.samples.size(); ++k)
      if (locus.computed[k] && locus.valid[k]) coarse = std::min(coarse, locus.samples[k].vertical_gap_m);
    refine_locus(track, locus, coarse);
  }
  double gap = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < locus.samples.size(); ++k)
    if (locus.valid[k]) gap = std::min(gap, locus.samples[k].vertical_gap_m);
  if (!std::isfinite(gap)) {
    throw Error(ErrorKind::no_contact,
                fmt::format("contact search, {} wheel at y = {:.3f} mm: the wheel and rail profiles do not overlap "
                            "laterally",
                            side_name(locus.side), locus.position.lateral_displacement_m / kMm));
  }
  return -gap;
}

WheelContactSearch contact_search(const WheelsetTrack& track, WheelLocus& locus, const WheelsetPosition& position,
                                  const ContactSearchOptions& options) {
  const WheelSide side = locus.side;
  const geometry::WheelOnRail w(track, side, position);
  WheelContactSearch search;
  search.side = side;
  const std::vector<std::uint8_t>& valid = locus.valid;
  // The locus at z: every point, and so every vertical gap, lifted by z.
  const double z = position.vertical_displacement_m;
  refine_locus(track, locus, -z);
  const auto lift = [&] {
    search.locus = locus.samples;
    for (ContactLocusSample& sample : search.locus) {
      sample.point_track_m[2] += z;
      sample.vertical_gap_m += z;
    }
  };
  lift();
  const std::size_t n = search.locus.size();
  std::size_t valid_count = 0;
  search.min_vertical_gap_m = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < n; ++k) {
    if (!valid[k]) continue;
    ++valid_count;
    if (search.locus[k].vertical_gap_m < search.min_vertical_gap_m) {
      search.min_vertical_gap_m = search.locus[k].vertical_gap_m;
      search.min_gap_sample = k;
    }
  }
  const std::string where =
      fmt::format("{} wheel at y = {:.3f} mm, z = {:.3f} mm, roll = {:.2f} mrad, yaw = {:.2f} mrad", side_name(side),
                  position.lateral_displacement_m / kMm, position.vertical_displacement_m / kMm,
                  position.roll_rad * 1e3, position.yaw_rad * 1e3);
  if (valid_count < 3) {
    throw Error(ErrorKind::no_contact,
                fmt::format("contact search, {}: the wheel and rail profiles do not overlap laterally", where));
  }

  // Runs of overlapping samples (vertical gap < 0), neighbours close along the rail and similar in
  // contact angle merged into one (docs/WHEELSET.md §3).
  const auto angle_of = [&](std::size_t first, std::size_t last) {
    return w.region(search.locus, first, last, options.weighting).contact_angle_rad;
  };
  std::vector<LocusRun> merged = merged_runs(overlap_runs(search.locus, valid, where), search.locus, options, angle_of);
  // An on-demand locus computed across each region and beside it (regions merged across a gap
  // hold samples that do not overlap).
  if (!locus.computed.empty()) {
    bool filled = false;
    const geometry::WheelOnRail at_nominal(track, side, locus.position);
    for (const LocusRun& r : merged) {
      for (std::size_t k = r.first > 0 ? r.first - 1 : 0; k <= std::min(r.last + 1, locus.samples.size() - 1); ++k) {
        if (locus.computed[k]) continue;
        fill_interval(at_nominal, k, locus);
        filled = true;
      }
    }
    if (filled) {
      lift();
      merged = merged_runs(overlap_runs(search.locus, valid, where), search.locus, options, angle_of);
    }
  }
  for (const LocusRun& r : merged) {
    search.regions.push_back(w.region(search.locus, r.first, r.last, options.weighting));
    const InterpenetrationRegion& region = search.regions.back();
    // Beyond the flange's steepest part, where the flange rounds off towards its tip (its slope
    // 5 degrees below the steepest), the wheel is climbing over the rail.
    const ProfileCurvePoint at_reference = w.wheel().at(w.wheel().parameter_at(region.wheel_profile_y_m));
    const double wheel_slope_rad = std::atan2(-at_reference.dz_ds, at_reference.dy_ds);
    if (region.wheel_profile_y_m < track.flange_steepest_point_y_m(side) &&
        wheel_slope_rad < track.flange_steepest_angle_rad(side) - kFlangeRoundingAngle_rad) {
      throw Error(ErrorKind::invalid_input,
                  fmt::format("contact search, {}: the flange is climbing over the rail: the contact lies at the "
                              "wheel profile's y_p = {:.2f} mm, beyond the flange's steepest point ({:.2f} mm, "
                              "{:.1f} degrees), towards its tip, where its slope has fallen to {:.1f} degrees",
                              where, region.wheel_profile_y_m / kMm, track.flange_steepest_point_y_m(side) / kMm,
                              track.flange_steepest_angle_rad(side) * 180.0 / M_PI, wheel_slope_rad * 180.0 / M_PI));
    }
  }
  std::sort(search.regions.begin(), search.regions.end(),
            [](const InterpenetrationRegion& a, const InterpenetrationRegion& b) {
              return a.rail_profile_y_m < b.rail_profile_y_m;
            });
  for (std::size_t k = 1; k < search.regions.size(); ++k) {
    const double midway = 0.5 * (search.regions[k - 1].rail_profile_y_max_m + search.regions[k].rail_profile_y_min_m);
    search.regions[k - 1].rail_profile_y_upper_bound_m = midway;
    search.regions[k].rail_profile_y_lower_bound_m = midway;
  }
  return search;
}

}  // namespace detail

}  // namespace railcontact
