#pragma once
// Stage: geometry. Wheel and rail profiles (readers, smoothing), the wheel–rail pair on the track,
// the contact point, and the undeformed distance h(x1, x2) on a potential contact area
// (docs/GEOMETRY.md; the wheel–rail pipeline on top of it: wheel_rail.hpp).
#include <array>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "railcontact/contact_patch.hpp"

// Wheel and rail cross-section profiles (METHOD.md §9, docs/GEOMETRY.md): readers for the
// SIMPACK (.prw/.prr), MiniProf (.ban/.whl) and plain two-column text formats, and a smooth
// parametric representation (a penalised least-squares cubic B-spline in arc length) that gives
// z(y), dz/dy, d2z/dy2 and the curvature.
//
// Profile frame (the SIMPACK convention, docs/GEOMETRY.md §1): lengths in metres; y lateral,
// z vertical pointing DOWN (into the rail for a rail profile, radially outward for a wheel
// profile), x = y × z along the track in the direction of travel. For the wheel–rail geometry a
// profile must be oriented as the shipped files are: a wheel's flange and a rail's gauge face
// on the side of negative y (the side towards the track centre), the wheel's taping line at
// the origin (70 mm from the flange back).

namespace railcontact {

enum class ProfileKind { unknown, wheel, rail };

// What curated() changed in a profile's point list (docs/GEOMETRY.md §8 "Measured profiles").
struct ProfileCuration {
  int zigzags_repaired = 0;         // pairs of stitched points replaced by their mean
  double largest_overhang_m = 0.0;  // the largest lateral fold-back of the points read (undercut)
  std::size_t hidden_points = 0;    // points dropped behind the envelope the other body sees
  double hidden_from_y_m = 0.0;     // ... their lateral range (profile frame), when any
  double hidden_to_y_m = 0.0;
  [[nodiscard]] bool changed() const { return zigzags_repaired > 0 || hidden_points > 0; }
};

// A profile as a point list in the profile frame (metres), in file order after the file's own
// processing flags (SIMPACK mirroring, inversion, units) have been applied.
struct Profile {
  std::vector<double> y_m;
  std::vector<double> z_m;
  ProfileKind kind = ProfileKind::unknown;
  std::string source;  // file name (or a description) used in error messages
  ProfileCuration curation;  // what read_profile's curation changed (nothing for a clean profile)

