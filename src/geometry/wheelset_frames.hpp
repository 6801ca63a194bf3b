#pragma once
// One wheel of a wheelset over its rail at one position, in the track frame (docs/WHEELSET.md
// §1–4): the placement of the two profiles, the wheel's contact locus, the reference point of an
// interpenetration region and the exact undeformed distance along a region's normal.
//
// Placement (σ = −1 for the right side, +1 for the left):
//   rail profile point (y_p, z_p)  ->  track (σ (R0 + y_p), −z_p),   R0 = gauge/2 − y_gauge point;
//   wheel profile point (y_w, z_w) ->  axial coordinate s = σ (W0 + y_w) along the axle from the
//                                      wheelset centre, radius r = r0 + z_w − z_w(taping line),
//                                      W0 = flange-back distance / 2 − y_w(flange back).
#include <array>
#include <cstddef>
#include <functional>
#include <vector>

#include "railcontact/wheelset_geometry.hpp"

namespace railcontact::geometry {

inline double side_sign(WheelSide side) { return side == WheelSide::right ? -1.0 : 1.0; }
inline double wheel_origin_offset_m(const TrackWheelsetParameters& p) {
  return 0.5 * p.flange_back_distance_m - p.flange_back_y_m;
}
inline double rail_origin_offset_m(const WheelRailPair& pair, const TrackWheelsetParameters& p) {
  return 0.5 * p.track_gauge_m - pair.rail_gauge_point_y_m();
}

inline double dot(const Vector3& a, const Vector3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vector3 cross(const Vector3& a, const Vector3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

class WheelOnRail {
 public:
  WheelOnRail(const WheelsetTrack& track, WheelSide side, const WheelsetPosition& position);

  // The locus sample at wheel profile parameter s (arc length); false when the wheel's normal
  // cannot be perpendicular to the track there, or there is no rail below the locus point.
  bool locus_sample(double wheel_parameter_m, ContactLocusSample& sample) const;

  // The region of the locus samples first..last (all overlapping ends included): weighted
  // averages, frame and tangent-plane bounding box.
  [[nodiscard]] InterpenetrationRegion region(const std::vector<ContactLocusSample>& locus, std::size_t first,
                                              std::size_t last, ReferenceWeighting weighting) const;

  // Rail surface on the normal line through tangent-plane coordinate x2 of a region: its
  // coordinate t along X3 from the reference point. rail_parameter: guess in, root out.
  [[nodiscard]] double rail_normal_m(const InterpenetrationRegion& region, double x2_m, double& rail_parameter) const;
  // Wheel surface on the normal line through (x1, x2): t along X3. t and wheel_parameter: guesses
  // in, roots out. Throws Error when the line misses the wheel.
  double wheel_normal_m(const InterpenetrationRegion& region, double x1_m, double x2_m, double& t_m,
                        double& wheel_parameter) const;

  // The rail and wheel surfaces across one strip of a conformal surface (docs/WHEELSET.md §4
  // "Conformal contact"): the rail point at rail profile parameter u (the reference point's x),
  // the wheel point on the rail's normal line through it, and both surfaces' unit normals oriented
  // as a region's X3 (from the rail into the wheel). wheel_parameter: guess in, root out. Throws
  // Error when the line misses the wheel.
  struct SurfacePair {
    Vector3 rail_point{}, rail_normal{}, wheel_point{}, wheel_normal{};
  };
  [[nodiscard]] SurfacePair surface_pair(const InterpenetrationRegion& region, double rail_parameter,
                                         double& wheel_parameter) const;

  [[nodiscard]] const SmoothProfile& wheel() const { return *wheel_; }
  [[nodiscard]] const SmoothProfile& rail() const { return *rail_; }
  [[nodiscard]] double sign() const { return sign_; }

 private:
  // Stages of region(): the rail surface point at track x and rail profile position y (track
  // frame); the reference point and contact frame from the region's averages; the bounding box.
  [[nodiscard]] Vector3 rail_point_track_m(double x_m, double rail_profile_y_m) const;
  [[nodiscard]] Vector3 rail_point_at_parameter_m(double x_m, double rail_parameter_m) const;  // the same, its parameter known
  void set_contact_frame(double x_reference_m, InterpenetrationRegion& r) const;
  void set_tangent_plane_box(const std::vector<ContactLocusSample>& locus, std::size_t first, std::size_t last,
                             double x_reference_m, InterpenetrationRegion& r) const;

  const SmoothProfile* wheel_;
  const SmoothProfile* rail_;
  WheelSide side_;
  double sign_;
  double wheel_offset_m_, rail_offset_m_;
  double nominal_radius_m_, radius_datum_z_m_;  // r0, and the wheel profile's z where the radius is r0
  Vector3 centre_{};  // wheelset centre, track frame
  Vector3 axle_{};    // unit axle direction
  Vector3 down_{};    // unit vector perpendicular to the axle, as close to −z as possible
  Vector3 ahead_{};   // axle × down: perpendicular to both, close to −x
};

// A potential area's size in elements along one axis: n rounded up to a multiple of the largest
// power of two g with 16 g <= n (1 below 32 elements), at most a sixteenth more. From one time step
// to the next the overlap's extent moves by an element or two, and a size that stays the same
// keeps the normal solver's plan (kernels, FFT plans) of the previous step.
int round_up_to_granule(int n);

// A potential contact area grown around a region's overlap (docs/WHEELSET.md §4): a mesh of
// dx1 x dx2 elements (centres at integer multiples from the reference point) over the region's
// bounding box and a border of border_elements, in whole granules, filled by `fill` (h_m, and the
// strips of a conformal area), grown by a quarter on each side the overlap (h < 0) reaches the
// border, at most 8 times. `what` and `where` name it in messages ("potential contact area", "in
// the tangent plane").
struct GrowingArea {
  const InterpenetrationRegion& region;
  double dx1_m, dx2_m;
  int border_elements;
  const char* what;
  const char* where;
};
using AreaFiller = std::function<void(const Mesh& mesh, TangentPlaneArea& area)>;
TangentPlaneArea grown_area(const GrowingArea& growing, const AreaFiller& fill);
inline constexpr int kMaximumGrowthSteps = 8;

// Along a strip of a mesh h varies on the scale of the wheel's radius: the exact root is found at
// some elements (`march`: from the middle element outwards, each direction every stride-th
// element and the strip's end) and the others take Lagrange's quintic through the six nearest
// roots (`interpolation`). The same on every strip of a mesh: made once per mesh.
struct StripRoots {
  struct Interpolated {
    int i1;
    static constexpr int kPoints = 6;  // the quintic through the six nearest roots
    std::array<int, kPoints> root{};  // i1 of the roots (unused ones repeat the last, with weight 0)
    std::array<double, kPoints> weight{};
  };
  int middle = 0;
  std::array<std::vector<int>, 2> march;  // towards +x1, towards −x1
  std::vector<Interpolated> interpolation;
};
StripRoots strip_roots(const Mesh& mesh);

// The undeformed distance along a region's X3 on the strips of a mesh (docs/WHEELSET.md §4):
// strip i2 at tangent-plane coordinate strip_x2_m[i2], each element at x1 = mesh.x1(i1); strips
// whose x2 is NaN are left as they are in h (mesh.index() order, sized by the caller). `roots`:
// strip_roots(mesh), made once where the function is called strip by strip.
void undeformed_distance_on_strips(const WheelOnRail& w, const InterpenetrationRegion& region, const Mesh& mesh,
                                   const std::vector<double>& strip_x2_m, std::vector<double>& h,
                                   const StripRoots* roots = nullptr);

}  // namespace railcontact::geometry
