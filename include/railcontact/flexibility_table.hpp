#pragma once
// Stage: flexibility table. nH-FastSim's flexibilities of a profile pair precomputed over the
// wheelset's lateral displacement and load, stored, interpolated, and used in a simulation step
// (docs/FLEXTABLE.md).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "railcontact/contact_patch.hpp"
#include "railcontact/geometry.hpp"
#include "railcontact/kalker.hpp"
#include "railcontact/tangential.hpp"
#include "railcontact/wheel_rail.hpp"

// Flexibility table (docs/FLEXTABLE.md): nH-FastSim's flexibilities L1, L2, L3 and the creepage
// coefficients f11, f22, f23 of one wheel–rail profile pair, computed once over a grid of
// wheelset lateral displacement y and vertical wheel load Fz (each node: solve_wheel_rail_patch,
// then the force rows of K2 and the term-by-term match of tangential.hpp), stored in a documented
// JSON file, and interpolated. A simulation step then costs one normal solve + FastSim, or
// FastSim only with a cached patch (FlexibilityTableFastSim below); no K2 at run time.
//
// Interpolation (measured in docs/FLEXTABLE.md §4): linear in y and linear in log Fz, of the
// area-scaled quantities L/√A, f11/A, f22/A, f23/A^1.5 (A the patch area; the dimensions of
// Kalker's theory: L ∝ a, f11, f22 ∝ G c², f23 ∝ G c³), multiplied back by the area of the patch
// at hand when there is one (lookup_for_patch), else by the interpolated area (log-linear).
// The mesh-discretisation noise of L and f then cancels to a large part against the patch's own
// area. Contact angle, spin and elements are interpolated linearly, F3 and the area log-linearly.
//
// Contact jumps (docs/WHEEL_RAIL.md §4: the point of first touch jumps, and γ, the spin from
// conicity and F3 jump with it) are located at build time to 1 µm and bracketed by two extra y
// nodes; a lookup between the two bracket nodes takes the nearer one, so nothing is interpolated
// across a jump. Nodes that give several contact patches (or fail) are kept, marked, and lookups
// in the intervals next to them are refused (an Error naming the node): the table has a gap there.