  [[nodiscard]] std::size_t size() const { return y_m.size(); }
};

// The curation of a measured profile (docs/GEOMETRY.md §8 "Measured profiles").
struct ProfileCurationOptions {
  // Two consecutive points at which the direction turns back by more than 150 degrees (a point
  // stitched twice where two measured sections meet) are replaced by their mean.
  bool repair_zigzags = true;
  // A profile that folds back laterally by more than ProfileLimits::max_lateral_retreat_m (an
  // undercut) is replaced by its envelope on the side the other body sees (a wheel's from below, a
  // rail's from above): the points behind it cannot be touched by a body approaching from that
  // side and are dropped. Needs the profile's role (a wheel or a rail).
  bool hide_undercuts = true;
  // More hidden points than this share of the profile is refused: the profile is upside down or
  // given in the other body's role.
  double max_hidden_fraction = 0.5;
};

// The profile with its zig-zags repaired and its undercuts hidden (the report in .curation);
// role: the profile's role in the pair (unknown: its file's kind; no envelope when both are
// unknown). A profile without these faults is returned unchanged, point for point. Throws Error
// when more than max_hidden_fraction of the points would be hidden.
Profile curated(Profile profile, ProfileKind role = ProfileKind::unknown, const ProfileCurationOptions& options = {});

// Options of the readers.
struct ProfileReadOptions {
  // Length unit of the columns of plain two-column text files (default: millimetres).
  double text_length_unit_m = 1e-3;
  // MiniProf files come with either vertical orientation (measured rails: Y up; wheels and
  // converted files: Y down). When true, a profile whose shape shows Y pointing up (a rail whose
  // highest point is an interior maximum, a wheel whose flange tip is an interior minimum) is
  // rotated by 180 degrees about the longitudinal axis (y -> -y, z -> -z).
  bool miniprof_auto_vertical = true;
  // Applied after reading, to any format: y -> -y and/or z -> -z.
  bool mirror_y = false;
  bool mirror_z = false;
  // The profile's role where the caller knows it (the wheel or the rail of a pair); unknown: the
  // file's own kind (SIMPACK type, MiniProf extension). Decides the side of the curation's envelope.
  ProfileKind role = ProfileKind::unknown;
  // Applied last, before the checks (validate).
  ProfileCurationOptions curation{};
};

// Reads a profile, choosing the format by the file extension (case-insensitive):
// .prw/.prr SIMPACK, .ban/.whl MiniProf, anything else plain two-column y z text.
// Throws Error("profile <file>:<line>: ...") for unreadable or malformed files.
Profile read_profile(const std::filesystem::path& path, const ProfileReadOptions& options = {});

// SIMPACK rail/wheel profile (.prr/.prw): header.begin/end (type 0 rail, 1 wheel) and
// spline.begin/end with the processing flags and the point.begin/end list (y z [weight]).
// Honours, in the order numbered in the file's own comments: point.dist.min, shift.y/z,
// bound.y/z (active when min < max), mirror.y/z, inversion, units.len.f. A non-zero rotate is
// rejected.
Profile read_simpack_profile(const std::filesystem::path& path);

// MiniProf profile (.ban rail, .whl wheel): a header of Key=Value lines (and, in old-style
// files, free text), a blank line, then one point per line; comments start with ", ! or %;
// columns are named by ColumnDef (default "X,Y"): X lateral, Y vertical, in millimetres.
Profile read_miniprof_profile(const std::filesystem::path& path, bool auto_vertical = true);

// Plain text: one point per line, the first two numbers (separated by blanks or commas) are y
// and z in units of length_unit_m; blank lines and lines starting with #, ! or % are skipped.
Profile read_text_profile(const std::filesystem::path& path, double length_unit_m = 1e-3);

// Writes the two-column text format read by read_text_profile (17 significant digits).
void write_text_profile(const std::filesystem::path& path, const Profile& profile, double length_unit_m = 1e-3);

// y -> -y (mirror about the vertical axis) / z -> -z; the point order is kept.
Profile mirrored_y(Profile profile);
Profile mirrored_z(Profile profile);

// What a wheel or rail profile's point list must satisfy (docs/GEOMETRY.md §8): checked by
// validate, by every reader and by SmoothProfile, before a spline is built.
struct ProfileLimits {
  static constexpr std::size_t max_points = 100000;
  // The lateral span (max y - min y) and the vertical span (max z - min z) of the points: a
  // tenth of these or a thousand times them is the tell-tale of a wrong length unit.
  static constexpr double min_lateral_extent_m = 0.010;
  static constexpr double max_lateral_extent_m = 0.400;
  static constexpr double max_vertical_extent_m = 0.200;
  // Consecutive points: further apart than coincident_m, at most max_point_gap_m apart, and the
  // direction of the point list turns by less than 150 degrees at every point.
  static constexpr double coincident_m = 1e-12;
  static constexpr double max_point_gap_m = 0.010;
  static constexpr double min_turn_cosine = -0.8660254037844386;  // cos 150°
  // The length of the polyline through the points.
  static constexpr double max_length_m = 1.0;
  // The self-intersection check compares the segments that overlap laterally, at most this often.
  static constexpr std::size_t max_crossing_comparisons = 20000000;
  // The contact search takes a profile as a graph z(y), each y once: the points may go back
  // laterally (an undercut gauge face or flange, which overhangs) by at most this much, the noise of
  // a measured near-vertical flank; a larger undercut would drop the overhang from the graph.
  static constexpr double max_lateral_retreat_m = 0.05e-3;
};

// Throws Error unless the profile is a plausible wheel or rail profile: as many y as z, 4 to
// ProfileLimits::max_points finite points spanning 10 to 400 mm laterally and at most 200 mm
// vertically (else the message suggests a wrong length unit), consecutive points distinct and at
// most 10 mm apart, no reversal of direction (more than 150 degrees) at a point, a polyline at
// most 1 m long that does not cross itself, and no undercut: y monotonic along the points within
// max_lateral_retreat_m. The message names the points at fault.
void validate(const Profile& profile);

// Smoothing of the point list (docs/GEOMETRY.md §5).
struct SmoothingOptions {
  // The spline minimises  sum_i w_i |C(s_i) - P_i|^2 + L^(2m) ∫ |d^m C/ds^m|^2 ds
  // (w_i: arc length per point, s: chord length, m = penalty_derivative): a smoothing spline
  // whose transfer function is 1 / (1 + (L ω)^(2m)). Features shorter than about 2π L are
  // smoothed away; circular arcs of radius R keep their curvature up to about (L/R)^(2m).
  double smoothing_length_m = 0.5e-3;
  // Spacing of the (uniform) B-spline knots in arc length; should not exceed smoothing_length.
  double knot_spacing_m = 0.25e-3;
  // Order m of the penalised derivative (1..3); 2 is the classical cubic smoothing spline.
  int penalty_derivative = 2;
};

// Derivatives of the parametric curve C(s) = (y(s), z(s)) at one parameter value.
struct ProfileCurvePoint {
  double s_m = 0.0;
  double y_m = 0.0, z_m = 0.0;
  double dy_ds = 0.0, dz_ds = 0.0;            // first derivatives (-)
  double d2y_ds2_per_m = 0.0, d2z_ds2_per_m = 0.0;  // second derivatives (1/m)
};

// The smooth representation of a profile: a cubic B-spline curve in (chord-)arc length s,
// oriented so that y grows with s (the point order is reversed if needed). Immutable and cheap
// to copy (shared state). The graph form z(y) is defined for y in [y_min_m(), y_max_m()]; where
// the curve turns back laterally (undercuts) it uses the first branch met from y_min.
class SmoothProfile {
 public:
  SmoothProfile() = default;
  explicit SmoothProfile(const Profile& profile, const SmoothingOptions& options = {});

