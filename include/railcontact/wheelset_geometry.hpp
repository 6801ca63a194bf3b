#pragma once
// Stage: geometry, the wheelset level (docs/WHEELSET.md §1–4). Both wheels of a wheelset on their
// rails in 3-D: the wheelset's position (lateral and vertical displacement, roll, yaw), the
// contact search by the contact locus of each wheel (a true surface of revolution), the
// interpenetration regions that become contact patches, each patch's smooth reference point and
// contact angle, and the exact undeformed distance on a mesh in the patch's tangent plane.
//
// Frames (docs/GEOMETRY.md §1–3):
// - Track frame: x along the track in the direction of travel, y lateral to the LEFT, z UP. Origin
//   on the track centreline at the height of the rail profiles' origins (z_p = 0).
// - Wheelset frame: the wheelset centre at (0, y, H0 + z), its axle along Rz(yaw) Rx(roll) e_y
//   (H0: nominal_axle_height_m()).
// - Each wheel and rail profile is given in its own side's profile frame: y_p away from the track
//   centre (flange / gauge face at −y_p), z_p down (geometry.hpp). The right side is seen from the
//   track frame as y = −(offset + y_p), the left side as its mirror image y = +(offset + y_p): one
//   profile file serves both sides.
// - Contact frame of a patch: X1 = x (the rail's direction: creepages are relative to the rail);
//   X3 the rail's normal into the wheel at the reference point, leaning towards the track centre
//   by the contact angle γ: X3 = (0, ±sin γ, cos γ) (+ right wheel, − left wheel);
//   X2 = X3 × X1 = (0, cos γ, ∓sin γ) points to the LEFT (+y) on both wheels.
#include <algorithm>
#include <limits>
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "railcontact/contact_patch.hpp"
#include "railcontact/geometry.hpp"

