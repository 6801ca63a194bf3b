#pragma once
// Stage: wheel–rail contact. Profiles and the wheelset on the track in; the contact patch of a
// wheel–rail pair with its contact angle, rolling radius, spin creepage and normal force out
// (docs/WHEEL_RAIL.md, docs/METHOD.md §9).
#include <array>
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <optional>
#include <vector>

#include "railcontact/contact_patch.hpp"
#include "railcontact/geometry.hpp"
#include "railcontact/hertz.hpp"
#include "railcontact/normal.hpp"
#include "railcontact/tangential.hpp"
#include "railcontact/wheelset_geometry.hpp"

// Spin creepage of a wheel rolling forward on its rail, from the conicity of the contact
// (paper Eq 24, |φ| = 2 sin γ / d) with its sign (docs/WHEEL_RAIL.md §3).
//
// Track frame: x along the track in the direction of travel, y to the LEFT, z UP. A wheelset
// rolling forward at speed V without slip at the nominal radius r0 = d/2 turns with
// ω = (0, V/r0, 0) (both wheels: one axle). The contact normal into the wheel leans towards the
// track centre by the contact angle γ: X3 = (0, +sin γ, cos γ) on the right wheel and
// (0, −sin γ, cos γ) on the left one (the mirror image). The rigid slip of the wheel relative
// to the rail, w = (ξ − φ x2, η + φ x1) (METHOD.md §6), contains the rotation of the wheel about
// X3, so φ = ω·X3 / V:
//   right wheel φ = +2 sin γ / d,   left wheel φ = −2 sin γ / d.

namespace railcontact {

// Unit contact normal into the wheel, in the track frame, for contact angle γ (rad; positive
// when the normal leans towards the track centre, docs/GEOMETRY.md §3).
std::array<double, 3> contact_normal_in_track_frame(double contact_angle_rad, WheelSide side);

// φ = ω·X3 / V (1/m) for a wheelset rolling forward, ω / V = (0, 1/r0, 0); x3_axis_track is the
// contact normal into the wheel in the track frame (e.g. WheelRailContactPoint::x3_axis_track).
double spin_creepage_per_m(const std::array<double, 3>& x3_axis_track, double nominal_rolling_radius_m);

// Eq 24 with its sign: φ = ±2 sin γ / d (+ right wheel, − left wheel). Throws Error unless γ is
// finite and d > 0.
double conicity_spin_per_m(double contact_angle_rad, WheelSide side, double nominal_wheel_diameter_m = 0.92);

}  // namespace railcontact

// The normal contact of one wheel–rail pair at one wheelset position (METHOD.md §5, §9;
// docs/WHEEL_RAIL.md): profiles → contact point → undeformed distance on a potential contact
// area → normal problem → the single contact patch, with its contact angle, rolling radius,
// spin creepage (Eq 24, signed) and normal force F3 = Fz / cos γ (frictionless equilibrium).
//
// Frames as in wheel_rail.hpp: the right wheel on the right rail; contact frame X1 rolling
// direction, X3 the contact normal into the wheel, X2 = X3 × X1 towards the flange / gauge side.