  [[nodiscard]] const std::string& source() const;
  [[nodiscard]] ProfileKind kind() const;

  // Parametric form.
  [[nodiscard]] double s_begin_m() const;
  [[nodiscard]] double s_end_m() const;
  [[nodiscard]] ProfileCurvePoint at(double s_m) const;  // s is clamped to [s_begin, s_end]
  // Signed curvature (y' z'' - z' y'') / (y'^2 + z'^2)^(3/2) (1/m): positive where the
  // curve bends towards +z (a rail crown, z down, has positive curvature).
  [[nodiscard]] double curvature_at(double s_m) const;

  // Graph form z(y).
  [[nodiscard]] double y_min_m() const;
  [[nodiscard]] double y_max_m() const;
  [[nodiscard]] double parameter_at(double y_m) const;  // s with y(s) = y (throws outside)
  [[nodiscard]] double z(double y_m) const;
  [[nodiscard]] double dz_dy(double y_m) const;
  [[nodiscard]] double d2z_dy2_per_m(double y_m) const;
  [[nodiscard]] double curvature_per_m(double y_m) const;  // same sign convention as above

  struct Impl;

 private:
  std::shared_ptr<const Impl> impl_;
  [[nodiscard]] const Impl& impl() const;
};

}  // namespace railcontact

// Wheel–rail contact geometry of one wheel–rail pair (METHOD.md §2, §9; docs/GEOMETRY.md):
// wheelset position on the track, the contact point, contact angle, rolling radius, and the
// undeformed distance h(x1, x2) in the tangent plane of the contact.
//
// Frames (docs/GEOMETRY.md §1–3):
// - Track frame: x along the track in the direction of travel, y lateral to the LEFT, z UP.
// - The modelled pair is the RIGHT wheel on the RIGHT rail (looking in the direction of travel).
// - Both profiles are given in their profile frames (geometry.hpp): y_p to the right (away from
//   the track centre, towards the field side), z_p down — the track frame turned by 180° about x.
// - Wheelset lateral displacement y (m) along the track y axis: y < 0 moves the wheelset to the
//   right, the right wheel's flange towards the right rail's gauge face, and the contact point
//   towards the flange (on the rail: towards the gauge corner).
// - Contact frame: X1 = x (rolling direction); X3 = the contact normal pointing into the wheel;
//   X2 = X3 × X1 lies in the tangent plane and points towards the flange / gauge side. Origin:
//   the point of first touch (the normal solver may move it to the centre of pressure).
// - Contact angle γ: the angle of the common tangent from the horizontal track plane, positive
//   when the normal into the wheel leans towards the track centre (the flange side), so
//   X3 = (0, sin γ, cos γ) and X2 = (0, cos γ, −sin γ) in the track frame.


