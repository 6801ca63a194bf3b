#pragma once
// Stage: geometry, the wheelset level (docs/CONTACT_GEOMETRY.md). The rigid contact geometry of a
// wheelset on its track, the everyday tool of wheel–rail engineers: for a lateral displacement y
// (yaw zero) the wheelset rests on both rails, wheels and rails rigid (no elastic approach), and
// each wheel touches its rail at one point: the contact points on wheel and rail, the contact
// angles, the rolling radii, the rolling-radius difference Δr(y) and the roll angle φ(y); and the
// equivalent conicity tan γe(ŷ) of EN 15302 from Δr(y).
//
// Sign conventions (track frame of wheelset_geometry.hpp: y to the LEFT, z UP):
// - y > 0: the wheelset displaced to the left, the left wheel's flange towards the left rail.
// - Δr = r_left − r_right. The wheel displaced towards its flange rolls on a larger radius, so
//   Δr(y) > 0 for y > 0 on every ordinary wheelset (Δr = 2 y tan γ0 for cones of angle γ0).
// - Contact angle γ: the rail's normal into the wheel at the contact point, from the vertical,
//   positive when it leans towards the track centre (both wheels alike), in the track frame.
// - Roll φ: about x, positive when the left wheel rises (WheelsetPosition::roll_rad).
#include <vector>

#include "railcontact/wheelset_geometry.hpp"

namespace railcontact {

// Options of the rigid contact search.
struct RigidContactOptions {
  // Spacing (arc length along the wheel profile) of the samples of the contact locus on which the
  // lowest point of the gap is looked for; the point found is then refined between its neighbours
  // to a fraction of a micrometre.
  double locus_step_m = 0.2e-3;
};
void validate(const RigidContactOptions& options);

// The contact point of one wheel with its rail.
struct RigidWheelContact {
  WheelSide side = WheelSide::right;
  double wheel_profile_y_m = 0.0;  // on the wheel profile (the wheel's profile frame)
  double wheel_profile_z_m = 0.0;
  double rail_profile_y_m = 0.0;   // on the rail profile (the rail's profile frame)
  double rail_profile_z_m = 0.0;
  Vector3 point_track_m{};         // the contact point, track frame (x = 0: under the axle)
  double contact_angle_rad = 0.0;  // γ (see the top of this header)
  double rolling_radius_m = 0.0;   // the wheel's radius at the contact point
};

// The wheelset at one lateral displacement resting on both rails.
struct RigidContactGeometry {
  double lateral_displacement_m = 0.0;
  double vertical_displacement_m = 0.0;  // of the wheelset centre above its nominal height (+ up)
  double roll_rad = 0.0;                 // φ, + the left wheel up
  RigidWheelContact right, left;
  double rolling_radius_difference_m = 0.0;  // Δr = r_left − r_right
};

// The rigid contact geometry at lateral displacement y (yaw 0): roll and vertical displacement are
// solved so that both wheels touch their rails (both smallest gaps zero), and each contact point
// is the point of first touch, the lowest point of the vertical gap along the wheel's contact
// locus. Throws Error (invalid_input) when y is not finite or larger than 0.1 m, when the contact
// reaches the end of a profile or climbs beyond the flange's steepest point (the wheelset off its
// track: y beyond flange contact), or (no_contact) when wheel and rail do not overlap laterally.
RigidContactGeometry rigid_contact_geometry(const WheelsetTrack& track, double lateral_displacement_m,
                                            const RigidContactOptions& options = {});

// y_from, y_from + step, ... up to y_to (inclusive within a millionth of the step). Throws Error
// (invalid_input) naming the value unless y_from < y_to and 0 < step <= y_to − y_from, at most
// 100000 positions.
std::vector<RigidContactGeometry> rigid_contact_sweep(const WheelsetTrack& track, double y_from_m, double y_to_m,
                                                      double y_step_m, const RigidContactOptions& options = {});

// Δr(y) tabulated on increasing y, linear between the samples.
class RollingRadiusDifference {
 public:
  // Throws Error (invalid_input) unless there are at least 3 finite samples, y strictly increasing.
  RollingRadiusDifference(std::vector<double> y_m, std::vector<double> delta_r_m);
  explicit RollingRadiusDifference(const std::vector<RigidContactGeometry>& sweep);