namespace railcontact {

using Vector3 = std::array<double, 3>;

enum class WheelSide { right, left };
// "right" / "left"
const char* side_name(WheelSide side);

// The wheelset's position on the track (SI units, angles in rad).
struct WheelsetPosition {
  double lateral_displacement_m = 0.0;   // y of the wheelset centre (+ to the left)
  double vertical_displacement_m = 0.0;  // z of the wheelset centre above its nominal height H0 (+ up)
  double roll_rad = 0.0;                 // about x (positive: the left wheel rises)
  double yaw_rad = 0.0;                  // about z (positive: the axle's left end moves backwards)
};
// Throws Error (invalid_input) naming the field unless every value is finite, |roll| <= 0.1 rad
// and |yaw| <= 0.1 rad (a wheelset beyond these is off its track) and |y|, |z| <= 0.1 m.
void validate(const WheelsetPosition& position);

// The axle's direction in the track frame: Rz(yaw) Rx(roll) (0, 1, 0) =
// (−sin ψ cos φ, cos ψ cos φ, sin φ) for roll φ and yaw ψ.
Vector3 axle_direction(double roll_rad, double yaw_rad);

// The four profiles of a wheelset on its track, each in its own side's profile frame.
struct WheelsetProfiles {
  Profile right_wheel, left_wheel;
  Profile right_rail, left_rail;
};

// How a patch's reference point and contact angle average its interpenetration region
// (docs/WHEELSET.md §4): each lateral strip of the rigid overlap weighted by
// - squared_gap: the integral of the squared gap along the strip, ∫ g² dx (the default, and the
//   default of Kalker's CONTACT, whose wheelset module users validate against);
// - depth: the strip's depth times its width (railcontact before 3.0).
// Both fall to zero continuously at the region's ends, so the reference point moves continuously.
enum class ReferenceWeighting { squared_gap, depth };
// "squared-gap" / "depth"
const char* reference_weighting_name(ReferenceWeighting weighting);
// Throws Error (invalid_input) naming the allowed names.
ReferenceWeighting parse_reference_weighting(const std::string& name);

// Options of the contact search (docs/WHEELSET.md §2–3).
struct ContactSearchOptions {
  ReferenceWeighting weighting = ReferenceWeighting::squared_gap;
  // Spacing of the contact-locus samples along the wheel profile (arc length).
  double locus_step_m = 0.1e-3;
  // Interpenetration regions (runs of the locus's overlap, cut at their necks) closer than this
  // along the rail profile are one patch (docs/WHEELSET.md §3) ...
  double merge_distance_m = 2.0e-3;
  // ... unless their own contact angles (averaged over each) differ by more than this.
  double merge_angle_rad = 0.35;
};
void validate(const ContactSearchOptions& options);

// One sample of a wheel's contact locus: the point of the wheel's surface, at one position along
// its profile, whose normal is perpendicular to the track (the only points that can touch a rail,
// which is straight along x), and the rail below it.
struct ContactLocusSample {
  double wheel_profile_y_m = 0.0;  // the sample's position on the wheel profile (profile frame)
  double rolling_radius_m = 0.0;   // the wheel's radius there
  Vector3 point_track_m{};         // the locus point on the wheel, track frame
  double rail_profile_y_m = 0.0;   // the rail profile point at the locus point's lateral position
  // Its arc-length parameter on the smoothed rail profile; NaN where the sample found no rail
  // below it (a sample that is not valid).
  double rail_parameter_m = std::numeric_limits<double>::quiet_NaN();
  double vertical_gap_m = 0.0;     // locus z − rail z (negative: interpenetration)
  double contact_angle_rad = 0.0;  // of the rail's normal there (positive: leaning to the track centre)
};

// An interpenetration region of one wheel: where the undeformed wheel at the given position
// overlaps its rail. It becomes one contact patch. Its reference point and contact angle are
// averages over the region, by default weighted by the squared gap as Kalker's CONTACT
// (ContactSearchOptions::weighting, docs/WHEELSET.md §4), so they move
// continuously with the wheelset's position; a region that appears starts with zero weight.
struct InterpenetrationRegion {
  WheelSide side = WheelSide::right;
  // The reference point on the rail surface, track frame, and on the rail profile (profile frame).
  Vector3 reference_point_track_m{};
  double rail_profile_y_m = 0.0;
  double wheel_profile_y_m = 0.0;   // weighted average position on the wheel profile
  double contact_angle_rad = 0.0;   // weighted average rail normal angle
  // The smallest and largest rail normal angle over the part of the overlap at least half as deep
  // as its deepest point (for a Hertzian contact: the contact area's width): a patch on a curved part of the
  // profile (flange root, flange) spans several; a planar patch in one tangent plane at
  // contact_angle_rad ignores the spread (docs/WHEELSET.md §4 "Angle variation"). NaN where not
  // known (a patch from a wheelset table).
  double contact_angle_min_rad = std::numeric_limits<double>::quiet_NaN();
  double contact_angle_max_rad = std::numeric_limits<double>::quiet_NaN();
  // The rail normal angle's standard deviation over the overlap with the reference point's weights
  // (rad): continuous in the position, as the reference is (ContactSurface::automatic's measure).
  double contact_angle_spread_rad = std::numeric_limits<double>::quiet_NaN();
  double rolling_radius_m = 0.0;    // weighted average wheel radius
  // The contact frame at the reference point (track frame, see the top of this header).
  Vector3 x1_axis{1.0, 0.0, 0.0};
  Vector3 x2_axis{};
  Vector3 x3_axis{};
  // Extent and depth of the overlap: lateral range on the rail profile, largest normal
  // interpenetration, and its integral over the rail profile (m²: the depth weighting's total).
  double rail_profile_y_min_m = 0.0, rail_profile_y_max_m = 0.0;
  // The stretch of the rail profile the region owns: midway to the overlaps of the wheel's
  // neighbouring regions (unbounded without a neighbour). Its potential contact area counts overlap
  // only on normal lines that meet the rail there, so a patch never carries its neighbour's contact.
  double rail_profile_y_lower_bound_m = -std::numeric_limits<double>::infinity();
  double rail_profile_y_upper_bound_m = std::numeric_limits<double>::infinity();
  double max_interpenetration_m = 0.0;
  double interpenetration_area_m2 = 0.0;
  // Bounding box of the overlap in the tangent plane (x1, x2 from the reference point), an
  // estimate from the locus (the wheel rising as x1² cos γ / 2r away from each locus point).
  double x1_min_m = 0.0, x1_max_m = 0.0, x2_min_m = 0.0, x2_max_m = 0.0;
  // Locus samples of the region [first_sample, last_sample] in WheelContactSearch::locus.
  std::size_t first_sample = 0, last_sample = 0;
};

// The largest difference between the rail normal angle over a region's overlap and its contact
// angle (rad): how far the planar patch's tangent plane is from the surface at its edges (NaN where
// the range is not known).
inline double contact_angle_variation_rad(const InterpenetrationRegion& r) {
  return std::max(r.contact_angle_max_rad - r.contact_angle_rad, r.contact_angle_rad - r.contact_angle_min_rad);
}
// Above this angle variation (0.1 rad, 5.7°) a planar patch is flagged (JSON, text output, study
// profiles): on S1002/UIC60 at 5 mm towards the flange (a variation of about 7°) the planar lateral
// force is 9 % of μFz from a conformal solution (issue #31's measurement); Kalker's CONTACT warns
// from 13.9°, where the undeformed distance errs by 3 %.
inline constexpr double kLargeContactAngleVariation_rad = 0.1;

// The contact search of one wheel at one position.
struct WheelContactSearch {
  WheelSide side = WheelSide::right;
  std::vector<ContactLocusSample> locus;        // along the wheel profile, from its −y_p end
  std::vector<InterpenetrationRegion> regions;  // ordered along the rail profile (−y_p first: gauge side)
  // The smallest vertical gap over the locus (negative: overlap) and where it is: the point of
  // first touch if the wheel were lowered vertically.
  double min_vertical_gap_m = 0.0;
  std::size_t min_gap_sample = 0;
};

// One strip (a line of elements along x1, one mesh column i2) of a conformal contact surface
// (docs/WHEELSET.md §4 "Conformal contact"). The surface is curved across the rolling direction:
// its lateral coordinate is the rail profile's arc length from the reference point (the mesh's x2),
// and each strip has its own frame, turned about X1 from the region's (X2, X3) by angle_rad:
//   t = cos(angle) X2 + sin(angle) X3,   n = cos(angle) X3 − sin(angle) X2.
struct ConformalStrip {
  // The strip's developed lateral coordinate: the rail profile's arc length from the reference
  // point along X2 (m), the x2 of its column in the developed mesh.
  double s_m = 0.0;
  // The strip's point midway between rail and wheel along X2 from the reference point (m): where
  // the strip lies in the tangent plane.
  double x2_m = 0.0;
  // The turn of the mean of the rail's and the wheel's normal there from X3 (rad).
  double angle_rad = 0.0;
  // The undeformed wheel surface's point on the rail's normal line through the strip's rail point
  // (at the reference point's x): where the strip's creepages are taken.
  Vector3 wheel_point_track_m{};
  // false where the strip cannot touch: beyond the rail profile, outside the region's own stretch
  // of it, or where the two surfaces' normals differ by more than kConformalTurnAway_rad (its h is
  // then a gap of 1 m).
  bool possible_contact = true;
};
// Rail and wheel normals further apart than this (52°, the surfaces turning away from each other)
// cannot be in contact: such strips are left out of a conformal surface.
inline constexpr double kConformalTurnAway_rad = 0.9;

// A mesh in a patch's tangent plane and the undeformed distance on it.
struct TangentPlaneArea {
  Mesh mesh;
  std::vector<double> h_m;  // mesh.index() order; negative where the undeformed bodies overlap
  int growth_steps = 0;
  // Conformal: one per mesh column (mesh.n2), the mesh's x2 the developed lateral coordinate (rail
  // arc length) and h measured along each strip's normal. Empty: planar, the mesh in the tangent plane.
  std::vector<ConformalStrip> strips;
};

// Both wheel–rail pairs of a wheelset on the track. Immutable after construction, thread-safe.
// The smallest element size of WheelsetTrack::potential_contact_area (0.001 mm).
inline constexpr double kMinimumTangentPlaneElement_m = 1e-6;

class WheelsetTrack {
 public:
  // Throws Error (naming the profile) when a profile is not a plausible, correctly oriented wheel or
  // rail profile (see WheelRailPair) or the track parameters are invalid.
  WheelsetTrack(const WheelsetProfiles& profiles, const TrackWheelsetParameters& parameters = {},
                const SmoothingOptions& smoothing = {});
  // The same wheel and rail profile on both sides.
  WheelsetTrack(const Profile& wheel, const Profile& rail, const TrackWheelsetParameters& parameters = {},
                const SmoothingOptions& smoothing = {});
  // Both sides from one wheel–rail pair (already smoothed and placed; the left side is its mirror
  // image), with the pair's track parameters: the single wheel–rail patch's smooth reference.
  explicit WheelsetTrack(const WheelRailPair& pair);