namespace railcontact {

// Where the nominal rolling radius r0 is measured on the wheel profile (docs/WHEEL_RAIL.md §12):
// - profile_origin: at the profile's origin, the point (0, 0) of its coordinates: the wheel's
//   radius at profile point (y, z) is r0 + z (z down). The default, as in Kalker's CONTACT
//   (NOMRADW) and the multibody codes' profile conventions.
// - taping_line: at the wheel's surface on the taping line (taping_line_from_flange_back_m from the
//   flange back): r0 + z − z(taping line).
// On a new S1002 drawn with its origin on the taping line the two agree; on a measured, hollow-worn
// wheel they differ by the wear depth there (1.2 mm moves ξ by 2.6e-3).
enum class NominalRadiusDatum { profile_origin, taping_line };
// "profile-origin" / "taping-line"
const char* nominal_radius_datum_name(NominalRadiusDatum datum);
// Throws Error (invalid_input) naming the allowed names.
NominalRadiusDatum parse_nominal_radius_datum(const std::string& name);

// Track and wheelset data (METHOD.md §9 defaults). By default (rail_cant_rad = 0) the rail
// inclination is part of the rail profile's coordinates (the shipped UIC60 is inclined 1:40) and
// is not applied again; a non-zero rail_cant_rad inclines the rail profile (canted_rail_profile).
struct TrackWheelsetParameters {
  double track_gauge_m = 1.435;               // between the gauge faces ...
  double gauge_measuring_depth_m = 0.014;     // ... measured this far below the top of the rails
  double flange_back_distance_m = 1.360;      // between the flange backs of the wheelset
  double flange_back_y_m = -0.070;            // the flange back in the wheel profile frame
  double taping_line_from_flange_back_m = 0.070;  // lateral distance flange back -> taping line
  double nominal_rolling_radius_m = 0.46;     // wheel radius r0 at nominal_radius_at
  NominalRadiusDatum nominal_radius_at = NominalRadiusDatum::profile_origin;
  // Rail inclination (cant) towards the track centre, applied to the rail profile before anything
  // else uses it (canted_rail_profile): atan(1/40) = 0.0249948 for an upright rail laid at 1:40;
  // 0 uses the rail profile as given.
  double rail_cant_rad = 0.0;
};

// The physical ranges of the track and wheelset data (m; docs/RELIABILITY.md "Values and solvers"):
// - track gauge [0.38, 2.2]: from the 15-inch minimum gauge (381 mm) to Brunel's 7 ft 1/4 in
//   (2140 mm); 1.435 standard, 1.000, 1.067, 1.520, 1.668 in use;
// - gauge measuring depth [0.001, 0.03]: within the rail head's gauge corner (EN 13848 14 mm, AREMA
//   5/8 in = 15.9 mm);
// - flange-back distance [0.3, 2.2], and the gauge minus it in [0.02, 0.2]: two flanges (about
//   30 mm thick each) and their play (1435 - 1360 = 75 mm);
// - flange-back position in the wheel profile frame [-0.2, 0.2] and taping line from the flange
//   back [0.01, 0.2]: within a wheel profile (at most 0.4 m wide, Profile; a wheel's tread is
//   about 135 mm, the taping line 70 mm from the back);
// - nominal rolling radius [0.04, 1.5]: from a 1:10 scale roller-rig wheel to a steam locomotive's
//   driving wheel (about 1.15 m); 0.46 for a new UIC freight or passenger wheel;
// - rail cant |cant| <= 0.1 rad (1:10, twice the steepest in use): the rail inclinations in use are
//   0 (vertical), 1:40, 1:30 and 1:20 (0.05 rad). The message of a value in [10, 100] reads it as a
//   ratio's denominator (40: 1:40 is atan(1/40) = 0.0249948 rad), of one up to 5.73 as degrees;
//   the ratio itself (0.025 for 1:40) lies within 5e-6 rad of the angle and is accepted.
// A value above a range that would lie in it in millimetres is said to be (a value of 46 for
// nominal_rolling_radius_m ran as a 46 m wheel).
inline constexpr double kMinimumTrackGauge_m = 0.38, kMaximumTrackGauge_m = 2.2;
inline constexpr double kMinimumGaugeMeasuringDepth_m = 0.001, kMaximumGaugeMeasuringDepth_m = 0.03;
inline constexpr double kMinimumFlangeBackDistance_m = 0.3, kMaximumFlangeBackDistance_m = 2.2;
inline constexpr double kMinimumGaugeMinusFlangeBack_m = 0.02, kMaximumGaugeMinusFlangeBack_m = 0.2;
inline constexpr double kMaximumFlangeBackPosition_m = 0.2;
inline constexpr double kMinimumTapingLineFromFlangeBack_m = 0.01, kMaximumTapingLineFromFlangeBack_m = 0.2;
inline constexpr double kMinimumNominalRollingRadius_m = 0.04, kMaximumNominalRollingRadius_m = 1.5;
inline constexpr double kMaximumRailCant_rad = 0.1;

// Throws Error (invalid_input) unless every field lies in its range above; the message names the
// field with `prefix` before it, e.g. "rc_track_parameters." or "" (the set-up file's keys are
// the field names): "nominal_rolling_radius_m = 46 m must lie in [0.04, 1.5] m (…)".
void validate(const TrackWheelsetParameters& parameters, std::string_view prefix = "track parameters: ");
// The rail cant's part of validate, for an input of another name (a command-line option): throws
// Error (invalid_input) "<name> = 40 rad must lie in [-0.1, 0.1] rad (…); … 1:40 is atan(1/40) = …".
void validate_rail_cant(double cant_rad, std::string_view name);

// The rail profile inclined by cant_rad towards the track centre (docs/GEOMETRY.md §1): every point
// turned about the profile's origin so that the rail's upward axis leans to the gauge side (-y),
//   y' = y cos c + z sin c,   z' = -y sin c + z cos c   (y to the field side, z down),
// which turns the head's crown to face the track centre and moves its highest point towards the
// field side (by about R_crown sin c: 7.5 mm for the R300 crown at 1:40). cant_rad = 0 returns
// the profile unchanged. Throws Error (invalid_input) unless |cant_rad| <= kMaximumRailCant_rad.
Profile canted_rail_profile(Profile rail, double cant_rad);

// The geometric contact point of one lateral displacement.
struct WheelRailContactPoint {
  double lateral_displacement_m = 0.0;  // wheelset y (track frame, positive to the left)
  double y_rail_m = 0.0;    // contact point in the rail profile frame
  double z_rail_m = 0.0;
  double y_wheel_m = 0.0;   // contact point in the wheel profile frame
  double z_wheel_m = 0.0;
  double y_track_m = 0.0;   // lateral position in the track frame (from the centreline, left +)
  double contact_angle_rad = 0.0;   // γ, see above
  double rolling_radius_m = 0.0;    // wheel radius at the contact point
  // Vertical position of the wheel profile frame in the rail profile frame after lowering the
  // wheel onto the rail (z_p of the wheel origin; z_p points down).
  double wheel_drop_m = 0.0;
  // Offset from wheel to rail profile coordinates: y_rail = y_wheel + wheel_to_rail_offset.
  double wheel_to_rail_offset_m = 0.0;
  // Lateral curvatures of the profiles at the contact (signed, profile frame, 1/m; see
  // SmoothProfile::curvature_at) and the quadratic form of h at the contact:
  // h ≈ A x1² + B x2² with A = cos γ / (2 r), B = (κ_rail − κ_wheel) / 2.
  double rail_curvature_per_m = 0.0;
  double wheel_curvature_per_m = 0.0;
  double A_per_m = 0.0;
  double B_per_m = 0.0;
  // Contact frame axes in the track frame (x, y, z).
  std::array<double, 3> x2_axis_track{};
  std::array<double, 3> x3_axis_track{};
  // Second-lowest local minimum of the vertical gap more than 1 mm away laterally (a candidate
  // second contact point): its gap (m) and rail position; gap = +inf when there is none.
  double secondary_gap_m = 0.0;
  double secondary_y_rail_m = 0.0;
};

// One wheel–rail pair: the two smoothed profiles placed on the track.
class WheelRailPair {
 public:
  // Throws Error when a profile is not oriented as documented (flange / gauge side at -y, z
  // down) or the taping line / gauge point cannot be found.
  WheelRailPair(const Profile& wheel, const Profile& rail, const TrackWheelsetParameters& parameters = {},
                const SmoothingOptions& smoothing = {});

