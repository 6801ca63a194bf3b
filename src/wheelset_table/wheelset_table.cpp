// The wheelset table at lookup (wheelset_table.hpp, docs/WHEELSET_TABLE.md): the nodes around the
// state, FastSim on their coarse patches with the state's creepages, bilinear interpolation of the
// forces.
#include "railcontact/wheelset_table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "railcontact/error.hpp"
#include "railcontact/text_file.hpp"
#include "tangential/lobe_sum.hpp"
#include "wheel_rail/wheelset_assembly.hpp"

namespace railcontact {
namespace {

constexpr double kMm = 1e-3;

bool finite3(const Vector3& v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

void check_grid(const std::vector<double>& grid, const char* name, bool positive) {
  if (grid.empty()) throw Error(fmt::format("wheelset table: the {} grid is empty", name));
  for (std::size_t i = 0; i < grid.size(); ++i) {
    if (!std::isfinite(grid[i]) || (positive && grid[i] <= 0.0))
      throw Error(fmt::format("wheelset table: {}[{}] = {} must be finite{}", name, i, grid[i], positive ? " and positive" : ""));
    if (i > 0 && grid[i] <= grid[i - 1])
      throw Error(fmt::format("wheelset table: the {} grid must be strictly increasing ({}[{}] = {} follows {})", name,
                              name, i, grid[i], grid[i - 1]));
  }
}

// A patch's lobes (two or more, or none), each with its centre and runtime copy (check_copy), and the
// whole patch's weight in [0, 1), 0 without lobes.
template <typename Fail, typename CheckCopy>
void check_lobes(const std::vector<WheelsetTableLobe>& lobes, double whole_patch_weight, const Fail& fail,
                 const CheckCopy& check_copy) {
  if (lobes.size() == 1) fail("a patch of one lobe keeps no lobes (two or more, or none)");
  if (!(whole_patch_weight >= 0.0 && whole_patch_weight < 1.0) || (whole_patch_weight > 0.0 && lobes.empty()))
    fail("the whole patch's weight must lie in [0, 1), and be 0 without lobes");
  for (const WheelsetTableLobe& l : lobes) {
    if (!std::isfinite(l.pressure_centre_x1_m) || !std::isfinite(l.pressure_centre_x2_m))
      fail("a lobe's centre of pressure must be finite");
    if (l.runtime_pressure_Pa.empty()) fail("a lobe needs its runtime pressure");
    check_copy(l);
  }
}

// A patch's conformal part: a weight in (0, 1], finite numbers, one plausible strip per column of
// its runtime copy.
template <typename Fail, typename CheckRuntime>
void check_conformal(const WheelsetTableConformalPatch& c, const Fail& fail, const CheckRuntime& check_runtime) {
  if (!(c.weight > 0.0 && c.weight <= 1.0)) fail("the conformal surface's weight must lie in (0, 1]");
  if (!(c.normal_force_N >= 0.0 && c.normal_force_N <= kMaximumNormalForce_N) || !finite3(c.pressure_force_track_N))
    fail("the conformal surface's normal force must lie in [0, 1e7] N, its resultant be finite");
  if (!(c.area_m2 >= 0.0 && c.area_m2 < 0.01) || !(c.max_pressure_Pa >= 0.0 && std::isfinite(c.max_pressure_Pa)) ||
      !std::isfinite(c.pressure_centre_x1_m) || !std::isfinite(c.pressure_centre_x2_m))
    fail("the conformal surface's area, pressure and centre must be finite (area in [0, 0.01) m²)");
  if (c.runtime_pressure_Pa.empty()) {
    if (!c.strips.empty()) fail("a conformal surface without elements in contact has no strips");
    return;
  }
  const auto check_copy = [&](const Flexibility& L, const Mesh& mesh, const std::vector<double>& pressure_Pa,
                              const std::vector<WheelsetTableStrip>& strips) {
    check_runtime(L, mesh, pressure_Pa);
    if (strips.size() != static_cast<std::size_t>(mesh.n2))
      fail("the conformal surface needs one strip per column of its runtime mesh");
    for (const WheelsetTableStrip& strip : strips)
      if (!(std::abs(strip.angle_rad) <= 1.6) || !finite3(strip.point_from_wheelset_centre_m) ||
          !(std::abs(strip.point_from_wheelset_centre_m[0]) + std::abs(strip.point_from_wheelset_centre_m[1]) +
                std::abs(strip.point_from_wheelset_centre_m[2]) <= 10.0))
        fail("a strip's angle must lie in [-1.6, 1.6] rad and its point within 10 m of the wheelset centre");
  };
  check_copy(c.flexibility, c.runtime_mesh, c.runtime_pressure_Pa, c.strips);
  check_lobes(c.lobes, c.whole_patch_weight, fail, [&](const WheelsetTableLobe& l) {
    check_copy(l.flexibility, l.runtime_mesh, l.runtime_pressure_Pa, l.strips);
  });
}

void check_patch(const WheelsetTablePatch& p, std::size_t node, int wheel, std::size_t k) {
  const auto fail = [&](const char* what) {
    throw Error(fmt::format("wheelset table: nodes[{}] wheel {} patch {}: {}", node, wheel, k, what));
  };
  if (!finite3(p.reference_point_track_m) || !finite3(p.point_from_wheelset_centre_m) || !finite3(p.x1_axis) ||
      !finite3(p.x2_axis) || !finite3(p.x3_axis))
    fail("the reference point and frame must be finite");
  if (!(std::abs(p.contact_angle_rad) <= 1.5)) fail("the contact angle must lie in [-1.5, 1.5] rad");
  if (!(p.rolling_radius_m > 0.0 && p.rolling_radius_m < 10.0)) fail("the rolling radius must lie in (0, 10) m");
  if (!std::isfinite(p.rail_profile_y_m) || !std::isfinite(p.wheel_profile_y_m)) fail("profile positions must be finite");
  if (!(p.normal_force_N >= 0.0 && p.normal_force_N <= kMaximumNormalForce_N))
    fail("the normal force must lie in [0, 1e7] N");
  if (!(p.area_m2 >= 0.0 && p.area_m2 < 0.01)) fail("the area must lie in [0, 0.01) m²");
  if (!(p.max_pressure_Pa >= 0.0 && std::isfinite(p.max_pressure_Pa))) fail("the maximum pressure must be finite, >= 0");
  if (!std::isfinite(p.pressure_centre_x1_m) || !std::isfinite(p.pressure_centre_x2_m))
    fail("the centre of pressure must be finite");
  // Plausible runtime patches only: a fuzzed table with elements of 3e99 m and a pressure of 1e306 Pa
  // made FastSim's forces overflow to NaN (fuzz/crashes/wheelset_table/). A coarse element is at
  // most a few millimetres, a pressure at most a few GPa, a flexibility about 1e-14 m/Pa.
  const auto check_runtime = [&](const Flexibility& L, const Mesh& mesh, const std::vector<double>& pressure_Pa) {
    for (double l : {L.L1, L.L2, L.L3})
      if (!(l >= 1e-18 && l < 1e-6)) fail("the flexibilities must lie in [1e-18, 1e-6) m/Pa");
    validate(mesh, 1u << 20);
    if (!(mesh.dx1_m <= 0.05 && mesh.dx2_m <= 0.05)) fail("the runtime mesh's elements must be at most 0.05 m long");
    if (!(std::abs(mesh.x1_first_m) <= 1.0 && std::abs(mesh.x2_first_m) <= 1.0))
      fail("the runtime mesh must start within 1 m of the centre of pressure");
    if (pressure_Pa.size() != mesh.size()) fail("the runtime pressure needs one value per mesh element");
    for (double p3 : pressure_Pa)
      if (!(p3 >= 0.0 && p3 <= 1e11)) fail("the runtime pressures must lie in [0, 1e11] Pa");
  };
  if (p.conformal) check_conformal(*p.conformal, fail, check_runtime);
  if (p.runtime_pressure_Pa.empty()) {  // a patch with overlap but no element in contact (or fully conformal)
    if (!p.lobes.empty()) fail("a patch without elements in contact has no lobes");
    // Its planar forces would be zero: only a fully conformal patch has elements and no planar copy.
    if (p.elements_in_contact > 0 && !(p.conformal && p.conformal->weight == 1.0))
      fail("a patch with elements in contact needs its runtime copy (runtime_pressure_Pa)");
    return;
  }
  check_runtime(p.flexibility, p.runtime_mesh, p.runtime_pressure_Pa);
  check_lobes(p.lobes, p.whole_patch_weight, fail, [&](const WheelsetTableLobe& l) {
    check_runtime(l.flexibility, l.runtime_mesh, l.runtime_pressure_Pa);
  });
}

// Every runtime copy's creepage coupling (CreepageCoupling::plausible).
void check_couplings(const WheelsetTablePatch& p, std::size_t node, int wheel, std::size_t k) {
  bool plausible = p.coupling.plausible();
  for (const WheelsetTableLobe& l : p.lobes) plausible = plausible && l.coupling.plausible();
  if (p.conformal) {
    plausible = plausible && p.conformal->coupling.plausible();
    for (const WheelsetTableLobe& l : p.conformal->lobes) plausible = plausible && l.coupling.plausible();
  }
  if (!plausible)
    throw Error(fmt::format("wheelset table: nodes[{}] wheel {} patch {}: the creepage coupling's ratios must lie "
                            "within ±1 and its lengths within ±0.1 m",
                            node, wheel, k));
}

// The interval of `grid` holding x and the weight of its upper node; a grid of one value holds
// only that value.
struct Bracket {
  std::size_t lower = 0, upper = 0;
  double upper_weight = 0.0;
};
Bracket bracket(const std::vector<double>& grid, double x, const char* what, const char* unit, double scale) {
  const double tolerance = 1e-9 * std::max(1.0, std::abs(grid.back() - grid.front()));
  if (!(x >= grid.front() - tolerance && x <= grid.back() + tolerance)) {
    throw Error(fmt::format("wheelset table: {} = {:.6g} {} lies outside the table's range [{:.6g}, {:.6g}] {}", what,
                            x / scale, unit, grid.front() / scale, grid.back() / scale, unit));
  }
  Bracket b;
  if (grid.size() == 1) return b;
  const auto it = std::upper_bound(grid.begin(), grid.end(), x);
  b.upper = std::min<std::size_t>(static_cast<std::size_t>(it - grid.begin()), grid.size() - 1);
  b.lower = b.upper - 1;
  b.upper_weight = std::clamp((x - grid[b.lower]) / (grid[b.upper] - grid[b.lower]), 0.0, 1.0);
  return b;
}



// A patch's forces at a lookup: the tangential forces on the wheel (contact frame; on a conformal
// patch F1, F2 the projections of the whole contact force, as Wheelset::evaluate gives them) and
// the whole contact force in the track frame.
struct PatchForces {
  TangentialForces forces{};
  Vector3 track_N{};
};

// The rotation about the vertical by the yaw a node does not have.
struct Turn {
  explicit Turn(double angle_rad) : cos(std::cos(angle_rad)), sin(std::sin(angle_rad)) {}
  [[nodiscard]] Vector3 operator()(const Vector3& r) const { return {cos * r[0] - sin * r[1], sin * r[0] + cos * r[1], r[2]}; }
  double cos, sin;
};

// The tractions of FastSim on one runtime copy of a conformal patch (the whole patch's or a lobe's,
// in the solve frame, its origin at its centre x1c_m along X1 from the reference point): each
// strip's creepages in its own frame (X1, t, n) at its creepage point (turned by the yaw the node
// does not have), over the patch's rolling speed; the sums of every element's traction along X1 and
// along its strip's tangent resolved on X2 and X3 (still in the solve frame), and FastSim's forces.
struct CopyTractions {
  double t1 = 0.0, t2 = 0.0, t3 = 0.0;
  TangentialForces fastsim{};  // F1, F2 in the developed solve frame; M3 about the copy's origin
};
// (Copy: WheelsetTable's private RuntimePatch::CurvedCopy.)
template <typename Copy>
CopyTractions copy_tractions(const Copy& copy, double x1c_m, const WheelsetKinematics& kinematics, double patch_speed,
                             const Turn& turn, double s2, double mu) {
  const std::vector<double>&cos_angle = copy.cos_angle, &sin_angle = copy.sin_angle;
  StripCreepages creepages(copy.frames.size());
  for (std::size_t j = 0; j < creepages.size(); ++j) {
    ContactFrame frame = copy.frames[j];
    frame.point_from_wheelset_centre_m = turn(frame.point_from_wheelset_centre_m);
    const WheelsetKinematics::AtContact at = kinematics.at(frame);
    const double scale = at.rolling_speed_m_per_s / patch_speed;
    const Creepage& k = at.creepage;
    // In the solve frame (x2 -> −x2 for a left wheel), from the copy's origin.
    const double phi = s2 * k.phi * scale;
    creepages[j] = {k.xi * scale, s2 * k.eta * scale + phi * x1c_m, phi};
  }
  const TangentialSolution f = copy.model.solve(creepages, mu, TangentialOutput::strip_forces);
  CopyTractions out;
  for (std::size_t j = 0; j < creepages.size(); ++j) {
    out.t1 += f.strip_F1_N[j];
    out.t2 += f.strip_F2_N[j] * cos_angle[j];
    out.t3 += f.strip_F2_N[j] * sin_angle[j];
  }
  out.fastsim = f.forces;
  return out;
}

// A conformal patch's forces at a lookup (docs/WHEELSET.md §4 "Conformal contact"): FastSim strip
// by strip on its runtime copy, or on each lobe's with its own flexibilities (blended with the whole
// copy's where a neck is: WheelsetTableConformalPatch::whole_patch_weight), every element's traction
// along its strip's tangent and its pressure along its strip's normal summed in the patch's frame.
// (Runtime: WheelsetTable's private RuntimePatch of the patch.)
template <typename Runtime>
PatchForces conformal_patch_forces(const Runtime& runtime, const WheelsetTablePatch& p,
                                   const WheelsetKinematics& kinematics, const Turn& turn, double s2,
                                   double mu) {
  const WheelsetTableConformalPatch& c = *p.conformal;
  const Vector3& r = p.point_from_wheelset_centre_m;
  const ContactFrame patch_frame{turn(r),
                                 p.x1_axis, p.x2_axis, p.x3_axis};
  const double patch_speed = kinematics.rolling_speed_m_per_s(patch_frame);
  const auto on = [&](const auto& copy, double x1c_m) {
    return copy_tractions(copy, x1c_m, kinematics, patch_speed, turn, s2, mu);
  };
  CopyTractions sum;
  double M3 = 0.0;  // solve frame, about the copy's centre
  if (c.lobes.empty()) {
    sum = on(*runtime.conformal, c.pressure_centre_x1_m);
    M3 = sum.fastsim.M3_Nm;
  } else {
    // Each lobe at its own centre (solve frame: x2 mirrored); M3 about the patch's centre.
    for (std::size_t k = 0; k < c.lobes.size(); ++k) {
      const WheelsetTableLobe& lobe = c.lobes[k];
      const CopyTractions t = on(runtime.conformal_lobes[k], lobe.pressure_centre_x1_m);
      sum.t1 += t.t1;
      sum.t2 += t.t2;
      sum.t3 += t.t3;
      M3 += detail::moment_about_origin_Nm(t.fastsim, lobe.pressure_centre_x1_m - c.pressure_centre_x1_m,
                                           s2 * (lobe.pressure_centre_x2_m - c.pressure_centre_x2_m));
    }
    if (const double w = c.whole_patch_weight; w > 0.0) {
      const CopyTractions whole = on(*runtime.conformal, c.pressure_centre_x1_m);
      sum.t1 = detail::blend(sum.t1, whole.t1, w);
      sum.t2 = detail::blend(sum.t2, whole.t2, w);
      sum.t3 = detail::blend(sum.t3, whole.t3, w);
      M3 = detail::blend(M3, whole.fastsim.M3_Nm, w);
    }
  }
  PatchForces out;
  for (std::size_t i = 0; i < 3; ++i)
    out.track_N[i] = sum.t1 * p.x1_axis[i] + s2 * sum.t2 * p.x2_axis[i] + s2 * sum.t3 * p.x3_axis[i] +
                     c.pressure_force_track_N[i];
  const auto dot = [](const Vector3& a, const Vector3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  out.forces = {sum.t1, dot(out.track_N, p.x2_axis), s2 * M3};
  return out;
}

// A lookup's state, friction coefficient and motion checked before any work (the loads and the
// table's ranges are checked where they are bracketed).
void check_lookup_state(const WheelsetState& state, double friction_coefficient) {
  // The nodes have zero roll; a roll would turn the contact points and frames the table does not
  // have (its kinematic creepages alone moved Fx from -4482 N to 14 N at 10 mrad, where the wheelset
  // solved at that roll gives 18320 N).
  if (state.position.roll_rad != 0.0)
    throw Error(fmt::format("wheelset table: the roll {:g} mrad must be zero: the table's nodes have zero roll (each "
                            "wheel's height is solved for its load); evaluate a rolled wheelset on the fly",
                            state.position.roll_rad * 1e3));
  if (!(friction_coefficient > 0.0 && std::isfinite(friction_coefficient)))
    throw Error(fmt::format("wheelset table: the friction coefficient {} must be positive and finite", friction_coefficient));
  const WheelsetPosition& position = state.position;
  if (!std::isfinite(position.lateral_displacement_m) || !std::isfinite(position.yaw_rad) ||
      !(std::abs(position.yaw_rad) <= 0.1))
    throw Error(fmt::format("wheelset table: the lateral displacement {} m and yaw {} rad must be finite, |yaw| <= 0.1 rad",
                            position.lateral_displacement_m, position.yaw_rad));
  validate(state.velocity);
  if (state.velocity.free_rolling)
    throw Error("wheelset table: free rolling is solved by Wheelset::evaluate only; from a table give the wheels' "
                "angular velocity or the extra longitudinal creepage");
}

// A planar patch's tangential forces at a lookup (on the wheel, contact frame, M3 about its centre
// of pressure): the table-driven model on its runtime copy or its lobes' (TangentialModel on a
// StoredPatch), as NhFastSimPerLobe solves a patch on the fly. (Runtime: WheelsetTable's private
// RuntimePatch of the patch.)
template <typename Runtime>
TangentialForces planar_patch_forces(const Runtime& runtime, const WheelsetTablePatch& p, const Creepage& creepage,
                                     double s2, double mu) {
  if (!runtime.planar) return {};  // no element in contact yet
  // In the solve frame (x2 -> −x2 for a left wheel), at the coarse patch's centre of pressure.
  const Creepage c_solve{creepage.xi, s2 * creepage.eta, s2 * creepage.phi};
  const Creepage at_centre = detail::creepage_at(c_solve, p.pressure_centre_x1_m, s2 * p.pressure_centre_x2_m);
  TangentialForces forces = runtime.planar->solve(at_centre, mu, TangentialOutput::forces_only).forces;
  forces.F2_N *= s2;
  forces.M3_Nm *= s2;
  return forces;
}

// A patch's table-driven tangential models (WheelsetTable's private RuntimePatch): its runtime copy
// and its lobes' as a StoredPatch (solve frame, s2 = −1 for a left wheel; the lobes' centres from
// the patch's centre of pressure), and its conformal copy and lobes' each with its strips' frames.
template <typename Runtime>
Runtime runtime_patch(const WheelsetTablePatch& p, double s2, const Material& material, const TractionBound& bound) {
  TangentialModelOptions options;
  options.nh_fastsim.bound = bound;
  Runtime runtime;
  const auto lobe = [&](const Mesh& mesh, const std::vector<double>& pressure_Pa, const Flexibility& flexibility,
                        const CreepageCoupling& coupling, double x1_m, double x2_m) {
    return StoredLobe{ContactPatch(mesh, pressure_Pa, material), flexibility, x1_m, s2 * x2_m, coupling};
  };
  if (!p.runtime_pressure_Pa.empty()) {
    StoredPatch stored;
    const StoredLobe whole = lobe(p.runtime_mesh, p.runtime_pressure_Pa, p.flexibility, p.coupling, 0.0, 0.0);
    for (const WheelsetTableLobe& l : p.lobes)
      stored.lobes.push_back(lobe(l.runtime_mesh, l.runtime_pressure_Pa, l.flexibility, l.coupling,
                                  l.pressure_centre_x1_m - p.pressure_centre_x1_m,
                                  l.pressure_centre_x2_m - p.pressure_centre_x2_m));
    if (stored.lobes.empty()) {
      stored.lobes.push_back(whole);
    } else if (p.whole_patch_weight > 0.0) {
      stored.whole = whole;
      stored.whole_patch_weight = p.whole_patch_weight;
    }
    runtime.planar.emplace(stored, options);
  }
  if (p.conformal && !p.conformal->runtime_pressure_Pa.empty()) {
    const auto curved = [&](const Mesh& mesh, const std::vector<double>& pressure_Pa, const Flexibility& flexibility,
                            const CreepageCoupling& coupling, const std::vector<WheelsetTableStrip>& strips) {
      StoredPatch stored;
      stored.lobes.push_back(lobe(mesh, pressure_Pa, flexibility, coupling, 0.0, 0.0));
      typename Runtime::CurvedCopy c{TangentialModel(stored, options), {}, {}, {}};
      for (const WheelsetTableStrip& strip : strips) {
        const double cos_angle = std::cos(strip.angle_rad), sin_angle = std::sin(strip.angle_rad);
        ContactFrame& frame = c.frames.emplace_back();
        frame.point_from_wheelset_centre_m = strip.point_from_wheelset_centre_m;
        frame.x1 = p.x1_axis;
        for (std::size_t i = 0; i < 3; ++i) {
          frame.x2[i] = cos_angle * p.x2_axis[i] + sin_angle * p.x3_axis[i];
          frame.x3[i] = cos_angle * p.x3_axis[i] - sin_angle * p.x2_axis[i];
        }
        c.cos_angle.push_back(cos_angle);
        c.sin_angle.push_back(sin_angle);
      }
      return c;
    };
    const WheelsetTableConformalPatch& c = *p.conformal;
    runtime.conformal.emplace(curved(c.runtime_mesh, c.runtime_pressure_Pa, c.flexibility, c.coupling, c.strips));
    for (const WheelsetTableLobe& l : c.lobes)
      runtime.conformal_lobes.push_back(
          curved(l.runtime_mesh, l.runtime_pressure_Pa, l.flexibility, l.coupling, l.strips));
  }
  return runtime;
}

// A node's patch at a lookup: its creepages, forces and numbers on its surface (the planar one,
// the conformal one, or their blend by the patch's conformal weight, as Wheelset::evaluate blends
// them), and its reference point turned with the node's contact points.
struct PatchAtLookup {
  Creepage creepage{};
  Vector3 reference_point_track_m{};
  PatchForces total{};
  Vector3 pressure_force_track_N{};
  double surface_weight = 0.0, normal_force_N = 0.0, area_m2 = 0.0, max_pressure_Pa = 0.0, elements = 0.0;
  double centre_x1_m = 0.0, centre_x2_m = 0.0;
  Flexibility flexibility{};
};

// One patch of the lookup: the contributions of the nodes that have it.
struct PatchSum {
  double rail_profile_y_m = 0.0;  // of its first contribution (for matching)
  std::vector<std::size_t> nodes;  // the nodes that contributed
  double present_weight = 0.0;     // sum of their weights
  // Weighted sums (over the nodes present) of the geometry and creepages ...
  Vector3 reference_point_track_m{}, x1{}, x2{}, x3{};
  double contact_angle_rad = 0.0, rolling_radius_m = 0.0, wheel_profile_y_m = 0.0, rail_y_sum_m = 0.0;
  double area_m2 = 0.0, elements = 0.0, max_pressure_Pa = 0.0, centre_x1_m = 0.0, centre_x2_m = 0.0;
  Creepage creepage{0.0, 0.0, 0.0};
  Flexibility flexibility{0.0, 0.0, 0.0};
  // ... and of the forces (a node without the patch counts with zero force).
  TangentialForces forces{};
  double normal_force_N = 0.0;
  Vector3 force_track_N{}, pressure_force_track_N{};
  double conformal_weight = 0.0;  // over the nodes present

  // Node n's patch at the lookup with the node's weight.
  void add(const PatchAtLookup& at, const WheelsetTablePatch& p, double weight);
  // The wheel's patch: averages over the nodes present, forces summed.
  [[nodiscard]] WheelsetPatch patch(WheelSide side) const;
};

template <typename Runtime>
PatchAtLookup patch_at_lookup(const Runtime& runtime, const WheelsetTablePatch& p, double node_y_m, const Turn& turn,
                              WheelSide side, double s2, const WheelsetMotion& motion,
                              const WheelsetKinematics& kinematics, double mu) {
  PatchAtLookup at;
  // The contact frame stays the rail's.
  const ContactFrame frame{turn(p.point_from_wheelset_centre_m), p.x1_axis, p.x2_axis, p.x3_axis};
  at.creepage = kinematics.at(frame).creepage;
  check_kinematic_creepage(at.creepage, motion, frame, side);
  const TangentialForces forces = planar_patch_forces(runtime, p, at.creepage, s2, mu);
  at.total = {forces, {}};
  for (std::size_t i = 0; i < 3; ++i) {
    at.total.track_N[i] = forces.F1_N * p.x1_axis[i] + forces.F2_N * p.x2_axis[i] + p.normal_force_N * p.x3_axis[i];
    at.pressure_force_track_N[i] = p.normal_force_N * p.x3_axis[i];
  }
  at.normal_force_N = p.normal_force_N;
  at.area_m2 = p.area_m2;
  at.max_pressure_Pa = p.max_pressure_Pa;
  at.elements = static_cast<double>(p.elements_in_contact);
  at.centre_x1_m = p.pressure_centre_x1_m;
  at.centre_x2_m = p.pressure_centre_x2_m;
  at.flexibility = p.flexibility;
  if (p.conformal) {
    const WheelsetTableConformalPatch& curved = *p.conformal;
    const double weight = at.surface_weight = curved.weight;
    PatchForces on_curve{{}, curved.pressure_force_track_N};  // no element in contact yet: its pressure only
    if (runtime.conformal) on_curve = conformal_patch_forces(runtime, p, kinematics, turn, s2, mu);
    const auto mix = [weight](double a, double b) { return (1.0 - weight) * a + weight * b; };
    at.total.forces = {mix(forces.F1_N, on_curve.forces.F1_N), mix(forces.F2_N, on_curve.forces.F2_N),
                       mix(forces.M3_Nm, on_curve.forces.M3_Nm)};
    for (std::size_t i = 0; i < 3; ++i) {
      at.total.track_N[i] = mix(at.total.track_N[i], on_curve.track_N[i]);
      at.pressure_force_track_N[i] = mix(at.pressure_force_track_N[i], curved.pressure_force_track_N[i]);
    }
    at.normal_force_N = mix(at.normal_force_N, curved.normal_force_N);
    at.area_m2 = mix(at.area_m2, curved.area_m2);
    at.max_pressure_Pa = mix(at.max_pressure_Pa, curved.max_pressure_Pa);
    at.elements = mix(at.elements, static_cast<double>(curved.elements_in_contact));
    at.centre_x1_m = mix(at.centre_x1_m, curved.pressure_centre_x1_m);
    at.centre_x2_m = mix(at.centre_x2_m, curved.pressure_centre_x2_m);
    at.flexibility = {mix(at.flexibility.L1, curved.flexibility.L1), mix(at.flexibility.L2, curved.flexibility.L2),
                      mix(at.flexibility.L3, curved.flexibility.L3)};
  }
  // The reference point turned about the wheelset centre (0, y_node, ·) as the contact point is.
  const Vector3& q = p.reference_point_track_m;
  at.reference_point_track_m = {node_y_m * turn.sin + turn.cos * q[0] - turn.sin * q[1],
                                node_y_m + turn.sin * q[0] + turn.cos * (q[1] - node_y_m), q[2]};
  return at;
}

void PatchSum::add(const PatchAtLookup& at, const WheelsetTablePatch& p, double weight) {
  present_weight += weight;
  for (std::size_t i = 0; i < 3; ++i) {
    reference_point_track_m[i] += weight * at.reference_point_track_m[i];
    x1[i] += weight * p.x1_axis[i];
    x2[i] += weight * p.x2_axis[i];
    x3[i] += weight * p.x3_axis[i];
    force_track_N[i] += weight * at.total.track_N[i];
    pressure_force_track_N[i] += weight * at.pressure_force_track_N[i];
  }
  contact_angle_rad += weight * p.contact_angle_rad;
  rolling_radius_m += weight * p.rolling_radius_m;
  wheel_profile_y_m += weight * p.wheel_profile_y_m;
  rail_y_sum_m += weight * p.rail_profile_y_m;
  area_m2 += weight * at.area_m2;
  elements += weight * at.elements;
  max_pressure_Pa += weight * at.max_pressure_Pa;
  centre_x1_m += weight * at.centre_x1_m;
  centre_x2_m += weight * at.centre_x2_m;
  creepage.xi += weight * at.creepage.xi;
  creepage.eta += weight * at.creepage.eta;
  creepage.phi += weight * at.creepage.phi;
  flexibility.L1 += weight * at.flexibility.L1;
  flexibility.L2 += weight * at.flexibility.L2;
  flexibility.L3 += weight * at.flexibility.L3;
  forces.F1_N += weight * at.total.forces.F1_N;
  forces.F2_N += weight * at.total.forces.F2_N;
  forces.M3_Nm += weight * at.total.forces.M3_Nm;
  normal_force_N += weight * at.normal_force_N;
  conformal_weight += weight * at.surface_weight;
}

WheelsetPatch PatchSum::patch(WheelSide side) const {
  const double g = 1.0 / present_weight;  // averages over the nodes present
  WheelsetPatch patch;
  patch.side = side;
  InterpenetrationRegion& region = patch.region;
  region.side = side;
  for (std::size_t i = 0; i < 3; ++i) region.reference_point_track_m[i] = g * reference_point_track_m[i];
  const auto unit = [](const Vector3& v) {
    const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    return Vector3{v[0] / n, v[1] / n, v[2] / n};
  };
  region.x1_axis = unit(x1);
  region.x2_axis = unit(x2);
  region.x3_axis = unit(x3);
  region.rail_profile_y_m = g * rail_y_sum_m;
  region.wheel_profile_y_m = g * wheel_profile_y_m;
  region.contact_angle_rad = g * contact_angle_rad;
  region.rolling_radius_m = g * rolling_radius_m;
  patch.creepage = Creepage{g * creepage.xi, g * creepage.eta, g * creepage.phi};
  patch.normal_force_N = normal_force_N;
  patch.pressure_force_track_N = pressure_force_track_N;
  patch.conformal_weight = g * conformal_weight;
  patch.surface = patch.conformal_weight > 0.0 ? ContactSurface::conformal : ContactSurface::planar;
  patch.area_m2 = area_m2;
  patch.elements_in_contact = static_cast<std::size_t>(std::lround(elements));
  patch.max_pressure_Pa = max_pressure_Pa;
  patch.pressure_centre_x1_m = g * centre_x1_m;
  patch.pressure_centre_x2_m = g * centre_x2_m;
  PatchSolverResult r;
  r.solver = TangentialSolver::nh_fastsim;
  r.forces = forces;
  r.force_track_N = force_track_N;
  r.flexibility = Flexibility{g * flexibility.L1, g * flexibility.L2, g * flexibility.L3};
  patch.solvers.push_back(r);
  return patch;
}

// The sum of the lookup's patch at nearly the same place on the rail profile that node n has not
// contributed to yet, or a new one.
PatchSum& matching_sum(std::vector<PatchSum>& sums, double rail_profile_y_m, std::size_t n) {
  for (PatchSum& s : sums)
    if (std::abs(s.rail_profile_y_m - rail_profile_y_m) <= kWheelsetTablePatchMatchDistance_m &&
        std::find(s.nodes.begin(), s.nodes.end(), n) == s.nodes.end())
      return s;
  PatchSum& s = sums.emplace_back();
  s.rail_profile_y_m = rail_profile_y_m;
  return s;
}

// The grid cell around a lookup (per axis the grid indices below and above and the upper one's
// weight), the state's yaw, motion and friction coefficient.
struct LookupCell {
  Bracket y, yaw, load;
  double yaw_rad = 0.0;
};
struct Lookup {
  LookupCell cell;
  const WheelsetMotion& motion;
  const WheelsetKinematics& kinematics;
  double mu;
};

// A patch's results at one state, by (node, wheel, patch): they do not depend on the load weights.
using PatchResults = std::map<std::array<std::size_t, 3>, PatchAtLookup>;

// One wheel from the table: each node of the cell around the lookup contributes its patches with
// its weight; patches of different nodes at nearly the same place on the rail profile are one
// patch. (RuntimeTable: WheelsetTable's private runtime copies, parallel to the nodes.) A patch
// already solved for this state (`known`) is only weighted.
template <typename RuntimeTable>
WheelResult evaluate_wheel(WheelSide side, const Lookup& lookup, const WheelsetTableGrid& grid_,
                           const std::vector<WheelsetTableNode>& nodes_, const RuntimeTable& runtime_,
                           PatchResults& known) {
  const LookupCell& cell = lookup.cell;
  const std::size_t w = side == WheelSide::right ? 0 : 1;
  const double s2 = side == WheelSide::left ? -1.0 : 1.0;  // the solve frame mirrors a left wheel
  WheelResult wheel;
  wheel.side = side;
  std::vector<PatchSum> sums;
  for (int c = 0; c < 8; ++c) {  // the corners of the cell: bit 0 y, bit 1 yaw, bit 2 load
    const bool upper_y = c & 1, upper_yaw = c & 2, upper_load = c & 4;
    const double weight = (upper_y ? cell.y.upper_weight : 1.0 - cell.y.upper_weight) *
                          (upper_yaw ? cell.yaw.upper_weight : 1.0 - cell.yaw.upper_weight) *
                          (upper_load ? cell.load.upper_weight : 1.0 - cell.load.upper_weight);
    if (weight <= 0.0) continue;
    const std::size_t n = grid_.index(upper_y ? cell.y.upper : cell.y.lower, upper_yaw ? cell.yaw.upper : cell.yaw.lower,
                                      upper_load ? cell.load.upper : cell.load.lower);
    const WheelsetTableNode& node = nodes_[n];
    if (node.status != WheelsetTableNodeStatus::solved)
      throw Error(fmt::format("wheelset table: the node at y = {:.4g} mm, yaw {:.4g} mrad, load {:.4g} kN is a gap ({})",
                              node.y_m / kMm, node.yaw_rad / 1e-3, node.wheel_load_N / 1e3, node.message));
    // The node's contact points, turned by the yaw the node does not have.
    const Turn turn(cell.yaw_rad - node.yaw_rad);
    wheel.vertical_displacement_m += weight * node.vertical_displacement_m[w];
    for (std::size_t k = 0; k < node.wheels[w].size(); ++k) {
      const WheelsetTablePatch& p = node.wheels[w][k];
      const std::array<std::size_t, 3> key{n, w, k};
      auto found = known.find(key);
      if (found == known.end())
        found = known
                    .emplace(key, patch_at_lookup(runtime_[n][w][k], p, node.y_m, turn, side, s2, lookup.motion,
                                                  lookup.kinematics, lookup.mu))
                    .first;
      const PatchAtLookup& at = found->second;
      PatchSum& sum = matching_sum(sums, p.rail_profile_y_m, n);
      sum.nodes.push_back(n);
      sum.add(at, p, weight);
    }
  }
  // The patches, gauge side first, each from its sums.
  std::sort(sums.begin(), sums.end(), [](const PatchSum& a, const PatchSum& b) {
    return a.rail_y_sum_m / a.present_weight < b.rail_y_sum_m / b.present_weight;
  });
  for (const PatchSum& s : sums) wheel.patches.push_back(s.patch(side));
  detail::sum_wheel_forces(wheel, 1);  // nH-FastSim's
  return wheel;
}

}  // namespace

void validate(const WheelsetTableGrid& grid) {
  check_grid(grid.y_m, "y", false);
  check_grid(grid.yaw_rad, "yaw", false);
  check_grid(grid.wheel_load_N, "wheel load", true);
  if (!(grid.yaw_rad.front() >= -0.1 && grid.yaw_rad.back() <= 0.1))
    throw Error(fmt::format("wheelset table: the yaw grid [{}, {}] rad must lie in [-0.1, 0.1] rad", grid.yaw_rad.front(),
                            grid.yaw_rad.back()));
}

WheelsetTable::WheelsetTable(WheelsetTableGrid grid, std::vector<WheelsetTableNode> nodes,
                             double nominal_rolling_radius_m, Material material, TractionBound bound,
                             WheelsetTableMetadata metadata)
    : grid_(std::move(grid)),
      nodes_(std::move(nodes)),
      nominal_rolling_radius_m_(nominal_rolling_radius_m),
      material_(material),
      bound_(bound),
      metadata_(std::move(metadata)) {
  validate(grid_);
  if (!(nominal_rolling_radius_m_ > 0.0 && nominal_rolling_radius_m_ < 10.0))
    throw Error(fmt::format("wheelset table: the nominal rolling radius {} m must lie in (0, 10) m", nominal_rolling_radius_m_));
  if (nodes_.size() != grid_.size())
    throw Error(fmt::format("wheelset table: {} nodes for {} y values × {} yaws × {} loads", nodes_.size(),
                            grid_.y_m.size(), grid_.yaw_rad.size(), grid_.wheel_load_N.size()));
  runtime_.resize(nodes_.size());
  for (std::size_t n = 0; n < nodes_.size(); ++n) {
    const WheelsetTableNode& node = nodes_[n];
    const std::size_t loads = grid_.wheel_load_N.size(), yaws = grid_.yaw_rad.size();
    const double y = grid_.y_m[n / (loads * yaws)], yaw = grid_.yaw_rad[(n / loads) % yaws];
    const double load = grid_.wheel_load_N[n % loads];
    if (std::abs(node.y_m - y) > 1e-12 || std::abs(node.yaw_rad - yaw) > 1e-12 ||
        std::abs(node.wheel_load_N - load) > 1e-9 * load)
      throw Error(fmt::format("wheelset table: nodes[{}] (y = {} m, yaw {} rad, load {} N) is not on its grid point "
                              "(y = {} m, yaw {} rad, load {} N)",
                              n, node.y_m, node.yaw_rad, node.wheel_load_N, y, yaw, load));
    if (node.status != WheelsetTableNodeStatus::solved) continue;
    for (int w = 0; w < 2; ++w) {
      if (!std::isfinite(node.vertical_displacement_m[w]))
        throw Error(fmt::format("wheelset table: nodes[{}] wheel {}: the vertical displacement must be finite", n, w));
      for (std::size_t k = 0; k < node.wheels[w].size(); ++k) {
        const WheelsetTablePatch& p = node.wheels[w][k];
        check_patch(p, n, w, k);
        check_couplings(p, n, w, k);
        runtime_[n][w].push_back(runtime_patch<RuntimePatch>(p, w == 1 ? -1.0 : 1.0, material_, bound_));
      }
    }
  }
}

const WheelsetTableNode& WheelsetTable::node(std::size_t iy, std::size_t iyaw, std::size_t iload) const {
  if (iy >= grid_.y_m.size() || iyaw >= grid_.yaw_rad.size() || iload >= grid_.wheel_load_N.size())
    throw Error(fmt::format("wheelset table: node ({}, {}, {}) outside the {} × {} × {} grid", iy, iyaw, iload,
                            grid_.y_m.size(), grid_.yaw_rad.size(), grid_.wheel_load_N.size()));
  return nodes_[grid_.index(iy, iyaw, iload)];
}

void WheelsetTable::check_track(const WheelsetTrack& track) const {
  const std::string name = source_.empty() ? "the wheelset table" : "wheelset table " + source_;
  const auto check = [&](const FileFingerprint& recorded, const std::string& source, const char* which) {
    FileFingerprint actual{source, 0};
    try {
      actual = file_fingerprint(source);
    } catch (const Error&) {  // not a file: compared by name
    }
    const bool same = recorded.fnv1a64 != 0 ? actual.fnv1a64 == recorded.fnv1a64 : actual.file == recorded.file;
    if (!same)
      throw Error(fmt::format("{} was built for another {} profile ({}, FNV-1a {}), not {} (FNV-1a {})", name, which,
                              recorded.file, recorded.hash_hex(), source, actual.hash_hex()));
  };
  check(metadata_.right_wheel_profile, track.pair(WheelSide::right).wheel().source(), "right wheel");
  check(metadata_.right_rail_profile, track.pair(WheelSide::right).rail().source(), "right rail");
  check(metadata_.left_wheel_profile, track.pair(WheelSide::left).wheel().source(), "left wheel");
  check(metadata_.left_rail_profile, track.pair(WheelSide::left).rail().source(), "left rail");
  const TrackWheelsetParameters& a = metadata_.track;
  const TrackWheelsetParameters& b = track.parameters();
  if (a.track_gauge_m != b.track_gauge_m || a.gauge_measuring_depth_m != b.gauge_measuring_depth_m ||
      a.flange_back_distance_m != b.flange_back_distance_m || a.flange_back_y_m != b.flange_back_y_m ||
      a.taping_line_from_flange_back_m != b.taping_line_from_flange_back_m ||
      a.nominal_rolling_radius_m != b.nominal_rolling_radius_m || a.nominal_radius_at != b.nominal_radius_at ||
      a.rail_cant_rad != b.rail_cant_rad)
    throw Error(fmt::format("{} was built for other track parameters (gauge {} m, flange-back distance {} m, nominal "
                            "rolling radius {} m at the {}, rail cant {} rad){}",
                            name, a.track_gauge_m, a.flange_back_distance_m, a.nominal_rolling_radius_m,
                            a.nominal_radius_at == NominalRadiusDatum::taping_line ? "taping line" : "profile origin",
                            a.rail_cant_rad,
                            a.nominal_radius_at != b.nominal_radius_at
                                ? fmt::format(": this track measures r0 at the {}; rebuild the table",
                                              b.nominal_radius_at == NominalRadiusDatum::taping_line ? "taping line"
                                                                                                     : "profile origin")
                            : a.rail_cant_rad != b.rail_cant_rad
                                ? fmt::format(": this track's rail cant is {} rad; rebuild the table", b.rail_cant_rad)
                                : std::string()));
}

const char* wheelset_table_setting_name(WheelsetTableSetting setting) {
  switch (setting) {
    case WheelsetTableSetting::material: return "material";
    case WheelsetTableSetting::element_size: return "element-size";
    case WheelsetTableSetting::flexibility_coarsening: return "flexibility-coarsening";
    case WheelsetTableSetting::collocation_offset: return "collocation-offset";
    case WheelsetTableSetting::slip_direction: return "slip-direction";
    case WheelsetTableSetting::traction_bound_skew: return "traction-bound-skew";
    case WheelsetTableSetting::nh_fastsim_recipe: return "recipe";
    case WheelsetTableSetting::contact_definition: return "contact-definition";
    case WheelsetTableSetting::contact_surface: return "contact-surface";
    case WheelsetTableSetting::patch_coupling: return "patch-coupling";
  }
  return "?";
}

WheelsetTableSetting parse_wheelset_table_setting(const std::string& name) {
  std::string allowed;
  for (WheelsetTableSetting s : kWheelsetTableSettings) {
    if (name == wheelset_table_setting_name(s)) return s;
    allowed += fmt::format("{}{}", allowed.empty() ? "" : ", ", wheelset_table_setting_name(s));
  }
  throw Error(fmt::format("unknown wheelset-table setting '{}' ({})", printable_excerpt(name), allowed));
}

std::vector<WheelsetTableMismatch> WheelsetTable::mismatches(const WheelsetOptions& options) const {
  // Doubles to 1e-9 relative: the same value given in other units (0.2 mm and 0.2e-3 m) may differ
  // in the last bits; a file keeps 17 digits, so a table's own values compare equal.
  const auto same = [](double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(std::abs(a), std::abs(b)); };
  std::vector<WheelsetTableMismatch> found;
  const auto add = [&](WheelsetTableSetting setting, std::string requested, std::string table) {
    found.push_back({setting, std::move(requested), std::move(table)});
  };
  const auto material = [](const Material& m) { return fmt::format("E = {:g} Pa, nu = {:g}", m.youngs_modulus_Pa, m.poisson_ratio); };
  if (!same(options.material.youngs_modulus_Pa, material_.youngs_modulus_Pa) ||
      !same(options.material.poisson_ratio, material_.poisson_ratio))
    add(WheelsetTableSetting::material, material(options.material), material(material_));
  if (!same(options.element_size_m, metadata_.element_size_m))
    add(WheelsetTableSetting::element_size, fmt::format("{:g} mm", options.element_size_m * 1e3),
        fmt::format("{:g} mm", metadata_.element_size_m * 1e3));
  const NhFastSimOptions& nh = options.nh_fastsim;
  const auto coarsening = [](int f) { return f == 0 ? std::string("0 (automatic)") : std::to_string(f); };
  if (nh.flexibility_coarsening != metadata_.flexibility_coarsening)
    add(WheelsetTableSetting::flexibility_coarsening, coarsening(nh.flexibility_coarsening),
        coarsening(metadata_.flexibility_coarsening));
  if (!same(nh.collocation_offset, metadata_.collocation_offset))
    add(WheelsetTableSetting::collocation_offset, fmt::format("{:g}", nh.collocation_offset),
        fmt::format("{:g}", metadata_.collocation_offset));
  if (nh.bound.slip_direction != bound_.slip_direction)
    add(WheelsetTableSetting::slip_direction, slip_direction_name(nh.bound.slip_direction),
        slip_direction_name(bound_.slip_direction));
  if (!same(nh.bound.skew, bound_.skew))
    add(WheelsetTableSetting::traction_bound_skew, fmt::format("{:g}", nh.bound.skew), fmt::format("{:g}", bound_.skew));
  if (metadata_.nh_fastsim_recipe != nh_fastsim_recipe(nh.creepage_coupling))
    add(WheelsetTableSetting::nh_fastsim_recipe, std::to_string(nh_fastsim_recipe(nh.creepage_coupling)),
        metadata_.nh_fastsim_recipe == 0 ? std::string("1 or 2, not recorded") : std::to_string(metadata_.nh_fastsim_recipe));
  if (options.search.weighting != metadata_.reference_weighting || !metadata_.creepage_on_wheel_surface) {
    const auto definition = [](ReferenceWeighting w, bool wheel_surface) {
      return fmt::format("{} reference point, creepages on the {}", reference_weighting_name(w),
                         wheel_surface ? "undeformed wheel surface over V_ref" : "rail surface over V (format 4 or older)");
    };
    add(WheelsetTableSetting::contact_definition, definition(options.search.weighting, true),
        definition(metadata_.reference_weighting, metadata_.creepage_on_wheel_surface));
  }
  const auto surface = [](ContactSurface kind, const ContactSurfaceSwitch& band) {
    if (kind != ContactSurface::automatic) return std::string(contact_surface_name(kind));
    return fmt::format("auto (conformal from {:g} to {:g})", band.planar_up_to, band.conformal_from);
  };
  const ContactSurfaceSwitch& a = options.contact_surface_switch;
  const ContactSurfaceSwitch& b = metadata_.contact_surface_switch;
  if (options.contact_surface != metadata_.contact_surface ||
      (options.contact_surface == ContactSurface::automatic &&
       (!same(a.planar_up_to, b.planar_up_to) || !same(a.conformal_from, b.conformal_from))))
    add(WheelsetTableSetting::contact_surface, surface(options.contact_surface, a),
        surface(metadata_.contact_surface, b));
  const auto coupling = [](const PatchCouplingOptions& c) {
    if (c.end_distance_m <= 0.0) return std::string("none");
    return fmt::format("full up to {:g} mm apart, none from {:g} mm", c.full_distance_m * 1e3, c.end_distance_m * 1e3);
  };
  const PatchCouplingOptions& pc = options.patch_coupling;
  const PatchCouplingOptions& tc = metadata_.patch_coupling;
  if (!same(pc.full_distance_m, tc.full_distance_m) || !same(pc.end_distance_m, tc.end_distance_m))
    add(WheelsetTableSetting::patch_coupling, coupling(pc), coupling(tc));
  return found;
}

struct WheelsetTable::LookupCache {
  PatchResults patches;
};

WheelsetResult WheelsetTable::evaluate(const WheelsetState& state, const WheelLoads& loads,
                                       double friction_coefficient, bool tangential_forces_in_vertical_balance) const {
  // The state is the same at every table load the balance tries: each node's patches are solved
  // once (FastSim on their coarse copies) and only weighted anew.
  LookupCache cache;
  WheelsetResult r = evaluate_at_table_loads(state, loads, friction_coefficient, cache);
  if (!tangential_forces_in_vertical_balance) return r;
  // Within one cell of the load grid a wheel's vertical force is linear in the table load (the
  // nodes' forces, tangential ones included, are interpolated linearly): the first step assumes it
  // proportional, L' = L Fz_wanted / Fz, the next ones are secants through the last two lookups,
  // which meet the load to 1e-6 (Wheelset's load tolerance) in one or two steps per cell crossed.
  // The wheels are independent. A table load the balance needs outside the grid is refused: the
  // lookup at the grid's edge would carry another load.
  const std::array<double, 2> wanted{loads.right_N, loads.left_N};
  std::array<double, 2> table_load = wanted, previous_load{}, previous_Fz{};
  const double lowest = grid_.wheel_load_N.front(), highest = grid_.wheel_load_N.back();
  constexpr int kIterations = 8;
  for (int iteration = 0; iteration <= kIterations; ++iteration) {
    bool met = true;
    for (std::size_t w = 0; w < 2; ++w) {
      const double Fz = r.wheels[w].force_track_N[2];
      if (std::abs(Fz - wanted[w]) <= 1e-6 * wanted[w]) continue;
      met = false;
      const char* side = side_name(w == 0 ? WheelSide::right : WheelSide::left);
      if (iteration == kIterations || !(Fz > 0.0))
        throw Error(ErrorKind::not_converged,
                    fmt::format("wheelset table: the {} wheel's vertical force with its tangential forces, {:.6g} kN, does "
                                "not meet its load {:.6g} kN after {} lookups (table load {:.6g} kN)",
                                side, Fz / 1e3, wanted[w] / 1e3, iteration + 1, table_load[w] / 1e3));
      double next = table_load[w] * wanted[w] / Fz;
      if (iteration > 0 && Fz != previous_Fz[w])
        next = table_load[w] + (wanted[w] - Fz) * (table_load[w] - previous_load[w]) / (Fz - previous_Fz[w]);
      const bool at_edge = table_load[w] == (next < lowest ? lowest : highest);
      if ((next < lowest || next > highest) && at_edge)
        throw Error(fmt::format(
            "wheelset table: the {} wheel's load {:.6g} kN, with its tangential forces in the vertical balance, needs a "
            "table load {}beyond the table's loads [{:.6g}, {:.6g}] kN (at {:.6g} kN its vertical force is {:.6g} kN): "
            "build the table with a {}, or look up with the frictionless balance (tangential forces left out; "
            "--frictionless-balance on the command line)",
            side, wanted[w] / 1e3,
            // The extrapolation from the grid's last cell, named only where it is a load at all.
            std::isfinite(next) && next > 0.0 ? fmt::format("of about {:.4g} kN (extrapolated), ", next / 1e3) : "",
            lowest / 1e3, highest / 1e3, table_load[w] / 1e3, Fz / 1e3,
            lowest == highest ? "load grid around the load (it has one load)" : "wider load grid"));
      previous_load[w] = table_load[w];
      previous_Fz[w] = Fz;
      table_load[w] = std::clamp(next, lowest, highest);
    }
    if (met) break;
    r = evaluate_at_table_loads(state, WheelLoads{table_load[0], table_load[1], loads.balance_roll},
                                friction_coefficient, cache);
  }
  return r;
}

WheelsetResult WheelsetTable::evaluate_at_table_loads(const WheelsetState& state, const WheelLoads& loads,
                                                      double friction_coefficient, LookupCache& cache) const {
  if (nodes_.empty()) throw Error("wheelset table: the table is empty");
  check_lookup_state(state, friction_coefficient);
  const WheelsetMotion motion = wheelset_motion(state, nominal_rolling_radius_m_);
  const WheelsetKinematics kinematics(motion);
  const WheelsetPosition& position = state.position;
  const Bracket by = bracket(grid_.y_m, position.lateral_displacement_m, "the lateral displacement y", "mm", kMm);
  // One yaw node serves every yaw (the contact point turned); several are interpolated.
  const Bracket byaw = grid_.yaw_rad.size() == 1 ? Bracket{}
                                                 : bracket(grid_.yaw_rad, position.yaw_rad, "the yaw", "mrad", 1e-3);
  WheelsetResult result;
  result.state = state;
  for (int w = 0; w < 2; ++w) {
    const WheelSide side = w == 0 ? WheelSide::right : WheelSide::left;
    const double load = w == 0 ? loads.right_N : loads.left_N;
    if (!(load > 0.0 && std::isfinite(load)))
      throw Error(fmt::format("wheelset table: the {} wheel's load {} N must be positive and finite", side_name(side), load));
    const Bracket bl =
        bracket(grid_.wheel_load_N, load, fmt::format("the {} wheel's load", side_name(side)).c_str(), "kN", 1e3);
    const Lookup lookup{{by, byaw, bl, position.yaw_rad}, motion, kinematics, friction_coefficient};
    result.wheels[w] = evaluate_wheel(side, lookup, grid_, nodes_, runtime_, cache.patches);
  }
  detail::sum_wheelset_forces(result, 1);
  return result;
}

}  // namespace railcontact
