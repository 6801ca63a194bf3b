#pragma once
// Stage: wheelset table (docs/WHEELSET_TABLE.md). Everything a wheelset
// time step needs from its contact, precomputed over the wheelset's lateral displacement y and the
// wheel load: each wheel's patches (tread, flange, both) with their normal force, reference point,
// contact angle, rolling radius, nH-FastSim flexibilities and a coarse copy of the patch for
// FastSim. A step then costs the kinematic creepages and a few FastSim marches on small patches:
// microseconds instead of the milliseconds of Wheelset::evaluate.
//
//   const WheelsetTable table = build_wheelset_table(default_wheelset_track(), {y_grid, yaw_grid, loads});
//   WheelsetResult r = table.evaluate(state, {98.1e3, 98.1e3}, 0.3);  // state: position + velocity
//
// What a node holds. Node (y, ψ, Fz) is Wheelset::evaluate at lateral displacement y, yaw ψ, zero
// roll, both wheels loaded with Fz (each wheel's height solved for its own load, the frictionless
// balance: the normal forces carry the load), with nH-FastSim on every patch. Per wheel and patch
// it keeps the reference point and frame, F3, the flexibilities L1-L3 of nH-FastSim (from K2 on the
// patch itself) and the patch coarsened to about kWheelsetTableRuntimeElements elements (the
// pressure of each block of elements summed, so F3 and the centre of pressure are kept). Built on
// the conformal or automatic surface, a patch also keeps its solution on the curved surface with a
// strip frame per column of its coarse copy (WheelsetTableConformalPatch), marched strip by strip.
//
// What a lookup does (WheelsetTable::evaluate): for each wheel, the nodes around (y, ψ, Fz of that
// wheel); on each of their patches the kinematic creepages of the state (its velocities and yaw;
// the contact point turned by the yaw the node does not have), FastSim on the coarse patch with the
// node's flexibilities and mu, the forces in the track frame; then the forces of the nodes are
// interpolated linearly in y, ψ and Fz. Patches of neighbouring nodes are matched by their position
// on the rail profile; a patch missing at a node (it appears between two nodes) counts there with
// zero force, so a flange contact grows from zero. Reference point, angle and creepages of a patch
// are the weighted average over the nodes that have it.
//
// Approximations (measured in docs/WHEELSET_TABLE.md): the geometry is that of the yaw nodes (with
// one yaw, zero: the yaw then enters the creepages, not the contact point, and the flange contact's
// lead of r tan γ sin ψ is not modelled); zero roll; the normal problem is frictionless; FastSim
// runs on the coarse patch.
#include <cstddef>
#include <filesystem>
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "railcontact/flexibility_table.hpp"
#include "railcontact/tangential.hpp"
#include "railcontact/tangential_model.hpp"
#include "railcontact/wheelset.hpp"
#include "railcontact/wheelset_geometry.hpp"