  [[nodiscard]] const SmoothProfile& wheel() const { return wheel_; }
  [[nodiscard]] const SmoothProfile& rail() const { return rail_; }
  [[nodiscard]] const TrackWheelsetParameters& parameters() const { return parameters_; }

  // Rail: highest point (z_p minimum) and the gauge point (gauge side, measuring depth below
  // the top), profile frame. Wheel: taping line (y_p, z_p) in the wheel profile frame.
  [[nodiscard]] double rail_top_z_m() const { return rail_top_z_m_; }
  [[nodiscard]] double rail_gauge_point_y_m() const { return rail_gauge_y_m_; }
  [[nodiscard]] double taping_line_y_m() const { return taping_y_m_; }
  [[nodiscard]] double taping_line_z_m() const { return taping_z_m_; }
  // The wheel profile's z at which the wheel's radius is r0 (parameters().nominal_radius_at): 0 at
  // the profile origin, z_w(taping line) at the taping line.
  [[nodiscard]] double nominal_radius_z_m() const {
    return parameters_.nominal_radius_at == NominalRadiusDatum::profile_origin ? 0.0 : taping_z_m_;
  }
  // Wheel radius at wheel profile position y (r0 + z_w(y) − nominal_radius_z_m()).
  [[nodiscard]] double wheel_radius_m(double y_wheel_m) const;

