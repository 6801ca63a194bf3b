#pragma once
// The wheelset evaluated as a whole (docs/WHEELSET.md §5–7): the state of a multibody time step in,
// every contact patch of both wheels and the forces on each wheel out.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "railcontact/tangential.hpp"
#include "railcontact/wheelset_geometry.hpp"
#include "railcontact/wheelset_kinematics.hpp"

namespace railcontact {

// The wheelset's velocities (SI units, rad/s): the rates of WheelsetPosition's coordinates, the
// forward speed and the wheels' rotation.
struct WheelsetVelocity {
  double forward_speed_m_per_s = 20.0;  // V > 0, also the rolling speed of the creepages
  double lateral_velocity_m_per_s = 0.0;
  double vertical_velocity_m_per_s = 0.0;
  double roll_rate_rad_per_s = 0.0;
  double yaw_rate_rad_per_s = 0.0;
  // The wheels' rotation, one of three (docs/WHEELSET.md §5):
  // - pure rolling at the nominal radius r0 with extra_longitudinal_creepage (the default: NaN
  //   angular velocity, wheel_angular_velocity_for_rolling);
  // - a given angular velocity about the axle (rad/s, positive rolling forward);
  // - free rolling: the angular velocity at which the wheels' longitudinal forces have no moment
  //   about the axle (an unbraked, undriven wheelset in steady state), solved by evaluate() and
  //   returned in the result's state; the other two must then be left at their defaults.
  double wheel_angular_velocity_rad_per_s = std::numeric_limits<double>::quiet_NaN();
  double extra_longitudinal_creepage = 0.0;  // ξ0 of the shortcut (< 0 traction, > 0 braking)
  bool free_rolling = false;
};

// The physical ranges of the velocities (docs/RELIABILITY.md "Values and solvers"):
// - forward speed V in (0, 200] m/s: the rail speed record is 160 m/s (574.8 km/h);
// - lateral and vertical velocity of the centre within ±10 m/s: hunting of 10 mm at 10 Hz is
//   0.6 m/s, a wheel flat's impact about 1 m/s;
// - roll and yaw rate within ±10 rad/s: hunting's yaw of 10 mrad at 10 Hz is 0.6 rad/s;
// - the wheels' angular velocity within ±1000 rad/s: 200 m/s on a wheel of 0.2 m radius;
// - the extra longitudinal creepage within ±kMaximumCreepage (0.5), the range of any creepage.
// Within them, a combination can still give a contact a creepage beyond a contact's range (a yaw
// rate of 10 rad/s at 1 m/s): check_kinematic_creepage refuses it before the tangential solve.
inline constexpr double kMaximumForwardSpeed_m_per_s = 200.0;
inline constexpr double kMaximumCentreVelocity_m_per_s = 10.0;
inline constexpr double kMaximumRollYawRate_rad_per_s = 10.0;
inline constexpr double kMaximumWheelAngularVelocity_rad_per_s = 1000.0;

// How the caller named the velocities in its input: the fields (default), a case file's keys or
// the command-line options ("--yaw-rate"), for the messages of validate(WheelsetVelocity).
struct WheelsetVelocityNames {
  std::string forward_speed = "forward_speed_m_per_s";
  std::string lateral_velocity = "lateral_velocity_m_per_s";
  std::string vertical_velocity = "vertical_velocity_m_per_s";
  std::string roll_rate = "roll_rate_rad_per_s";
  std::string yaw_rate = "yaw_rate_rad_per_s";
  std::string wheel_angular_velocity = "wheel_angular_velocity_rad_per_s";
  std::string extra_longitudinal_creepage = "extra_longitudinal_creepage";
  std::string free_rolling = "free_rolling";
};

// Throws Error (invalid_input) unless every velocity lies in its range above (the wheels' angular
// velocity may be NaN: the rolling shortcut); the message names the value as `names` has it:
// "wheelset: yaw_rate_rad_per_s = 1e+06 rad/s must lie in [-10, 10] rad/s (…)", "--yaw-rate 1e+06 rad/s …".
void validate(const WheelsetVelocity& velocity, const WheelsetVelocityNames& names = {});

struct WheelsetState {
  WheelsetPosition position;
  WheelsetVelocity velocity;
};


// The contact surface of each patch (docs/WHEELSET.md §4 "Conformal contact"): planar, the patch
// in the tangent plane at its reference point with one contact angle (Kalker's CONTACT's planar
// approach), or conformal, curved with the profiles across the rolling direction, each strip of
// the patch in its own frame (CONTACT's conformal approach), by every tangential solver (the
// strips' own creepages; nH-FastSim with K2 on the developed patch). automatic chooses per patch:
// planar where its contact angle hardly varies, conformal where it does, both blended between
// (ContactSurfaceSwitch).
enum class ContactSurface { planar, conformal, automatic };
// "planar", "conformal", "auto"
const char* contact_surface_name(ContactSurface surface);
// Throws Error (invalid_input) naming the allowed names.
ContactSurface parse_contact_surface(const std::string& name);

// Where ContactSurface::automatic changes from the planar to the conformal surface
// (docs/WHEELSET.md §4 "Choosing the surface"). Its measure is a patch's contact angle spread over
// the cosine of its contact angle, contact_angle_spread_rad / cos γ: how far the tangent plane
// leaves the surface over the patch, with the leverage a steep flange gives a tilt of the normal
// in the lateral force (F2 ≈ F3 tan γ, d tan γ / dγ = 1 / cos² γ). The spread is continuous in the
// position, so is the choice. Up to planar_up_to a patch is planar, from conformal_from conformal,
// and between the two surfaces' results are blended with a weight rising smoothly (C¹) from 0 to
// 1. Measured on the shipped profile pairs (exact solver, 1461 patches): below 0.02 the planar
// lateral and vertical forces are within 1.0 % of μFz of the conformal ones, from 0.02 to 0.03
// within 1.4 %, and they differ by up to 8.5 % at 0.07 and 61 % in flange contact.
struct ContactSurfaceSwitch {
  double planar_up_to = 0.02;
  double conformal_from = 0.03;
};
void validate(const ContactSurfaceSwitch& s);
// The conformal surface's weight in a patch's results: 0 planar, 1 conformal; for automatic the
// smooth step of ContactSurfaceSwitch over the region's measure (1 where the measure is unknown).
double conformal_surface_weight(ContactSurface surface, const ContactSurfaceSwitch& s,
                                const InterpenetrationRegion& region);

// The normal problem of each wheel: by position (the state's vertical displacement and roll give
// the overlap) or by load (each wheel's vertical force is met by solving its height: the state's
// vertical displacement is ignored; with balance_roll the wheelset's height and roll are solved
// together so that one rigid axle meets both loads).
struct WheelLoads {
  double right_N = 98100.0;
  double left_N = 98100.0;
  // A rigid axle: both loads met by the wheelset's height and roll together (the roll found is the
  // result's state.position.roll_rad). false: each wheel's height is solved on its own (two
  // independent wheels; the result's vertical displacement is then the mean of the two).
  bool balance_roll = false;
};

// The elastic coupling between a wheel's separate patches (docs/WHEELSET.md §5 "Coupled patches"):
// the pressure on each patch lifts the others' surfaces, by the half-space's influence of a point
// load. Its weight fades with the distance between the patches' overlaps (in the track's
// cross-section, y and z): 1 up to full_distance_m, a smoothstep down to 0 at end_distance_m, so the
// forces stay continuous where two overlaps come within the merge distance
// (ContactSearchOptions::merge_distance_m) and become one patch, coupled by its own mesh. Kalker's
// CONTACT solves patches closer than its D_SEP (8 mm by default) on one grid, coupled, and separate
// ones without coupling: the fade is centred on that. Both 0: no coupling.
struct PatchCouplingOptions {
  double full_distance_m = 6e-3;
  double end_distance_m = 10e-3;
};
void validate(const PatchCouplingOptions& options);

struct WheelsetOptions {
  Material material{2.1e11, 0.3};
  double friction_coefficient = 0.3;
  // Square elements of the potential contact areas (0.2 mm: the accuracy targets' mesh).
  double element_size_m = 0.2e-3;
  // The solvers to run on every patch; the first one's forces are the patch's `forces`.
  std::vector<TangentialSolver> solvers{TangentialSolver::nh_fastsim};
  // The solver whose forces the vertical load balance (their vertical components) and free rolling
  // use; one of `solvers`. Unset: the first of them.
  std::optional<TangentialSolver> balance_solver;
  // nH-FastSim with the rigid-slip direction (docs/FASTSIM.md "The slip direction"): within 3 % of
  // the exact solver also on the flange, where Eq 8 misses by up to 4 %, and in full slip under spin,
  // where the flexibility-weighted direction misses by up to 30 %; and with the creepage coupling
  // (docs/FASTSIM.md "The creepage coupling"): K2's F1 per eta and spin, F2 per xi, on patches without
  // symmetry (flanges, comet-shaped treads); and where a patch slips everywhere, Coulomb's law along
  // the elastic slip (SlipDirection::elastic_slip; docs/FASTSIM.md "Where the exact solver slips
  // everywhere: the elastic slip").
  NhFastSimOptions nh_fastsim{.bound = {TractionBound{}.skew, SlipDirection::elastic_slip}, .creepage_coupling = true};
  RollingOptions rolling{};
  // The normal solver's relative residual: 5e-6 in a wheelset (1e-10 for a single patch). Along
  // 60 time steps of 1 µm (0.2 mm elements, y = 0 and −6.5 mm, by position and by load) the forces
  // lie within 1e-6 of F3 and 6.0e-4 of μF3 of a solve to 1e-12, more than three times below the
  // accuracy targets, and a time step by position needs 4.8 conjugate-gradient iterations at y = 0
  // instead of 7.4 at 1e-6 (docs/WHEELSET.md §8, build/bench/wheelset_normal_tolerance).
  NormalOptions normal{.tolerance = 5e-6};
  ContactSearchOptions search{};
  PatchCouplingOptions patch_coupling{};
  ContactSurface contact_surface = ContactSurface::planar;
  ContactSurfaceSwitch contact_surface_switch{};  // for ContactSurface::automatic
  // By load (default, 98.1 kN per wheel) or, when empty, by position.
  std::optional<WheelLoads> loads = WheelLoads{};
  // The vertical force balance includes the tangential forces' vertical components (the total
  // contact force carries the load); false: the normal forces alone (frictionless balance).
  bool tangential_forces_in_vertical_balance = true;
  // Relative tolerance of the load balance.
  double load_tolerance = 1e-6;
  // A wheel without contact (lifted) gives no patches and zero forces instead of an error.
  bool allow_wheel_lift = false;
  // Keep each patch's pressure and tractions (for maps and figures).
  bool keep_tractions = false;
};
void validate(const WheelsetOptions& options);

// One solver's result on a patch.
struct PatchSolverResult {
  TangentialSolver solver = TangentialSolver::nh_fastsim;
  // On the wheel, contact frame; M3 about the centre of pressure. On a conformal patch F1, F2 are
  // the tractions and pressures of every strip turned into the contact frame and summed (Kalker's
  // CONTACT's "bar" forces), M3 that of the strips' own tractions.
  TangentialForces forces;
  Vector3 force_track_N{};  // F1 X1 + F2 X2 + F3 X3 on the wheel, track frame
  // The flexibilities L1-L3 FastSim ran with (m/Pa): nh_fastsim's from K2 of the patch (or the
  // equivalent ellipse's for a patch too small for K2), fastsim's of the equivalent ellipse
  // (Eq 9); zero for the exact solvers.
  Flexibility flexibility{0.0, 0.0, 0.0};
  // nh_fastsim's creepage coupling about the patch's origin (CreepageCoupling, tangential.hpp; the
  // most loaded lobe's on a patch of several); zero for the other solvers.
  CreepageCoupling coupling;
  std::vector<double> p1_Pa, p2_Pa;  // per contact element (keep_tractions)
  std::vector<std::uint8_t> slip;
  double adhesion_fraction = 0.0;
};

struct WheelsetPatch {
  WheelSide side = WheelSide::right;
  InterpenetrationRegion region;   // reference point, contact angle, frame, overlap
  Creepage creepage;               // kinematic, of the creepage point, about the reference point
  // The creepage point Q on the undeformed wheel surface (track frame): the reference point moved
  // into the rail along the normal by the approach, the patch's largest rigid overlap (m).
  Vector3 creepage_point_track_m{};
  double approach_m = 0.0;
  double rolling_radius_m = 0.0;       // distance of Q from the axle: the radius ξ uses
  double rolling_speed_m_per_s = 0.0;  // V_ref = (V + Ω rolling_radius_m)/2, the creepages' divisor
  double normal_force_N = 0.0;     // F3: the pressure's integral (on a conformal patch over the curved surface)
  // The largest normal displacement the wheel's other patches impose on this one where it may touch
  // (m; PatchCouplingOptions): 0 for a patch solved on its own.
  double coupling_lift_m = 0.0;
  ContactSurface surface = ContactSurface::planar;  // planar or conformal (the latter when blended)
  // The conformal surface's weight in this patch's results (conformal_surface_weight): 0 planar, 1
  // conformal. Between (ContactSurface::automatic in its blend band) the two surfaces were solved
  // and every number of the patch except its counts, strips and tractions (the conformal
  // surface's) is (1 − w) planar + w conformal.
  double conformal_weight = 0.0;
  // The pressure's resultant on the wheel, track frame: F3 X3 on a planar patch; on a conformal one
  // the sum over its strips of their pressure along their own normals.
  Vector3 pressure_force_track_N{};
  // A conformal patch's strips in contact, across the rolling direction (empty on a planar patch).
  std::vector<ConformalStrip> strips;
  double area_m2 = 0.0;
  double max_pressure_Pa = 0.0;
  std::size_t elements_in_contact = 0;
  int normal_iterations = 0;       // of the final normal solve (conjugate gradients)
  // Elements of the mesh the normal problem was solved on: the whole potential contact area, or in
  // a time step the window of the previous step's contact (docs/WHEELSET.md §8).
  std::size_t normal_mesh_elements = 0;
  double pressure_centre_x1_m = 0.0, pressure_centre_x2_m = 0.0;  // from the reference point
  std::vector<PatchSolverResult> solvers;  // in the order of WheelsetOptions::solvers
  // The patch (keep_tractions), its origin at the centre of pressure. A left wheel's patch is
  // stored as solved, mirrored into a right wheel's frame (x2 -> −x2; the tractions p2 of
  // PatchSolverResult are given in the patch's own frame, with their sign restored).
  ContactPatch patch;
  // With keep_tractions, a patch that blends the two surfaces (0 < conformal_weight < 1) keeps each
  // surface's own patch, unblended (what the wheelset table stores of it); empty otherwise.
  std::shared_ptr<const WheelsetPatch> planar_surface, conformal_surface;
  [[nodiscard]] const TangentialForces& forces() const { return solvers.front().forces; }
};

struct WheelResult {
  WheelSide side = WheelSide::right;
  std::vector<WheelsetPatch> patches;  // along the rail profile, gauge side first
  Vector3 force_track_N{};             // sum over the patches (first solver)
  // The same for every solver, in the order of WheelsetOptions::solvers.
  std::vector<Vector3> solver_force_track_N;
  double vertical_displacement_m = 0.0;  // the height at which the wheel was solved
  // By load: the normal problems this wheel's height iteration solved, over every pass of the
  // vertical balance (0 by position).
  int load_iterations = 0;
};

struct WheelsetResult {
  WheelsetState state;                // as solved (by load: the vertical displacement and roll found)
  std::array<WheelResult, 2> wheels;  // right, left
  Vector3 force_track_N{};            // on the wheelset, sum of both wheels (first solver)
  std::vector<Vector3> solver_force_track_N;  // the same per solver, in the order of the options'
  // Free rolling: the evaluations of the wheels' angular velocity it took (0 otherwise).
  int free_rolling_iterations = 0;
};

// Where a Wheelset's evaluations spent their time (Wheelset::time_stages; docs/WHEELSET.md §8
// "Where a step's time goes"): wall-clock seconds per stage, summed over the evaluations since the
// timing was switched on. Each interval counts in exactly one stage, the innermost one running
// (the normal problems a height iteration's trials solve count as normal, not as height), so the
// stages add up to the evaluations' time (total_s).
struct WheelsetStageTimes {
  double search_s = 0.0;      // contact search: each wheel's contact locus, overlap regions, first touch
  double area_s = 0.0;        // the potential contact areas and their undeformed distance h
  double normal_s = 0.0;      // normal problems (contact windows, their checks, whole areas, coupling), warm start
  double height_s = 0.0;      // by load: the heights' and balances' own work (first touch, steps), not their trials'
  double kinematics_s = 0.0;  // each patch's creepage point, frame, kinematic creepages and rolling speed
  double tangential_s = 0.0;  // the tangential solvers, with their patches made from the pressure
  double assembly_s = 0.0;    // the rest: checks of the input, the patches' other numbers, the forces summed
  long evaluations = 0;       // Wheelset::evaluate calls timed (free rolling's inner evaluations not counted)
  [[nodiscard]] double total_s() const {
    return search_s + area_s + normal_s + height_s + kinematics_s + tangential_s + assembly_s;
  }
  // Adds the times and evaluations of `other` (timings of several Wheelsets, one after another).
  WheelsetStageTimes& operator+=(const WheelsetStageTimes& other) {
    search_s += other.search_s;
    area_s += other.area_s;
    normal_s += other.normal_s;
    height_s += other.height_s;
    kinematics_s += other.kinematics_s;
    tangential_s += other.tangential_s;
    assembly_s += other.assembly_s;
    evaluations += other.evaluations;
    return *this;
  }
};

namespace detail {
struct WheelsetWarmStart;
}

// A wheelset on its track, evaluated state after state. Keeps the options, the track, the normal
// solvers' plans (FFT plans and influence tables, per mesh size) and the last pressures of its
// patches, which start the next evaluation's normal solves (a warm start: a time step close to
// the previous one is cheaper; docs/WHEELSET.md §8). Not thread-safe: one per thread; copies are
// independent (a copy starts cold).
class Wheelset {
 public:
  Wheelset(WheelsetTrack track, WheelsetOptions options = {});
  ~Wheelset();
  Wheelset(const Wheelset& other);
  Wheelset& operator=(const Wheelset& other);
  Wheelset(Wheelset&&) noexcept;
  Wheelset& operator=(Wheelset&&) noexcept;
  [[nodiscard]] const WheelsetTrack& track() const { return track_; }
  [[nodiscard]] const WheelsetOptions& options() const { return options_; }
  // Throws Error: invalid_input for a bad state or options and for the contact search's refusals
  // (docs/WHEELSET.md §3), no_contact when a wheel has none (unless allow_wheel_lift),
  // not_converged when a solver or the load balance fails. Nothing non-finite is returned.
  [[nodiscard]] WheelsetResult evaluate(const WheelsetState& state);
  // Forgets the warm start (the previous patches' pressures and the normal solvers' plans): the
  // next evaluation starts cold and gives the numbers of a fresh Wheelset with the same track and
  // options, to the last digit. For a jump in the state (a new simulation, a restart from a saved
  // state) after which the previous pressures are no guide.
  void reset_warm_start();
  // Times the stages of every evaluation from now on (on) or stops (off); either way the times
  // start again from zero. Off by default: timing reads the clock at every change of stage (26
  // readings of about 35 ns in a step by position with two patches). Copies start with timing as
  // the original's, from zero.
  void time_stages(bool on);
  [[nodiscard]] const WheelsetStageTimes& stage_times() const { return stage_times_; }

 private:
  // evaluate() at a given rotation of the wheels (not free rolling).
  WheelsetResult evaluate_rolling(const WheelsetState& state);
  WheelsetTrack track_;
  WheelsetOptions options_;
  std::unique_ptr<detail::WheelsetWarmStart> warm_;
  bool time_stages_ = false;
  WheelsetStageTimes stage_times_;
};

// The wheelset's motion of a state (the rigid-body velocities the kinematic creepages need), with
// the rolling shortcut resolved at the nominal radius r0 when the wheels' angular velocity is NaN.
WheelsetMotion wheelset_motion(const WheelsetState& state, double nominal_rolling_radius_m);

// The default wheelset: S1002 on UIC60 1:40 (the shipped set-up), both sides.
WheelsetTrack default_wheelset_track();

}  // namespace railcontact