namespace railcontact {

enum class FlexibilityNodeStatus {
  solved,           // one patch: every value is set
  several_patches,  // the normal solution has several contact patches: no values (a gap)
  failed,           // the patch or K2 could not be computed (message): no values (a gap)
};

// One grid node (y, Fz).
struct FlexibilityTableNode {
  double y_m = 0.0;              // wheelset lateral displacement (track frame, y < 0 towards the flange)
  double vertical_load_N = 0.0;  // Fz
  FlexibilityNodeStatus status = FlexibilityNodeStatus::solved;
  std::string message;           // why the node is not solved (empty when solved)
  Flexibility flexibility;       // L1, L2, L3 (m/Pa), term by term (tangential.hpp)
  double f11_N = 0.0;            // -K2_11: F1 per unit xi (N)
  double f22_N = 0.0;            // -K2_22: F2 per unit eta (N)
  double f23_Nm = 0.0;           // -K2_23: F2 per 1/m of spin (N m)
  CreepageCoupling coupling;     // nH-FastSim's creepage coupling (tangential.hpp); zero in older tables
  double normal_force_N = 0.0;   // F3 = Fz / cos γ
  double contact_angle_rad = 0.0;  // γ of the point of first touch
  double spin_per_m = 0.0;       // Eq 24, signed (right wheel)
  double area_m2 = 0.0;          // patch area (elements × element area)
  std::size_t elements_in_contact = 0;
};

// An interval of the y grid that holds a jump of the point of first touch: its two nodes are
// the bracket (at most contact_jump_resolution_m apart), y_rail the first-touch points on the rail.
struct ContactJump {
  std::size_t interval = 0;  // between y_m()[interval] and y_m()[interval + 1]
  double y_rail_left_m = 0.0, y_rail_right_m = 0.0;
};

// The provenance of an input file: its name as given and the 64-bit FNV-1a hash of its bytes. The
// hash identifies the content, not the name: a copied or moved file keeps its fingerprint, an
// edited one does not.
struct FileFingerprint {
  std::string file;           // the path as given
  std::uint64_t fnv1a64 = 0;  // of the file's bytes
  [[nodiscard]] std::string hash_hex() const;  // 16 lower-case hexadecimal digits
};
// Reads the file and hashes it. Throws Error(io) when it cannot.
FileFingerprint file_fingerprint(const std::filesystem::path& path);

struct FlexibilityTableMetadata {
  FileFingerprint wheel_profile;  // file as given, FNV-1a 64 of its bytes
  FileFingerprint rail_profile;
  TrackWheelsetParameters track;
  Material material;
  int target_elements = 0;        // WheelRailPatchOptions::target_elements of the build
  double collocation_offset = 0.0;  // NhFastSimOptions::collocation_offset of K2
  int flexibility_coarsening = 0;   // NhFastSimOptions::flexibility_coarsening (0: automatic)
  // WheelRailPatchOptions::reference of the build (format version 3; older tables: first touch).
  ContactReference contact_reference = ContactReference::smooth;
  // kNhFastSimRecipe of the build (format version 4; 0 for older tables: recipe 1 or 2).
  int nh_fastsim_recipe = kNhFastSimRecipe;
  std::string railcontact_version;
  std::string created_utc;        // ISO 8601, e.g. 2024-05-01T12:00:00Z
};

// For a flexibility or wheelset table built with an older nH-FastSim recipe than this library's
// (its metadata's nh_fastsim_recipe < kNhFastSimRecipe; 0: not recorded), what a command tells
// its user: the table still works, but its flexibilities are not today's on-the-fly ones. Empty
// for a table of the current recipe.
std::string older_nh_fastsim_recipe_note(int nh_fastsim_recipe);

// Interpolated values at (y, Fz): the fields of FlexibilityTableNode, with the flexibilities and
// creepage coefficients for the patch area area_m2.
struct FlexibilityTableValues {
  double y_m = 0.0, vertical_load_N = 0.0;
  Flexibility flexibility;
  double f11_N = 0.0, f22_N = 0.0, f23_Nm = 0.0;
  CreepageCoupling coupling;  // interpolated: its lengths (xi_per_phi_m, eta_per_phi_m) as L
  double normal_force_N = 0.0, contact_angle_rad = 0.0, spin_per_m = 0.0;
  double area_m2 = 0.0;              // the patch's own (lookup_for_patch) or the interpolated area
  double elements_in_contact = 0.0;  // interpolated
};

enum class FlexibilityInterpolation {
  area_scaled,  // L/√A, f11/A, f22/A, f23/A^1.5 (the default; see above)
  plain,        // L, f themselves (linear in y, in log Fz); for comparison
};

class FlexibilityTable {
 public:
  FlexibilityTable() = default;
  // Nodes in y-major order: nodes[iy * loads + iload]. Throws Error unless y and the loads are
  // finite and strictly increasing (loads positive), every node sits on its grid point, solved
  // nodes hold plausible values (0 < L1, L2, L3 < 1e-6 m/Pa; 0 < f11, f22 < 1e12 N;
  // 0 < f23 < 1e10 N m; 0 < F3 <= 1e8 N; |γ| <= 1.5 rad; |spin| <= 100 1/m; 0 < area < 0.01 m²;
  // at least one element; the message names nodes[k] and the key), and the jumps name distinct
  // intervals.
  FlexibilityTable(FlexibilityTableMetadata metadata, std::vector<double> y_m, std::vector<double> vertical_loads_N,
                   std::vector<FlexibilityTableNode> nodes, std::vector<ContactJump> contact_jumps = {});

  [[nodiscard]] const FlexibilityTableMetadata& metadata() const { return metadata_; }
  [[nodiscard]] const std::vector<double>& y_m() const { return y_m_; }
  [[nodiscard]] const std::vector<double>& vertical_loads_N() const { return loads_N_; }
  [[nodiscard]] const std::vector<FlexibilityTableNode>& nodes() const { return nodes_; }
  [[nodiscard]] const FlexibilityTableNode& node(std::size_t iy, std::size_t iload) const;
  [[nodiscard]] const std::vector<ContactJump>& contact_jumps() const { return jumps_; }
  [[nodiscard]] bool empty() const { return nodes_.empty(); }

  // Where the table came from, for messages: the file it was loaded from (empty when built).
  [[nodiscard]] const std::string& source() const { return source_; }
  void set_source(std::string source) { source_ = std::move(source); }
  // "flexibility table FILE" or "flexibility table".
  [[nodiscard]] std::string name() const;