  [[nodiscard]] const TrackWheelsetParameters& parameters() const { return parameters_; }
  // The side's wheel–rail pair (its profiles, taping line, gauge point; zero-yaw 2-D geometry).
  [[nodiscard]] const WheelRailPair& pair(WheelSide side) const { return side == WheelSide::right ? right_ : left_; }
  // Height of the wheelset centre above the track frame's origin at which, at zero lateral
  // displacement, roll and yaw, the first wheel touches its rail.
  [[nodiscard]] double nominal_axle_height_m() const { return nominal_axle_height_m_; }
  // Lateral position (track y) of the wheel's and the rail's profile origins.
  [[nodiscard]] double wheel_profile_origin_y_m(WheelSide side) const;
  [[nodiscard]] double rail_profile_origin_y_m(WheelSide side) const;
  // The steepest point of the wheel's flange (largest slope angle of the profile between the
  // flange tip and the taping line), on the wheel profile: a contact beyond it, towards the flange
  // tip, is the wheel climbing over the rail (an error of the contact search).
  [[nodiscard]] double flange_steepest_point_y_m(WheelSide side) const {
    return side == WheelSide::right ? flange_steepest_y_m_[0] : flange_steepest_y_m_[1];
  }
  [[nodiscard]] double flange_steepest_angle_rad(WheelSide side) const {
    return side == WheelSide::right ? flange_steepest_angle_rad_[0] : flange_steepest_angle_rad_[1];
  }
  // The vertical displacement at which the wheel of `side` first touches its rail, at the lateral
  // displacement, roll and yaw of `position` (its vertical displacement is ignored).
  [[nodiscard]] double touching_vertical_displacement_m(WheelSide side, const WheelsetPosition& position) const;