namespace railcontact {

// Shape of the elements of the potential contact area (cf. EllipseMeshLayout).
enum class PatchMeshLayout {
  square,            // dx1 = dx2
  rolling_resolved,  // dx1 = dx2 min(1, L1/L2) with L1, L2 the patch extents along X1, X2:
                     // square when the patch is longer than wide, else as many elements along
                     // X1 as along X2 (the rolling direction is never resolved more coarsely)
};

// The fewest elements in contact a wheel–rail patch may be asked for (target_elements). With fewer,
// the elements are so large that the first potential contact area, which has a border of whole
// elements, can reach beyond the rail head: the default S1002/UIC60 pair fails at y = 0 with 10
// elements (98.1 kN), with 15 at 200 kN and with 20–50 from 300 kN–1 MN, while 100 elements serve
// every y in −4.5 … 4.5 mm up to 1 MN. Such patches are also wrong: with 20 elements the area is
// 6–15 % too large and the maximum pressure up to 24 % too small, with 100 within 7 % and 1 %
// (y = −3, 0, 3 mm at 98.1 kN, against 3000 elements).
// The largest lateral displacement |y| of a wheel-rail case (case [geometry] y, in metres): 0.05 m. A flangeway's play is about ±8 mm and a flange is about 30 mm thick: beyond
// 50 mm the wheel is off its rail (a value like 5 is millimetres given as metres).
inline constexpr double kMaximumWheelRailLateralDisplacement_m = 0.05;
inline constexpr int kMinimumWheelRailElements = 100;
inline constexpr int kMaximumWheelRailElements = 200000;
// On the smooth reference the patch is meshed with elements of at least
// kMinimumTangentPlaneElement_m (0.001 mm, railcontact/wheelset_geometry.hpp): a target_elements
// whose elements would be smaller at the given load (a light load, a small patch) is refused
// before any solve, from the Hertzian estimate, with a message that begins with this text.
inline constexpr std::string_view kWheelRailElementsTooSmall = "wheel-rail patch: elements too small:";

// The reference of a wheel–rail patch: the origin of its contact frame and its contact angle γ,
// from which F3 = Fz / cos γ, the spin and the rolling radius follow (docs/WHEEL_RAIL.md §6).
enum class ContactReference {
  // The wheelset's smooth reference (docs/WHEELSET.md §4): averages over the interpenetration
  // region at the wheel's height that carries the load (ContactSearchOptions::weighting). It
  // moves continuously with y, and it is the reference of `railcontact wheelset`: a single patch
  // and the wheelset's right wheel at the same y and load (zero roll and yaw) agree.
  smooth,
  // The point of first touch of the lowered wheel (before 2026-11-25): it jumps where the lowest
  // point of the gap moves from one local minimum to another (y ≈ −0.21 mm on S1002/UIC60).
  first_touch,
};
// "smooth", "first-touch"; parse_contact_reference throws Error (invalid_input) naming the
// allowed names.
const char* contact_reference_name(ContactReference reference);
ContactReference parse_contact_reference(const std::string& name);

struct WheelRailPatchOptions {
  // Fz (METHOD.md §9: 10 t), in [kMinimumNormalForce_N, kMaximumNormalForce_N] (1 N ... 1e7 N,
  // contact_patch.hpp), as is F3 = Fz / cos γ.
  double vertical_load_N = 98100;
  // About this many elements in contact, in [kMinimumWheelRailElements, kMaximumWheelRailElements].
  int target_elements = 3000;
  NormalOptions normal;
  Material material{2.1e11, 0.3};
  PatchMeshLayout layout = PatchMeshLayout::rolling_resolved;
  // The mesh is refined (element area scaled by count / target) while the number of elements in
  // contact is off the target by more than this fraction, in at most max_mesh_passes solves.
  double element_count_tolerance = 0.15;
  int max_mesh_passes = 3;
  // The first potential area holds h < 1.5 × this approach estimate; default: Hertz's approach
  // for the local curvatures. A potential area that the patch touches is enlarged (margin × 1.5,
  // approach estimate up to × 2) at most max_enlargements times.
  std::optional<double> initial_approach_m;
  int max_enlargements = 4;
  // Connected contact regions carrying more than this fraction of F3 are patches; smaller ones
  // (specks) are dropped from `patch`. More than one patch throws Error unless
  // allow_several_patches (then `patch` holds the largest one and `regions` all of them).
  double significant_load_fraction = 0.01;
  bool allow_several_patches = false;
  // The patch's reference; with `smooth`, the contact search's rule separates and merges
  // interpenetration regions (search.merge_distance_m, merge_angle_rad: docs/WHEELSET.md §3),
  // and each region is one patch.
  ContactReference reference = ContactReference::smooth;
  ContactSearchOptions search{};
  // smooth: relative tolerance of the wheel's height iteration on the vertical load (a single
  // patch then carries Fz exactly: its last solve is by force).
  double load_tolerance = 1e-6;
};

struct WheelRailPatch {
  WheelRailContactPoint contact;    // point of first touch, its contact frame, local curvatures
  ContactReference reference = ContactReference::smooth;
  // smooth: the interpenetration region of the patch (reference point on the rail, contact frame,
  // overlap) at the wheel's height below, and that height (the wheelset's vertical displacement
  // above its nominal height, WheelsetPosition) with the iterations that found it.
  InterpenetrationRegion region;
  double vertical_displacement_m = 0.0;
  int load_iterations = 0;
  double lateral_displacement_m = 0.0;  // wheelset y (track frame, positive to the left)
  double contact_angle_rad = 0.0;       // γ of the reference
  double rolling_radius_m = 0.0;        // wheel radius at the reference
  double spin_per_m = 0.0;              // Eq 24 signed: +2 sin γ / d (right wheel)
  double vertical_load_N = 0.0;         // Fz
  // F3 of the patch: Fz / cos γ for a single patch; with several patches (allow_several_patches,
  // smooth reference) the share of this patch, the patches together carrying Fz vertically.
  double normal_force_N = 0.0;
  // The patch on the potential-area mesh cropped to its bounding box, with its origin at its centre
  // of pressure. smooth: every element in contact of the most loaded interpenetration region (as
  // a wheelset's patch); first touch: the largest connected region.
  ContactPatch patch;
  // The normal solution on the potential-area mesh and that mesh. The mesh origin is the
  // reference point (smooth: only this patch's interpenetration region is on it; first touch: all
  // regions); h on it is potential_h_m, zero at its lowest point (its approach is normal.approach_m).
  NormalSolution normal;
  Mesh potential_area;
  std::vector<double> potential_h_m;
  // Connected contact regions of `normal`, by decreasing load (regions.size() >= 1).
  std::vector<ContactRegion> regions;
  // Patches carrying more than significant_load_fraction of the load (smooth: interpenetration
  // regions; first touch: connected contact regions), and the fraction of the load not in `patch`
  // (smooth: of the vertical load Fz; first touch: of F3).
  std::size_t patches = 1;
  double dropped_load_fraction = 0.0;
  // Centre of pressure of `patch` in the tangent plane, from the reference point.
  double pressure_centre_x1_m = 0.0;
  double pressure_centre_x2_m = 0.0;
  // The centre of pressure on the rail (rail profile frame, the tangent-plane point) and the
  // rail's slope angle there: like the smooth γ (unlike the first-touch one) it varies continuously
  // through a contact jump (docs/WHEEL_RAIL.md §6). For information; F3 and the spin use γ.
  double pressure_centre_y_rail_m = 0.0;
  double pressure_centre_contact_angle_rad = 0.0;
  // Measures of `patch`: extents along X1 and X2 (element edges), area (elements × S), p3 max.
  double extent_x1_m = 0.0, extent_x2_m = 0.0, area_m2 = 0.0, max_pressure_Pa = 0.0;
  double approach_m = 0.0;            // δ of the normal solution (along X3, from h's lowest point)
  std::size_t elements_in_contact = 0;  // elements of `patch`
  int iterations = 0;                 // normal-solver iterations of the final solve
  // Normal solves performed: the first-touch mesh passes (refinements, enlargements) and, smooth,
  // the height iteration's solves.
  int mesh_passes = 0;
  // Hertz's solution for the local curvatures A, B of the contact point and F3, for comparison
  // (all zero when B <= 0: no Hertzian contact exists).
  HertzContact local_hertz;
};

// Solves the normal contact at wheelset displacement y_m (track frame, m). Throws Error when the
// profiles never touch, the load or options are invalid, the normal solver does not converge,
// the potential area cannot hold the patch (the message says whether the elements or the load
// are too large for the profiles), or (unless allowed) y gives several patches.
WheelRailPatch solve_wheel_rail_patch(const WheelRailPair& pair, double y_m, const WheelRailPatchOptions& options = {});

// A wheel–rail set-up: a profile pair and its track, as data (a JSON file, docs/WHEEL_RAIL.md
// "Set-up files"). The shipped default, data/wheel_rail/s1002_uic60.json, is the paper's test set:
// S1002 on UIC60 1:40, 1435 mm gauge (docs/METHOD.md §9).
struct WheelRailSetup {
  std::string description;
  std::filesystem::path wheel_profile;  // resolved against the set-up file's directory
  std::filesystem::path rail_profile;
  TrackWheelsetParameters track;
};
// Throws Error naming the file and the key: kind io when it cannot be read, invalid_input for
// malformed JSON, missing or unknown keys, non-finite or non-physical track values.
WheelRailSetup read_wheel_rail_setup(const std::filesystem::path& path);
WheelRailPair load_wheel_rail_pair(const WheelRailSetup& setup);

// The shipped default set-up. The data directory is the one of the build (RAILCONTACT_DATA_DIR)
// unless the environment variable RAILCONTACT_DATA names another.
std::filesystem::path default_wheel_rail_setup_path();
std::filesystem::path default_wheel_profile_path();
std::filesystem::path default_rail_profile_path();
WheelRailPair default_wheel_rail_pair();

// A pair from profile files (formats: geometry.hpp); errors name the file and the line.
WheelRailPair load_wheel_rail_pair(const std::filesystem::path& wheel_profile,
                                   const std::filesystem::path& rail_profile,
                                   const TrackWheelsetParameters& parameters = {});

}  // namespace railcontact