  // Throws Error("flexibility table … was built for other profiles …") unless the fingerprints
  // (hashes only; the names may differ) equal the table's.
  void check_profiles(const FileFingerprint& wheel, const FileFingerprint& rail) const;
  // The same for the files the pair was read from (SmoothProfile::source()), and its track
  // parameters.
  void check_profiles(const WheelRailPair& pair) const;
  // Throws Error unless the material and K2's collocation offset are the table's.
  void check_material(const Material& material, double collocation_offset = 0.0) const;
  // Throws Error unless nH-FastSim's recipe of the caller is the table's: the flexibility
  // coarsening (NhFastSimOptions::flexibility_coarsening, 0: automatic, compared as recorded) and
  // K2's collocation offset. A case run with a table calls it with the case's values.
  void check_recipe(int flexibility_coarsening, double collocation_offset) const;
  // Throws Error unless the patch's contact reference (smooth or first touch) is the table's: the
  // two give patches of other shapes near a contact jump, and other flexibilities there.
  void check_contact_reference(ContactReference reference) const;

  // Interpolated values at (y, Fz). Throws Error naming the range when y or Fz lies outside the
  // grid (a table with one load holds that load only), or naming the node when an interval next
  // to an unsolved node (several patches, failed) is needed.
  [[nodiscard]] FlexibilityTableValues lookup(double y_m, double vertical_load_N,
                                              FlexibilityInterpolation interpolation = FlexibilityInterpolation::area_scaled) const;
  // The same for a patch of area patch_area_m2 at (y, Fz) (e.g. WheelRailPatch::area_m2): the
  // flexibilities and creepage coefficients are scaled with that area.
  [[nodiscard]] FlexibilityTableValues lookup_for_patch(
      double y_m, double vertical_load_N, double patch_area_m2,
      FlexibilityInterpolation interpolation = FlexibilityInterpolation::area_scaled) const;

 private:
  // patch_area_m2 = 0: the interpolated area.
  [[nodiscard]] FlexibilityTableValues interpolate(double y_m, double vertical_load_N, double patch_area_m2,
                                                   FlexibilityInterpolation interpolation) const;

