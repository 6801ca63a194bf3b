#pragma once
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
#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace railcontact {

enum class ProfileKind { unknown, wheel, rail };

// A profile as a point list in the profile frame (metres), in file order after the file's own
// processing flags (SIMPACK mirroring, inversion, units) have been applied.
struct Profile {
  std::vector<double> y_m;
  std::vector<double> z_m;
  ProfileKind kind = ProfileKind::unknown;
  std::string source;  // file name (or a description) used in error messages

  [[nodiscard]] std::size_t size() const { return y_m.size(); }
};

// Options of the readers.
struct ProfileReadOptions {
  // Length unit of the columns of plain two-column text files (default: millimetres).
  double text_length_unit_m = 1e-3;
  // MiniProf files come with either vertical orientation (measured rails: Y up; wheels and
  // converted files: Y down). When true, a profile whose shape shows Y pointing up (a rail whose
  // highest point is an interior maximum, a wheel whose flange tip is an interior minimum) is
  // rotated by 180 degrees about the longitudinal axis (y -> -y, z -> -z).
  bool miniprof_auto_vertical = true;
  // Applied last, to any format: y -> -y and/or z -> -z.
  bool mirror_y = false;
  bool mirror_z = false;
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

// Throws Error unless the profile has at least 4 points, finite coordinates, as many y as z.
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