  // Contact locus and interpenetration regions of one wheel. Throws Error (no_contact) when the
  // wheel and rail do not overlap laterally, or the locus does not exist near the contact (a yaw
  // too large for the flange), or (invalid_input) an overlap reaches the end of a profile (the
  // flange climbing over the rail, the wheel off the rail head).
  [[nodiscard]] WheelContactSearch contact_search(WheelSide side, const WheelsetPosition& position,
                                                  const ContactSearchOptions& options = {}) const;

  // The exact undeformed distance at tangent-plane point (x1, x2) of a region: the distance along
  // the region's X3 from the rail surface to the wheel surface (a surface of revolution, yawed and
  // rolled) on the line through O + x1 X1 + x2 X2 (negative: overlap at this position).
  [[nodiscard]] double undeformed_distance_m(const WheelsetPosition& position, const InterpenetrationRegion& region,
                                             double x1_m, double x2_m) const;
  [[nodiscard]] std::vector<double> undeformed_distance_m(const WheelsetPosition& position,
                                                          const InterpenetrationRegion& region,
                                                          const Mesh& mesh) const;
  // A mesh of square elements of the given size (in [kMinimumTangentPlaneElement_m, 10 mm]) around
  // the region's overlap (h < 0) with a border
  // of border_elements, grown until the overlap stays off the border; the mesh is aligned with the
  // reference point (element centres at integer multiples of the size from it).
  [[nodiscard]] TangentPlaneArea potential_contact_area(const WheelsetPosition& position,
                                                        const InterpenetrationRegion& region, double element_size_m,
                                                        int border_elements = 2) const;
  // The potential contact area on the region's conformal surface (docs/WHEELSET.md §4 "Conformal
  // contact"): a mesh of square elements in (x1, s), s the rail profile's arc length from the
  // reference point, one ConformalStrip per column; h is the distance along X3 at the strip's
  // tangent-plane point times the cosine of its angle (the normal distance of locally parallel
  // surfaces). Grown as potential_contact_area. Throws Error naming the position and the angles
  // when the developed surface folds over in the tangent plane (two strips' points out of order).
  [[nodiscard]] TangentPlaneArea conformal_contact_area(const WheelsetPosition& position,
                                                        const InterpenetrationRegion& region, double element_size_m,
                                                        int border_elements = 2) const;
  // The same with elements of dx1 x dx2 (element centres at integer multiples of each from the
  // reference point), for the single wheel–rail patch's rolling-resolved meshes.
  [[nodiscard]] TangentPlaneArea potential_contact_area(const WheelsetPosition& position,
                                                        const InterpenetrationRegion& region, double dx1_m,
                                                        double dx2_m, int border_elements) const;

 private:
  void place_wheelset();  // the nominal axle height and the flanges' steepest points
  WheelRailPair right_, left_;
  TrackWheelsetParameters parameters_;
  double nominal_axle_height_m_ = 0.0;
  double flange_steepest_y_m_[2] = {0.0, 0.0};
  double flange_steepest_angle_rad_[2] = {0.0, 0.0};
};

}  // namespace railcontact