  FlexibilityTableMetadata metadata_;
  std::vector<double> y_m_;
  std::vector<double> loads_N_;
  std::vector<FlexibilityTableNode> nodes_;
  std::vector<ContactJump> jumps_;
  std::vector<std::uint8_t> jump_after_;  // per y interval: 1 when it holds a contact jump
  std::string source_;
};

// Runs a build's independent nodes k = 0 … count−1 (docs/SCALING.md): solve(k) computes node k and
// returns it as text (an exact round trip), store(k, text) files it in the build. A runner may
// call solve on several threads at once (each call uses its own solver objects) or hand the work
// to other processes running the same build (MPI ranks), as long as, in the process whose build
// returns, every k is stored exactly once (store calls may come from any thread, one at a time).
// The nodes and the table do not depend on the runner. Empty: one node after the other on the
// calling thread. The library starts no threads and sends no messages itself.
using TableNodeSolver = std::function<std::string(std::size_t k)>;
using TableNodeStore = std::function<void(std::size_t k, const std::string& text)>;
using TableNodeRunner = std::function<void(std::size_t count, const TableNodeSolver& solve, const TableNodeStore& store)>;

struct FlexibilityTableOptions {
  // Mesh, material, normal solver of each node; vertical_load_N is replaced by the grid's loads.
  WheelRailPatchOptions patch;
  // nH-FastSim's recipe at each node: the one `railcontact run` uses unless changed here (its
  // traction bound does not enter the table).
  NhFastSimOptions nh_fastsim;
  // Contact jumps: a change of the first-touch point (on rail or wheel) larger than
  // contact_jump_m between y values at most contact_jump_resolution_m apart.
  bool locate_contact_jumps = true;
  double contact_jump_m = 0.2e-3;
  double contact_jump_resolution_m = 1e-6;
  // Who computes the nodes (above); empty: serially on the calling thread.
  TableNodeRunner runner;
  // The metadata's created_utc (ISO 8601, e.g. 2024-05-01T12:00:00Z); empty: the time of the
  // build. For reproducible files (the CLI gives SOURCE_DATE_EPOCH's time here).
  std::string created_utc;
};

// Progress of a build, reported after each node (the library does not print; the caller may).
struct FlexibilityTableProgress {
  std::size_t nodes_done = 0, nodes_total = 0;  // nodes_total includes the contact-jump brackets
  const FlexibilityTableNode* node = nullptr;    // the node just computed (solved or a gap)
  double node_seconds = 0.0;
};
using FlexibilityTableProgressCallback = std::function<void(const FlexibilityTableProgress&)>;

// Builds the table of a pair over y_grid_m (strictly increasing, m) and load_grid_N (strictly
// increasing, N, at least one), plus two bracket nodes per contact jump. The profile fingerprints
// are those of the files the pair was read from. Nodes with several patches or a failing solve
// are marked (a gap), not thrown; throws Error for bad grids or options, unreadable profile
// files, or when no node can be solved. `progress` is called after each node.
FlexibilityTable build_flexibility_table(const WheelRailPair& pair, const std::vector<double>& y_grid_m,
                                         const std::vector<double>& load_grid_N,
                                         const FlexibilityTableOptions& options = {},
                                         const FlexibilityTableProgressCallback& progress = {});

// Resource limits (docs/RELIABILITY.md "Resource limits"), checked before anything is allocated
// or built; results never depend on the machine.
// Build: every node is a wheel–rail normal solve and K2, about 0.1 s at 3000 elements in contact
// (measured: `flextable build`, 0.04–0.12 s per node), growing about as elements^1.5 (the patch
// alone: 0.11 s at 12500, 0.77 s at 50000, 6.7 s at 200000 elements). The work of a build is
// counted in nodes at 3000 elements, nodes × (target_elements / 3000)^1.5, and may not exceed
// kMaximumFlexibilityTableWork (200000 such nodes, about 5.6 hours).
inline constexpr double kFlexibilityTableSecondsPerNode = 0.1;
inline constexpr double kFlexibilityTableReferenceElements = 3000.0;
inline constexpr double kMaximumFlexibilityTableWork = 200000.0;
// At most this many y values and loads in a build's grids (10000 × 100).
inline constexpr std::size_t kMaximumFlexibilityTableYValues = 10000;
inline constexpr std::size_t kMaximumFlexibilityTableLoads = 100;
// A table (read from a file or constructed) holds at most this many nodes (y values × loads):
// twice a build's largest grid, room for the contact-jump brackets. Checked on the sizes of the
// y and load lists, before the nodes are read.
inline constexpr double kMaximumFlexibilityTableNodes = 2e6;

// Throws Error (invalid_input) unless a build of y_values × loads nodes at target_elements
// elements in contact stays within kMaximumFlexibilityTableWork: "flexibility table: 5001 y
// values × 1 load = 5001 nodes at 200000 elements in contact would take about 64 hours (about
// 0.1 s per node at 3000 elements, growing as elements^1.5); at most the work of 200000 nodes at
// 3000 elements (about 5.6 hours) is allowed: …". build_flexibility_table calls it first.
void check_flexibility_table_work(std::size_t y_values, std::size_t loads, int target_elements);

// y from y_from to y_to (inclusive, within 1e-9 of a step) in steps of y_step (m); throws Error
// for non-finite values, y_to < y_from, a non-positive step or more than 10000 values.
std::vector<double> flexibility_table_y_grid(double y_from_m, double y_to_m, double y_step_m);

// The file format (JSON, docs/FLEXTABLE.md §3). save throws Error when the file cannot be
// written; load throws Error("flexibility table FILE: …") for unreadable or malformed files
// (JSON syntax with the line, unknown format or version, missing or wrong keys, bad grids).
void save_flexibility_table(const FlexibilityTable& table, const std::filesystem::path& path);
FlexibilityTable load_flexibility_table(const std::filesystem::path& path);
std::string flexibility_table_json(const FlexibilityTable& table);
FlexibilityTable parse_flexibility_table(const std::string& json_text, const std::string& source);

std::string_view flexibility_node_status_name(FlexibilityNodeStatus status);  // solved, several-patches, failed

}  // namespace railcontact