namespace railcontact {

// FastSim at lookup runs on patches of about this many elements (fewer when the fine patch has
// fewer; the coarsening is by whole blocks, so a copy has between this many and four times as
// many): the cost of a lookup against the error of FastSim's discretisation. With 400 the hollow
// wheel's 1800-element tread patch went to 2 × 2 blocks, and the table missed the wheelset on the
// fly by 2.5 % of μFz; with 600 it is kept whole, 0.9 % (docs/WHEELSET_TABLE.md §1).
inline constexpr int kWheelsetTableRuntimeElements = 600;
// Patches of neighbouring nodes are one patch when their reference points lie at most this far
// apart on the rail profile (tread and flange contacts lie 10 mm and more apart).
inline constexpr double kWheelsetTablePatchMatchDistance_m = 4e-3;

// One patch of one wheel at one node, in that wheel's own terms (the left wheel's as it is, not
// mirrored).
// One strip (column) of a conformal patch's runtime copy, in the runtime mesh's column order (the
// solve frame: a left wheel's mirrored): its turn from the patch's X3 about X1 in the wheel's own
// frame (ConformalStrip::angle_rad) and its creepage point on the undeformed wheel surface from the
// wheelset centre (track frame, the node's position).
struct WheelsetTableStrip {
  double angle_rad = 0.0;
  Vector3 point_from_wheelset_centre_m{};
};

// One lobe of a patch of several (tread and flange root joined: NhFastSimPerLobe, docs/WHEELSET.md
// §8): its own flexibilities, centre of pressure and coarse patch.
struct WheelsetTableLobe {
  // Centre of pressure of its coarse patch from the patch's reference point (contact frame).
  double pressure_centre_x1_m = 0.0, pressure_centre_x2_m = 0.0;
  Flexibility flexibility;  // L1-L3 of nH-FastSim on this lobe
  CreepageCoupling coupling;  // its creepage coupling about the runtime copy's origin (tangential.hpp)
  Mesh runtime_mesh;        // as the patch's: solve frame, origin at the lobe's centre of pressure
  std::vector<double> runtime_pressure_Pa;
  // A lobe of a conformal patch: one strip per runtime_mesh column (empty for a planar patch's).
  std::vector<WheelsetTableStrip> strips;
};

// A patch's solution on the conformal surface (docs/WHEELSET.md §4 "Conformal contact"), for a table
// built with the conformal or automatic surface: its own numbers and its runtime copy, on which a
// lookup marches FastSim strip by strip with each strip's creepages, and sums every element's
// traction and pressure in its strip's frame.
struct WheelsetTableConformalPatch {
  // The conformal surface's weight in the patch (WheelsetPatch::conformal_weight): 1 conformal; in
  // (0, 1) blended with the planar surface's solution that the patch's other fields hold.
  double weight = 1.0;
  double normal_force_N = 0.0;         // Σ p3 S over the curved surface
  Vector3 pressure_force_track_N{};    // the pressures along their strips' normals, summed
  double area_m2 = 0.0;
  std::size_t elements_in_contact = 0;
  double max_pressure_Pa = 0.0;
  double pressure_centre_x1_m = 0.0, pressure_centre_x2_m = 0.0;  // of the runtime copy, developed
  Flexibility flexibility;  // L1-L3 of nH-FastSim on the developed patch
  CreepageCoupling coupling;  // its creepage coupling about the runtime copy's origin
  Mesh runtime_mesh;        // solve frame, origin at its centre of pressure
  std::vector<double> runtime_pressure_Pa;
  std::vector<WheelsetTableStrip> strips;  // one per runtime_mesh column
  // A patch of several lobes, as on a planar patch (WheelsetTablePatch::lobes): each lobe's
  // flexibilities, coarse copy and strips, and the whole patch's weight where a neck is blended.
  std::vector<WheelsetTableLobe> lobes;
  double whole_patch_weight = 0.0;
};

struct WheelsetTablePatch {
  Vector3 reference_point_track_m{};       // reference point, track frame (the node's y, yaw, height)
  // The creepage point (on the undeformed wheel surface, docs/WHEEL_RAIL.md §12) from the
  // wheelset centre.
  Vector3 point_from_wheelset_centre_m{};
  Vector3 x1_axis{1.0, 0.0, 0.0}, x2_axis{}, x3_axis{};
  double contact_angle_rad = 0.0;
  double rolling_radius_m = 0.0;
  double rail_profile_y_m = 0.0;
  double wheel_profile_y_m = 0.0;
  double normal_force_N = 0.0;   // F3
  double area_m2 = 0.0;          // of the fine patch
  std::size_t elements_in_contact = 0;  // of the fine patch
  double max_pressure_Pa = 0.0;
  // Centre of pressure from the reference point (contact frame).
  double pressure_centre_x1_m = 0.0, pressure_centre_x2_m = 0.0;
  Flexibility flexibility;  // L1-L3 of nH-FastSim on this patch
  CreepageCoupling coupling;  // its creepage coupling about the runtime copy's origin (tangential.hpp)
  // The coarse patch for FastSim at lookup, in the solve frame (a left wheel's patch mirrored
  // x2 -> −x2 into a right wheel's frame, as Wheelset solves it), origin at its centre of pressure.
  // Empty (no elements) for a patch that has overlap but no element in contact yet.
  Mesh runtime_mesh;
  std::vector<double> runtime_pressure_Pa;  // per runtime_mesh element
  // A patch of several lobes: FastSim on each lobe at lookup, with its own flexibilities and the
  // creepages at its own centre, the forces summed (the patch's flexibility above is then its most
  // loaded lobe's, for the record). Empty for a patch of one lobe.
  std::vector<WheelsetTableLobe> lobes;
  // A patch whose neck is between a quarter and half its lobes' width (NhFastSimPerLobe::
  // whole_patch_weight): the lobes' forces blended with the whole patch's (FastSim on the runtime
  // patch with `flexibility`, then the whole patch's) with this weight in (0, 1); 0 otherwise.
  double whole_patch_weight = 0.0;
  // A table of the conformal or automatic surface: the patch on the conformal surface where its
  // weight is above 0. With weight 1 the fields above are the conformal solution's and carry no
  // runtime copy; below 1 they are the planar surface's solution, blended with this one at lookup.
  std::optional<WheelsetTableConformalPatch> conformal;
};

enum class WheelsetTableNodeStatus {
  solved,  // both wheels' patches are set
  failed,  // Wheelset::evaluate failed (message): a gap of the table
};

// The grid of a table: nodes at every (y, yaw, wheel load). Each list strictly increasing; the
// loads positive. A yaw grid of one value serves every yaw by the approximation of §2 (the contact
// point turned with the yaw); with several values, lookups interpolate between them and a yaw
// outside the grid is refused.
struct WheelsetTableGrid {
  std::vector<double> y_m;
  std::vector<double> yaw_rad{0.0};
  std::vector<double> wheel_load_N;
  [[nodiscard]] std::size_t size() const { return y_m.size() * yaw_rad.size() * wheel_load_N.size(); }
  // The position of node (iy, iyaw, iload) in WheelsetTable::nodes() (y-major, then yaw, then load).
  [[nodiscard]] std::size_t index(std::size_t iy, std::size_t iyaw, std::size_t iload) const {
    return (iy * yaw_rad.size() + iyaw) * wheel_load_N.size() + iload;
  }
};

// Throws Error (invalid_input) unless each list is non-empty, finite and strictly increasing, the
// loads positive and the yaws within ±0.1 rad.
void validate(const WheelsetTableGrid& grid);

struct WheelsetTableNode {
  double y_m = 0.0;
  double yaw_rad = 0.0;
  double wheel_load_N = 0.0;  // vertical load of each wheel
  WheelsetTableNodeStatus status = WheelsetTableNodeStatus::solved;
  std::string message;
  std::array<std::vector<WheelsetTablePatch>, 2> wheels;  // right, left; patches gauge side first
  // Each wheel's height as solved for its load (WheelResult::vertical_displacement_m).
  std::array<double, 2> vertical_displacement_m{0.0, 0.0};
};

// Where a table came from: the profile files (fingerprints; fnv1a64 = 0 when a profile was not
// read from a file), the track, the recipe, the version that built it.
struct WheelsetTableMetadata {
  FileFingerprint right_wheel_profile, right_rail_profile, left_wheel_profile, left_rail_profile;
  TrackWheelsetParameters track;
  double element_size_m = 0.0;
  int flexibility_coarsening = 0;   // NhFastSimOptions::flexibility_coarsening (0: automatic)
  double collocation_offset = 0.0;  // NhFastSimOptions::collocation_offset
  int runtime_elements = 0;
  // kNhFastSimRecipe of the build (format version 4; 0 for older tables: recipe 1 or 2).
  int nh_fastsim_recipe = kNhFastSimRecipe;
  // How the nodes' reference points were averaged (ContactSearchOptions::weighting), and whether
  // their creepages were taken on the undeformed wheel surface over the rolling speed V_ref
  // (docs/WHEEL_RAIL.md §12; format version 5). Tables of format 4 and older: depth-weighted
  // reference points, creepages on the rail surface over the forward speed.
  ReferenceWeighting reference_weighting = ReferenceWeighting::squared_gap;
  bool creepage_on_wheel_surface = true;
  // The contact surface of the build (format version 6; older: planar) and, for the automatic
  // surface, its switch.
  ContactSurface contact_surface = ContactSurface::planar;
  ContactSurfaceSwitch contact_surface_switch{};
  // The elastic coupling of a wheel's separate patches in the build (format version 8; older: none,
  // {0, 0}).
  PatchCouplingOptions patch_coupling{0.0, 0.0};
  std::string railcontact_version;
  std::string created_utc;
};

// The y grid refined where linear interpolation between neighbouring nodes would miss a node's
// contact: a flange snapping into contact, a second contact appearing (docs/WHEELSET_TABLE.md §3
// "Where the contact jumps"). A node whose wheel's lateral normal force (its patches' pressure
// resultants along y) lies further than lateral_force_fraction of its load from the straight line
// between its two neighbours along y has the intervals on both sides halved, at every yaw and load,
// for at most `rounds` halvings; intervals of smallest_step_m or less are kept.
// The lateral_force_fraction the command line, the C API and Python build with by default
// (docs/WHEELSET_TABLE.md §3 "Where the contact jumps"); WheelsetTableRefinement's own is 0, since a
// refined build needs its nodes on one process (not a runner over MPI ranks).
inline constexpr double kWheelsetTableRefinementDefault = 0.01;

struct WheelsetTableRefinement {
  double lateral_force_fraction = 0.0;  // 0: no refinement; else in (0, 1]
  double smallest_step_m = 0.0125e-3;
  int rounds = 3;
};

struct WheelsetTableOptions {
  // The wheelset solver of each node: material, element size, nH-FastSim's recipe, normal solver,
  // contact search. Its loads, solvers, friction and keep_tractions are set by the build.
  WheelsetOptions wheelset{};
  int runtime_elements = kWheelsetTableRuntimeElements;
  WheelsetTableRefinement refinement{};
  // Who computes the blocks of nodes (TableNodeRunner, railcontact/flexibility_table.hpp; a block
  // is kWheelsetTableBlock consecutive y values at one yaw and load); empty: serially.
  TableNodeRunner runner;
  // The metadata's created_utc; empty: the time of the build (as FlexibilityTableOptions).
  std::string created_utc;
};
// Nodes per block of a build: along a block the wheelset's warm start carries over from one y to
// the next; each block starts cold, so the blocks are independent (threads, MPI ranks).
inline constexpr std::size_t kWheelsetTableBlock = 8;

struct WheelsetTableProgress {
  std::size_t nodes_done = 0, nodes_total = 0;
  const WheelsetTableNode* node = nullptr;
  double node_seconds = 0.0;
};
using WheelsetTableProgressCallback = std::function<void(const WheelsetTableProgress&)>;

// The settings of a wheelset that change a table's numbers but are not among its axes (y, yaw,
// load). A table holds the values of its build (its metadata, material and bound) and is used only
// with those (docs/WHEELSET_TABLE.md §5 "What a table is used with"); speed, velocities and mu are
// inputs of every lookup, not settings.
enum class WheelsetTableSetting {
  material,                // E and nu: the normal problem, K2 and FastSim's patches
  element_size,            // the mesh of the nodes' patches
  flexibility_coarsening,  // nH-FastSim's K2 blocks (NhFastSimOptions::flexibility_coarsening)
  collocation_offset,      // K2's collocation points (NhFastSimOptions::collocation_offset)
  slip_direction,          // FastSim's slipping traction (TractionBound::slip_direction)
  traction_bound_skew,     // FastSim's traction bound (TractionBound::skew)
  nh_fastsim_recipe,       // kNhFastSimRecipe of the build (this railcontact computes with today's)
  contact_definition,      // the reference point's weighting and where the creepages are taken
  contact_surface,         // planar, conformal or automatic (with its switch)
  patch_coupling,          // the elastic coupling of separate patches (WheelsetOptions::patch_coupling)
};
inline constexpr WheelsetTableSetting kWheelsetTableSettings[] = {
    WheelsetTableSetting::material,           WheelsetTableSetting::element_size,
    WheelsetTableSetting::flexibility_coarsening, WheelsetTableSetting::collocation_offset,
    WheelsetTableSetting::slip_direction,     WheelsetTableSetting::traction_bound_skew,
    WheelsetTableSetting::nh_fastsim_recipe, WheelsetTableSetting::contact_definition,
    WheelsetTableSetting::contact_surface,    WheelsetTableSetting::patch_coupling};
// "material", "element-size", "flexibility-coarsening", "collocation-offset", "slip-direction",
// "traction-bound-skew", "recipe", "contact-definition", "contact-surface", "patch-coupling".
const char* wheelset_table_setting_name(WheelsetTableSetting setting);
// Throws Error (invalid_input) naming the allowed names.
WheelsetTableSetting parse_wheelset_table_setting(const std::string& name);

// A setting whose requested value is not the table's (the values as text, with units).
struct WheelsetTableMismatch {
  WheelsetTableSetting setting = WheelsetTableSetting::material;
  std::string requested, table;
};

class WheelsetTable {
 public:
  WheelsetTable() = default;
  // Nodes in the order of grid.index(). nominal_rolling_radius_m: r0 of the track
  // the table was built for (pure rolling in WheelsetVelocity's shortcut). Throws Error unless the
  // grids are finite and strictly increasing (loads positive), each node sits on its grid point,
  // solved nodes hold finite, plausible values, and r0 > 0.
  WheelsetTable(WheelsetTableGrid grid, std::vector<WheelsetTableNode> nodes,
                double nominal_rolling_radius_m, Material material, TractionBound bound = {},
                WheelsetTableMetadata metadata = {});