  // Lowers the wheel (vertically, zero roll and yaw) onto the rail until first touch at
  // wheelset displacement y. Throws Error when the profiles never touch (no lateral overlap) or
  // first touch is at the end of a profile (no common tangent).
  [[nodiscard]] WheelRailContactPoint contact_point(double lateral_displacement_m) const;

  // Exact undeformed distance (m) at tangent-plane point (x1, x2) of a contact: the distance
  // along the contact normal between the rail surface and the wheel surface on the line
  // through (x1, x2) (docs/GEOMETRY.md §4). Throws Error when the line misses a profile.
  [[nodiscard]] double undeformed_distance(const WheelRailContactPoint& contact, double x1_m, double x2_m) const;

  // h at every element centre of the mesh (X1 rolling, X2 as above), stored as mesh.index().
  [[nodiscard]] std::vector<double> undeformed_distance(const WheelRailContactPoint& contact, const Mesh& mesh) const;

 private:
  SmoothProfile wheel_;
  SmoothProfile rail_;
  TrackWheelsetParameters parameters_;
  double rail_top_z_m_ = 0.0;
  double rail_gauge_y_m_ = 0.0;
  double taping_y_m_ = 0.0;
  double taping_z_m_ = 0.0;
  double wheel_origin_lateral_m_ = 0.0;  // wheel profile origin from the track centreline, outward
  double rail_origin_lateral_m_ = 0.0;   // rail profile origin from the track centreline, outward
};

// Choice of the potential contact area.
struct PotentialAreaOptions {
  // The area holds the region where h < margin_factor × approach (the undeformed
  // interpenetration h < approach holds every contact patch of the normal problem).
  double margin_factor = 1.5;
  // Element sizes: if positive they are used as given; otherwise the interpenetration region
  // (h < approach) spans about elements_across elements along X1 and along X2.
  double dx1_m = 0.0;
  double dx2_m = 0.0;
  int elements_across = 30;
  // Extra elements around the margin region; the area grows while the margin region reaches
  // into this border ring, at most max_growth_steps times.
  int border_elements = 3;
  int max_growth_steps = 10;
};

// A potential contact area with the undeformed distance on it.
struct PotentialContactArea {
  Mesh mesh;
  std::vector<double> h_m;  // at the element centres, mesh.index() order
  int growth_steps = 0;     // how often the area had to be enlarged
};

// The largest potential contact area (mesh elements) a normal problem is set up on, and the
// memory of that problem per element: the wheel–rail normal solve (h, pressures, the CG vectors,
// the FFT influence products on the doubled grid) measured at about 350 bytes per mesh element
// (229 MB of peak memory for the whole `railcontact patch --elements 200000`, a 966 x 648 mesh),
// counted as 400. 4e6 elements are about 1.5 GiB, six times the largest area the allowed
// target_elements (at most 200000 in contact) normally need. A larger area is refused before
// anything is allocated (docs/RELIABILITY.md "Resource limits").
inline constexpr double kMaximumPotentialAreaElements = 4e6;
inline constexpr double kNormalSolveBytesPerElement = 400.0;
// The start of the message of that refusal: "potential contact area: a mesh of …".
inline constexpr std::string_view kPotentialAreaTooLarge = "potential contact area: a mesh of";

// Mesh and h for an approach estimate (m), e.g. Hertz's approach for the local curvatures
// A_per_m, B_per_m of the contact point (hertz_from_curvatures in hertz.hpp). Throws Error
// (invalid_input) "potential contact area: a mesh of N1 x N2 = N elements … needs about X GiB …"
// when the area would need more than kMaximumPotentialAreaElements elements.
PotentialContactArea potential_contact_area(const WheelRailPair& pair, const WheelRailContactPoint& contact,
                                            double approach_m, const PotentialAreaOptions& options = {});

}  // namespace railcontact