// nH-FastSim with its flexibilities from a flexibility table (flexibility_table.hpp,
// docs/FLEXTABLE.md §5): the creep forces of a time-domain simulation step without K2.
//
//   const FlexibilityTableFastSim nh(load_flexibility_table("s1002_uic60.json"), default_wheel_rail_pair());
//   // (a) a full step: the normal problem at (y, Fz), then FastSim with the table's L
//   TangentialForces F = nh.forces(y, Fz, creepage, mu);
//   // (b) a cached patch: prepared once (normal solve, FastSim preparation, table lookup) ...
//   const FlexibilityTableFastSim::Patch patch = nh.prepare(y, Fz);
//   // ... then each step is FastSim only (a few µs at 3000 elements, no allocation):
//   for (const Creepage& c : creepages_of_each_time_step) F = patch.forces(c, mu);
//
// A simulation re-prepares the patch when y or Fz has moved by more than it tolerates (the patch,
// F3 and L follow y and Fz; between table nodes L changes by well under 1 % per 0.1 mm).
// Patch is immutable: copies share the prepared data, forces() and solve() are thread-safe, so one
// Patch per wheel can serve parallel evaluations.


namespace railcontact {

class FlexibilityTableFastSim {
 public:
  // A prepared contact: the wheel–rail patch, FastSim prepared on it, the table's values for it.
  class Patch {
   public:
    // From a patch solved by the caller (solve_wheel_rail_patch at patch.lateral_displacement_m,
    // patch.vertical_load_N); the table's L and f11, f22, f23 are scaled with the patch's area.
    // Throws Error as FlexibilityTable::lookup_for_patch does.
    Patch(const FlexibilityTable& table, WheelRailPatch patch);

    // FastSim with the table's flexibilities (Kalker's sign convention, forces on the wheel).
    // Throws Error unless mu > 0 and the creepages are finite (as FastSim does).
    [[nodiscard]] TangentialForces forces(const Creepage& creepage, double mu) const;
    [[nodiscard]] FastSimResult solve(const Creepage& creepage, double mu) const;

    // Raw creepages from normalised ones (Eq 22-23): xi = xi' 3 mu F3 / f11, eta = eta' 3 mu F3 / f22
    // with the table's f11, f22 and this patch's F3; phi as given (e.g. spin_per_m(), Eq 24).
    [[nodiscard]] Creepage creepage_from_normalised(double xi_normalised, double eta_normalised, double phi_per_m,
                                                    double mu) const;

    [[nodiscard]] const WheelRailPatch& wheel_rail_patch() const { return *patch_; }
    [[nodiscard]] const FlexibilityTableValues& table_values() const { return values_; }
    [[nodiscard]] const Flexibility& flexibility() const { return values_.flexibility; }
    [[nodiscard]] const NhFastSim& nh_fastsim() const { return nh_fastsim_; }
    [[nodiscard]] double normal_force_N() const { return patch_->normal_force_N; }
    [[nodiscard]] double spin_per_m() const { return patch_->spin_per_m; }  // from conicity, Eq 24

   private:
    std::shared_ptr<const WheelRailPatch> patch_;
    FlexibilityTableValues values_;
    NhFastSim nh_fastsim_;
  };

  // Checks once that the pair is the table's (fingerprints of its profile files, track
  // parameters); the normal problem uses the table's material and target number of elements,
  // or the given options (whose material must be the table's). Throws Error otherwise.
  FlexibilityTableFastSim(FlexibilityTable table, WheelRailPair pair);
  FlexibilityTableFastSim(FlexibilityTable table, WheelRailPair pair, const WheelRailPatchOptions& patch_options);

  // (a) The normal problem at (y, Fz) (solve_wheel_rail_patch), FastSim prepared on its patch and
  // the table's values for it; no K2. Throws Error for y or Fz outside the table (before solving),
  // a gap of the table, or a failing normal solve.
  [[nodiscard]] Patch prepare(double y_m, double vertical_load_N) const;
  // prepare(y, Fz).forces(creepage, mu).
  [[nodiscard]] TangentialForces forces(double y_m, double vertical_load_N, const Creepage& creepage, double mu) const;

  [[nodiscard]] const FlexibilityTable& table() const { return table_; }
  [[nodiscard]] const WheelRailPair& pair() const { return pair_; }
  [[nodiscard]] const WheelRailPatchOptions& patch_options() const { return patch_options_; }

 private:
  FlexibilityTable table_;
  WheelRailPair pair_;
  WheelRailPatchOptions patch_options_;
};

}  // namespace railcontact