  [[nodiscard]] const WheelsetTableGrid& grid() const { return grid_; }
  [[nodiscard]] const std::vector<WheelsetTableNode>& nodes() const { return nodes_; }
  [[nodiscard]] const WheelsetTableNode& node(std::size_t iy, std::size_t iyaw, std::size_t iload) const;
  [[nodiscard]] double nominal_rolling_radius_m() const { return nominal_rolling_radius_m_; }
  [[nodiscard]] const Material& material() const { return material_; }
  [[nodiscard]] TractionBound bound() const { return bound_; }
  [[nodiscard]] const WheelsetTableMetadata& metadata() const { return metadata_; }
  // Where the table came from, for messages: the file it was loaded from (empty when built).
  [[nodiscard]] const std::string& source() const { return source_; }
  void set_source(std::string source) { source_ = std::move(source); }

  // Throws Error unless the track's four profiles hash as the table's (a profile not read from a
  // file is compared by name) and its track parameters are the table's.
  void check_track(const WheelsetTrack& track) const;

  // The settings of `options` that are not the table's (WheelsetTableSetting; element size and
  // doubles to 1e-9 relative, the rest exactly; the recipe is kNhFastSimRecipe against the table's),
  // in the order of kWheelsetTableSettings; empty: the table was built for these options.
  [[nodiscard]] std::vector<WheelsetTableMismatch> mismatches(const WheelsetOptions& options) const;