  [[nodiscard]] double y_min_m() const { return y_m_.front(); }
  [[nodiscard]] double y_max_m() const { return y_m_.back(); }
  [[nodiscard]] const std::vector<double>& y_m() const { return y_m_; }
  [[nodiscard]] const std::vector<double>& delta_r_m() const { return delta_r_m_; }
  // Δr at y (linear interpolation; y must lie in [y_min, y_max]).
  [[nodiscard]] double operator()(double y_m) const;
  // ∫_{y_min}^{y} Δr dy (exact for the piecewise linear Δr).
  [[nodiscard]] double integral_m2(double y_m) const;
  // The zero of Δr nearest to y = 0 (interpolated), where the wheelset runs centred. Throws Error
  // (invalid_input) when Δr does not change sign from − to + in the table.
  [[nodiscard]] double centre_m() const;

 private:
  std::vector<double> y_m_, delta_r_m_;
  std::vector<double> integral_m2_;  // at the samples
  [[nodiscard]] std::size_t segment(double y_m) const;
};

// Options of the equivalent conicity.
struct EquivalentConicityOptions {
  // Integration points over one half-wave (the wavelength's integral) and over one period (the
  // regression); both integrands are sampled at the midpoints of equal steps in phase.
  int integration_points = 4000;
};

// The equivalent conicity at one amplitude ŷ (docs/CONTACT_GEOMETRY.md §3).
struct EquivalentConicity {
  double amplitude_m = 0.0;
  // EN 15302's definition: the conicity of the coned wheelset whose kinematic (Klingel) motion has
  // the same wavelength as this wheelset's at amplitude ŷ, the wavelength found by integrating the
  // nonlinear kinematic equation y'' = −Δr(y) / (2 e0 r0) (EN 15302 Annex B):
  //   tan γe = π² / (∫ dy / sqrt(E − V(y)))²  over the half-wave from y_low to y_high,
  // V(y) = ∫ Δr dy, E = V(y_low) = V(y_high), y_high − y_low = 2 ŷ (independent of e0 r0).
  double tan_gamma_e_wavelength = 0.0;
  double turning_point_low_m = 0.0, turning_point_high_m = 0.0;
  // The alternative: half the slope of the least-squares line through Δr(y) sampled uniformly in
  // time over one sinusoidal cycle y = y_c + ŷ sin θ (the linear regression of EN 15302 Annex C,
  // weighted by the time the wheelset spends at each y), y_c the zero of Δr (centre_m()).
  double tan_gamma_e_regression = 0.0;
  double centre_m = 0.0;
  // The wavelength of a wheelset of half contact distance e0 and radius r0 follows from either:
  // L = 2π sqrt(e0 r0 / tan γe) (Klingel).
};

// Throws Error (invalid_input) naming the amplitude and the allowed range when ŷ is not positive or
// the motion of amplitude ŷ reaches beyond the tabulated Δr, or when Δr does not rise through zero.
EquivalentConicity equivalent_conicity(const RollingRadiusDifference& delta_r, double amplitude_m,
                                       const EquivalentConicityOptions& options = {});

// The largest amplitude equivalent_conicity accepts for this Δr table (both methods), 0 if none.
double largest_conicity_amplitude_m(const RollingRadiusDifference& delta_r);

// Klingel: the wavelength L = 2π sqrt(e0 r0 / tan γe) of the kinematic motion.
double klingel_wavelength_m(double tan_gamma_e, double half_contact_distance_m, double rolling_radius_m);

}  // namespace railcontact