  // The wheelset's contact forces at a state: both wheels, every patch, as Wheelset::evaluate
  // gives them (one solver, nh_fastsim; no tractions; the state's vertical displacement is not
  // used: each wheel carries its load, loads.balance_roll is ignored). The nodes have zero roll: a
  // state with a roll other than zero is refused. Throws Error (invalid_input) for a bad state,
  // load or mu, for y or a load outside the table's grid, and when a node needed is a gap.
  // Thread-safe (const).
  // The nodes carry their loads on the normal forces alone (a frictionless balance). With
  // tangential_forces_in_vertical_balance (WheelsetOptions' default, which the command line, the C
  // API and Python pass on) each wheel is looked up at the table load at which its normal and
  // tangential forces together carry its load, as Wheelset::evaluate balances it: a secant on the
  // table's load, to 1e-6 of the load (docs/WHEELSET_TABLE.md §2 "The vertical balance").
  [[nodiscard]] WheelsetResult evaluate(const WheelsetState& state, const WheelLoads& loads,
                                        double friction_coefficient,
                                        bool tangential_forces_in_vertical_balance = false) const;

 private:
  // The patches' FastSim results of one state at the nodes looked up so far (wheelset_table.cpp):
  // the vertical balance looks the same state up at several table loads.
  struct LookupCache;
  [[nodiscard]] WheelsetResult evaluate_at_table_loads(const WheelsetState& state, const WheelLoads& loads,
                                                       double friction_coefficient, LookupCache& cache) const;
  WheelsetTableGrid grid_;
  std::vector<WheelsetTableNode> nodes_;
  double nominal_rolling_radius_m_ = 0.0;
  Material material_{};
  TractionBound bound_{};
  WheelsetTableMetadata metadata_;
  std::string source_;
  // Per node and wheel, the table-driven tangential model (TangentialModel on a StoredPatch) of each
  // patch: on its coarse copy or its lobes' (empty for a patch without elements); on its conformal
  // copy and its lobes', each with its strips' frames (creepage points at the node's yaw) and the
  // cosine and sine of their turn.
  struct RuntimePatch {
    std::optional<TangentialModel> planar;
    struct CurvedCopy {
      TangentialModel model;
      std::vector<ContactFrame> frames;
      std::vector<double> cos_angle, sin_angle;
    };
    std::optional<CurvedCopy> conformal;
    std::vector<CurvedCopy> conformal_lobes;
  };
  std::vector<std::array<std::vector<RuntimePatch>, 2>> runtime_;
};

// Builds the table over the grid. Nodes whose wheelset solve fails are kept as gaps (message), not
// thrown; throws Error for bad grids or options and when no node can be solved.
WheelsetTable build_wheelset_table(const WheelsetTrack& track, const WheelsetTableGrid& grid,
                                   const WheelsetTableOptions& options = {},
                                   const WheelsetTableProgressCallback& progress = {});

// The file format (JSON, docs/WHEELSET_TABLE.md §4). save throws Error (io) when the file cannot
// be written; load throws Error("wheelset table FILE: …") for unreadable or malformed files (the
// key at fault named).
void save_wheelset_table(const WheelsetTable& table, const std::filesystem::path& path);
WheelsetTable load_wheelset_table(const std::filesystem::path& path);
std::string wheelset_table_json(const WheelsetTable& table);
WheelsetTable parse_wheelset_table(const std::string& json_text, const std::string& source);

}  // namespace railcontact
