// The wheelset evaluated as a whole (docs/WHEELSET.md §5–7): per wheel, the contact search, one
// normal problem per patch (by position, or by load through the wheel's height), the kinematic
// creepages at each patch's reference point, the tangential solvers, and the forces in the track
// frame.
#include <Eigen/Core>
#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geometry/wheel_locus.hpp"
#include "normal/known_product.hpp"
#include "railcontact/error.hpp"
#include "railcontact/normal.hpp"
#include "railcontact/wheelset.hpp"
#include "support/smoothstep.hpp"
#include "wheel_rail/conformal_patch.hpp"
#include "wheel_rail/contact_window.hpp"
#include "wheel_rail/patch_coupling.hpp"
#include "wheel_rail/patch_tangential_model.hpp"
#include "wheel_rail/stage_clock.hpp"
#include "wheel_rail/wheelset_assembly.hpp"
#include "tangential/cropped_patch.hpp"
#include "wheel_rail/wheel_height.hpp"

namespace railcontact {

namespace {

constexpr double kMm = 1e-3;
constexpr int kMaximumLoadIterations = 40;
// The deepest overlap of the undeformed wheel and rail a patch may have (see solve_normal).
constexpr double kMaximumOverlap_m = detail::kMaximumWheelOverlap_m;
constexpr int kMaximumBalanceIterations = 16;
// Both wheels' heights agree to this when the roll is balanced (one rigid axle).
constexpr double kHeightTolerance_m = 1e-8;
// The tangential forces' vertical components settle to this fraction of the load, or, after
// kStrictBalancePasses passes, to the coarser one: they settle only to the discretisation level of
// the tangential solution, and an element entering the patch as the wheel's height changes by
// 0.04 µm moves them by 65 N in flange contact at 0.5 mm elements (0.07 % of the load).
constexpr double kTangentialBalanceTolerance = 1e-5;
constexpr double kCoarseTangentialBalanceTolerance = 1e-3;
constexpr int kStrictBalancePasses = 6;
constexpr double kBracketTolerance = 1e-5;
using detail::kMinimumElementsForK2;

// The distance of a point (from the wheelset centre) from the axle.
double distance_from_axle_m(const Vector3& q, const WheelsetMotion& motion) {
  const Vector3 a = axle_direction(motion.roll_rad, motion.yaw_rad);
  const double along = q[0] * a[0] + q[1] * a[1] + q[2] * a[2];
  const Vector3 radial{q[0] - along * a[0], q[1] - along * a[1], q[2] - along * a[2]};
  return std::sqrt(radial[0] * radial[0] + radial[1] * radial[1] + radial[2] * radial[2]);
}

Vector3 combine(const InterpenetrationRegion& r, double F1, double F2, double F3) {
  Vector3 f{};
  for (int i = 0; i < 3; ++i) f[static_cast<std::size_t>(i)] = F1 * r.x1_axis[i] + F2 * r.x2_axis[i] + F3 * r.x3_axis[i];
  return f;
}

// The index in options.solvers of the solver whose forces the load balance and free rolling use.
std::size_t balance_index(const WheelsetOptions& options) {
  if (!options.balance_solver) return 0;
  const auto it = std::find(options.solvers.begin(), options.solvers.end(), *options.balance_solver);
  return static_cast<std::size_t>(it - options.solvers.begin());
}

// A normal solve's pressure and its product u = A p on the mesh it was solved on (a contact window
// or the whole area): the next time step's start takes its product from these (known_product.hpp).
struct SolvedMesh {
  Mesh mesh;
  std::vector<double> pressure_Pa, displacement_m;
};

// A patch's normal problem on one contact surface at a position.
struct SurfaceSolution {
  TangentPlaneArea area;                 // planar, or conformal (with its strips)
  NormalSolution normal;                 // on area.mesh
  std::size_t solved_mesh_elements = 0;  // of the mesh solved on: a contact window or area.mesh
  // Solved on a window: the whole-area check that proved it (made now, or an earlier one the
  // bound held against), for the next step's window (contact_window.hpp).
  std::shared_ptr<const detail::WholeAreaCheck> check;
  std::shared_ptr<const SolvedMesh> solved;  // the pressure and its product as solved
};

// One patch's normal problem: on the surface the options choose, and, where the automatic surface
// blends the two (0 < conformal_weight < 1), also on the planar one.
struct NormalPatch : SurfaceSolution {
  InterpenetrationRegion region;
  double conformal_weight = 0.0;  // conformal_surface_weight; this is the conformal surface when > 0
  std::optional<SurfaceSolution> planar;  // the planar surface to blend with
  double coupling_lift_m = 0.0;  // WheelsetPatch::coupling_lift_m
};

// The pressure's resultant on the wheel, track frame (WheelsetPatch::pressure_force_track_N).
Vector3 pressure_force_track_N(const InterpenetrationRegion& region, const SurfaceSolution& p) {
  if (!p.area.strips.empty()) return detail::conformal_pressure_force_track_N(region, p.area, p.normal.pressure_Pa);
  return combine(region, 0.0, 0.0, p.normal.normal_force_N);
}

// The same for a patch, blended where it is.
Vector3 pressure_force_track_N(const NormalPatch& p) {
  Vector3 f = pressure_force_track_N(p.region, p);
  if (p.planar) {
    const Vector3 g = pressure_force_track_N(p.region, *p.planar);
    for (std::size_t i = 0; i < 3; ++i) f[i] = p.conformal_weight * f[i] + (1.0 - p.conformal_weight) * g[i];
  }
  return f;
}

}  // namespace

namespace detail {

// The warm start of a Wheelset (docs/WHEELSET.md §8): normal-solver plans per mesh size, and each
// wheel's last patches (their meshes and pressures) to start the next solves from.
struct WheelsetWarmStart {
  static constexpr std::size_t kMaximumPlans = 12;
  struct Plan {
    int n1, n2;
    std::uint64_t last_use;
    NormalContactSolver solver;
  };
  // A patch's solution, the position it was solved at and the evaluation it was solved in;
  // `older` the same patch's last solution in an earlier evaluation (the step before, for the
  // linear prediction of initial_pressure; by load the heights' iterates of one evaluation do not
  // count as steps). The pressure is kept as solved (on its contact window, zero outside it, or on
  // the whole area), shared, not copied: a whole area's field is 110 kB at y = 0.
  struct Solved {
    WheelsetPosition position;
    std::uint64_t evaluation = 0;
    std::shared_ptr<const SolvedMesh> solved;  // as solved, with its product
    [[nodiscard]] const Mesh& mesh() const { return solved->mesh; }
  };
  struct Previous {
    double rail_profile_y_m;
    Solved last;
    std::optional<Solved> older;
    std::shared_ptr<const WholeAreaCheck> check;  // its window's last whole-area check
  };
  std::vector<Plan> plans;
  std::array<std::vector<Previous>, 2> previous;  // right, left
  std::array<WheelLocus, 2> locus;                // each wheel's last contact locus (right, left)
  std::optional<NormalInfluenceBound> influence;  // for the windows' bound, made at the first
  std::uint64_t clock = 0;
  std::uint64_t evaluation = 0;  // counts Wheelset::evaluate_rolling calls
  StageClock* stage_clock = nullptr;  // the running evaluation's, when its stages are timed
  // By load: each wheel's last overlap below its first touch, its contact stiffness dF/dδ and the
  // tangential forces' vertical part its last balance settled on, the first guesses of the next
  // evaluation's height iteration and balance when that evaluation is a time step away
  // (near_last_position; docs/WHEELSET.md §8). Zero stiffness: none.
  std::array<double, 2> overlap_m{0.0, 0.0};
  std::array<double, 2> stiffness_N_per_m{0.0, 0.0};
  std::array<double, 2> tangential_vertical_N{0.0, 0.0};
  double roll_rad = 0.0;  // the roll the last balance settled on (WheelLoads::balance_roll)
  std::optional<WheelsetPosition> last_position;
  // The overlaps, tangential parts and roll of the time step before (at older_position), for
  // their linear prediction (predicted); none after a jump.
  std::array<double, 2> older_overlap_m{0.0, 0.0};
  std::array<double, 2> older_tangential_vertical_N{0.0, 0.0};
  double older_roll_rad = 0.0;
  std::optional<WheelsetPosition> older_position;

  // The first guesses of each wheel's overlap and tangential part, and of the balanced roll, at
  // `now`, a time step after the last evaluation by load: the last ones moved on along the last
  // step, x + r (x − x_older) with r as in initial_pressure (the overlap kept within a factor 2 of
  // the last). Along a 1 µm drift the overlap's guess carries the load to within the load
  // tolerance, so that most steps solve each wheel's normal problem once (docs/WHEELSET.md §8
  // "The prediction").
  struct HeightGuess {
    std::array<double, 2> overlap_m, tangential_vertical_N;
    double roll_rad;
  };
  [[nodiscard]] HeightGuess predicted(const WheelsetPosition& now) const {
    if (!older_position || !last_position) return {overlap_m, tangential_vertical_N, roll_rad};
    const double r = step_ratio(*older_position, *last_position, now);
    HeightGuess guess{};
    guess.roll_rad = roll_rad + r * (roll_rad - older_roll_rad);
    for (std::size_t k = 0; k < 2; ++k) {
      guess.overlap_m[k] = std::clamp(overlap_m[k] + r * (overlap_m[k] - older_overlap_m[k]), 0.5 * overlap_m[k],
                                      2.0 * overlap_m[k]);
      guess.tangential_vertical_N[k] =
          tangential_vertical_N[k] + r * (tangential_vertical_N[k] - older_tangential_vertical_N[k]);
    }
    return guess;
  }

  // A time step away from the last evaluation by load: within 0.1 mm laterally and 1 mrad of roll
  // and yaw. A jump starts the heights and the balance afresh, so that its numbers do not depend on
  // where it jumped from.
  [[nodiscard]] bool near_last_position(const WheelsetPosition& p) const {
    return last_position && std::abs(p.lateral_displacement_m - last_position->lateral_displacement_m) <= 0.1e-3 &&
           std::abs(p.roll_rad - last_position->roll_rad) <= 1e-3 &&
           std::abs(p.yaw_rad - last_position->yaw_rad) <= 1e-3;
  }

  // The contact locus of a wheel at `position`: the last one where only the height differs (the
  // height iteration's trials, wheel_locus.hpp), otherwise sampled anew, on demand: every
  // kLocusCoarseEvery-th sample first, the others where the wheel may overlap its rail
  // (refine_locus; docs/WHEELSET.md §8 "The locus on demand").
  static constexpr int kLocusCoarseEvery = 8;
  WheelLocus& locus_at(const WheelsetTrack& track, WheelSide side, const WheelsetPosition& position, double step_m) {
    WheelLocus& kept = locus[side == WheelSide::right ? 0 : 1];
    if (!kept.serves(side, position, step_m)) {
      WheelsetPosition at_nominal = position;
      at_nominal.vertical_displacement_m = 0.0;
      validate(at_nominal);
      kept = sample_wheel_locus(track, side, at_nominal, step_m, kLocusCoarseEvery);
    }
    return kept;
  }

  NormalContactSolver& plan(const Mesh& mesh, const WheelsetOptions& options) {
    ++clock;
    for (Plan& p : plans) {
      if (p.n1 == mesh.n1 && p.n2 == mesh.n2) {
        p.last_use = clock;
        return p.solver;
      }
    }
    if (plans.size() >= kMaximumPlans) {
      plans.erase(std::min_element(plans.begin(), plans.end(),
                                   [](const Plan& a, const Plan& b) { return a.last_use < b.last_use; }));
    }
    plans.push_back(Plan{mesh.n1, mesh.n2, clock, NormalContactSolver(mesh, options.material, options.normal)});
    return plans.back().solver;
  }

  // The earlier patch of this wheel nearest to rail_profile_y_m (within 2 mm along the rail).
  [[nodiscard]] const Previous* nearest(WheelSide side, double rail_profile_y_m) const {
    const Previous* best = nullptr;
    for (const Previous& p : previous[side == WheelSide::right ? 0 : 1]) {
      const double d = std::abs(p.rail_profile_y_m - rail_profile_y_m);
      if (d < 2e-3 && (!best || d < std::abs(best->rail_profile_y_m - rail_profile_y_m))) best = &p;
    }
    return best;
  }

  // The solutions a start combines (`last`, and `older` where r > 0), for its product
  // (predicted_product).
  struct StartSources {
    std::shared_ptr<const SolvedMesh> last, older;  // older only where r > 0
    double r = 0.0;
    // How the solve is preconditioned (set by solve_normal: a time step's prediction by position).
    StartKind kind = StartKind::given;
  };

  // The start of a patch's normal solve on `mesh`: the previous pressure of the nearest earlier
  // patch of this wheel, moved onto the new mesh element by element (both meshes have their element
  // centres at integer multiples of the element size from their reference points); empty when
  // there is none. With `at` given and the same patch solved in an earlier evaluation too, the
  // linear prediction p + r (p − p_older), r the new step's length along the last one's (in
  // [0, kLargestPredictionRatio]; 0 when the steps turn back), floored at zero: along a 1 µm drift
  // it halves the conjugate-gradient iterations (docs/WHEELSET.md §8 "The prediction"). With `from`
  // given, the solutions it combined are written there, for its product (predicted_product).
  std::vector<double> initial_pressure(WheelSide side, double rail_profile_y_m, const Mesh& mesh,
                                       const WheelsetPosition* at, StartSources* from = nullptr) const {
    const Previous* best = nearest(side, rail_profile_y_m);
    if (!best || best->last.mesh().dx1_m != mesh.dx1_m) return {};
    std::vector<double> p = moved_onto(*best->last.solved, mesh);
    if (from != nullptr) *from = {best->last.solved, nullptr, 0.0};
    if (at == nullptr || !best->older || best->older->mesh().dx1_m != mesh.dx1_m) return p;
    const double r = step_ratio(best->older->position, best->last.position, *at);
    if (r <= 0.0) return p;
    const std::vector<double> older = moved_onto(*best->older->solved, mesh);
    for (std::size_t k = 0; k < p.size(); ++k) p[k] = std::max(0.0, prediction(p[k], older[k], r));
    if (from != nullptr) *from = {best->last.solved, best->older->solved, r};
    return p;
  }
  // The linear prediction of one element's pressure (or product) from its last two solutions.
  static double prediction(double last, double older, double r) { return last + r * (last - older); }

  // A solution's pressure on another mesh of the same element size, zero where it did not reach.
  static std::vector<double> moved_onto(const SolvedMesh& from, const Mesh& mesh) {
    const int shift1 = static_cast<int>(std::lround((mesh.x1_first_m - from.mesh.x1_first_m) / mesh.dx1_m));
    const int shift2 = static_cast<int>(std::lround((mesh.x2_first_m - from.mesh.x2_first_m) / mesh.dx2_m));
    std::vector<double> p(mesh.size(), 0.0);
    // Row by row: the columns i1 in [lo1, hi1) lie on `from`'s mesh.
    const int lo1 = std::clamp(-shift1, 0, mesh.n1), hi1 = std::clamp(from.mesh.n1 - shift1, lo1, mesh.n1);
    for (int i2 = 0; i2 < mesh.n2; ++i2) {
      const int j2 = i2 + shift2;
      if (j2 < 0 || j2 >= from.mesh.n2 || lo1 == hi1) continue;
      const auto source = from.pressure_Pa.begin() + static_cast<std::ptrdiff_t>(from.mesh.index(lo1 + shift1, j2));
      std::copy(source, source + (hi1 - lo1), p.begin() + static_cast<std::ptrdiff_t>(mesh.index(lo1, i2)));
    }
    return p;
  }

  // The step from `last` to `now` projected on the step from `older` to `last`, as a multiple of
  // that step: positions as (y, z, roll, yaw) with the angles times kAngleLever_m (about a wheel's
  // distance from the wheelset centre). Clamped to [0, kLargestPredictionRatio]; 0 when the last step is
  // nil.
  static constexpr double kLargestPredictionRatio = 2.0;
  static constexpr double kAngleLever_m = 1.0;
  static double step_ratio(const WheelsetPosition& older, const WheelsetPosition& last, const WheelsetPosition& now) {
    const auto coordinates = [](const WheelsetPosition& p) {
      return std::array<double, 4>{p.lateral_displacement_m, p.vertical_displacement_m, p.roll_rad * kAngleLever_m,
                                   p.yaw_rad * kAngleLever_m};
    };
    const std::array<double, 4> a = coordinates(older), b = coordinates(last), c = coordinates(now);
    double along = 0.0, length2 = 0.0;
    for (std::size_t i = 0; i < 4; ++i) {
      along += (c[i] - b[i]) * (b[i] - a[i]);
      length2 += (b[i] - a[i]) * (b[i] - a[i]);
    }
    if (!(length2 > 0.0)) return 0.0;
    return std::clamp(along / length2, 0.0, kLargestPredictionRatio);
  }

  // A wheel's patches solved at `position`; each keeps, as its older solution, the nearest earlier
  // patch's last solution of an earlier evaluation.
  void remember(WheelSide side, const WheelsetPosition& position, const std::vector<NormalPatch>& patches) {
    std::vector<Previous> list;
    for (const NormalPatch& p : patches) {
      // A Solved reads its mesh and pressure from its solution (solve_surface always makes one); a
      // patch without one is not a start.
      if (!p.solved) continue;
      Previous n{p.region.rail_profile_y_m, Solved{position, evaluation, p.solved},
                 std::nullopt, p.check};
      if (const Previous* earlier = nearest(side, p.region.rail_profile_y_m))
        n.older = earlier->last.evaluation == evaluation ? earlier->older : std::optional<Solved>(earlier->last);
      list.push_back(std::move(n));
    }
    previous[side == WheelSide::right ? 0 : 1] = std::move(list);
  }
};

}  // namespace detail

namespace {

// The normal problem of a time step on the window of the previous contact (docs/WHEELSET.md §8,
// wheel_rail/contact_window.hpp): the previous contact's bounding box widened by 3 elements and to
// whole multiples of 4, used where its padded FFT grid is at most 75 % of the potential area's. The window's
// solution is the whole area's solution when its contact stays off the window's inner edges and
// its complementarity residual on the whole area (one product there: no overlap left outside the
// window) is within 10 times the solver's tolerance; otherwise nothing is returned and the whole
// area is solved. The two solutions agree to the solver's tolerance (test
// Wheelset/WindowedTimeStep.GivesTheWholeAreasSolution).
struct WindowedSolution {
  NormalSolution normal;  // on the whole area's mesh
  std::size_t window_elements = 0;
  std::shared_ptr<const detail::WholeAreaCheck> check;  // the check that proved it
  std::shared_ptr<const SolvedMesh> solved;     // on the window
};

// The start's prediction q = p + r (p − p_older) on `mesh` (before its floor at zero: the linear
// combination) and its product, the same combination of the two solutions' products, both moved
// onto `mesh` by whole elements as the pressures are (docs/WHEELSET.md §8 "The start's product").
// Nothing when a product does not cover the mesh, the element sizes differ, or a solution's pressure
// reaches beyond the mesh (its part there would be in the product but not in the start).
std::optional<detail::KnownProduct> predicted_product(const detail::WheelsetWarmStart::StartSources& from,
                                                      const Mesh& mesh) {
  if (!from.last || (from.r > 0.0 && !from.older)) return std::nullopt;
  detail::KnownProduct known{std::vector<double>(mesh.size()), std::vector<double>(mesh.size())};
  std::vector<double> older_pressure, older_displacement;
  const auto move = [&](const SolvedMesh& solved, std::vector<double>& pressure,
                        std::vector<double>& displacement) {
    const Mesh& m = solved.mesh;
    if (m.dx1_m != mesh.dx1_m || m.dx2_m != mesh.dx2_m) return false;
    const int shift1 = static_cast<int>(std::lround((mesh.x1_first_m - m.x1_first_m) / mesh.dx1_m));
    const int shift2 = static_cast<int>(std::lround((mesh.x2_first_m - m.x2_first_m) / mesh.dx2_m));
    if (shift1 < 0 || shift2 < 0 || shift1 + mesh.n1 > m.n1 || shift2 + mesh.n2 > m.n2) return false;
    // No pressure left behind: zero on the rows and columns that do not reach `mesh`.
    const auto zero = [](auto first, auto last) { return std::all_of(first, last, [](double p) { return p == 0.0; }); };
    for (int j2 = 0; j2 < m.n2; ++j2) {
      const auto row = solved.pressure_Pa.begin() + static_cast<std::ptrdiff_t>(m.index(0, j2));
      const bool on = j2 >= shift2 && j2 < shift2 + mesh.n2;
      if (!on) {
        if (!zero(row, row + m.n1)) return false;
        continue;
      }
      if (!zero(row, row + shift1) || !zero(row + shift1 + mesh.n1, row + m.n1)) return false;
      const auto at = static_cast<std::ptrdiff_t>(mesh.index(0, j2 - shift2));
      std::copy(row + shift1, row + shift1 + mesh.n1, pressure.begin() + at);
      const auto u = solved.displacement_m.begin() + static_cast<std::ptrdiff_t>(m.index(shift1, j2));
      std::copy(u, u + mesh.n1, displacement.begin() + at);
    }
    return true;
  };
  if (!move(*from.last, known.pressure_Pa, known.displacement_m)) return std::nullopt;
  if (from.r > 0.0) {
    older_pressure.resize(mesh.size());
    older_displacement.resize(mesh.size());
    if (!move(*from.older, older_pressure, older_displacement)) return std::nullopt;
    for (std::size_t k = 0; k < mesh.size(); ++k) {
      known.pressure_Pa[k] = detail::WheelsetWarmStart::prediction(known.pressure_Pa[k], older_pressure[k], from.r);
      known.displacement_m[k] =
          detail::WheelsetWarmStart::prediction(known.displacement_m[k], older_displacement[k], from.r);
    }
  }
  return known;
}

std::optional<WindowedSolution> solve_in_contact_window(const TangentPlaneArea& area, const std::vector<double>& initial,
                                                        const detail::WheelsetWarmStart::StartSources& from,
                                                        const std::shared_ptr<const detail::WholeAreaCheck>& earlier,
                                                        const WheelsetOptions& options,
                                                        detail::WheelsetWarmStart& warm) {
  constexpr int kWindowMargin = 3;
  constexpr int kWindowGranule = 4;
  constexpr double kLargestWindowFraction = 0.75;
  if (initial.empty()) return std::nullopt;
  const std::optional<detail::MeshWindow> window =
      detail::contact_window(area.mesh, initial, kWindowMargin, kWindowGranule, kLargestWindowFraction);
  if (!window) return std::nullopt;
  const Mesh mesh = detail::window_mesh(area.mesh, *window);
  NormalSolution s;
  auto solved = std::make_shared<SolvedMesh>();
  try {
    const std::optional<detail::KnownProduct> known = predicted_product(from, mesh);
    s = detail::NormalSolverAccess::solve_at_approach(
        warm.plan(mesh, options), detail::cut_window(area.mesh, area.h_m, *window), 0.0,
        detail::cut_window(area.mesh, initial, *window), known ? &*known : nullptr, &solved->displacement_m,
        from.kind);
  } catch (const Error& e) {
    if (e.kind() != ErrorKind::not_converged) throw;
    return std::nullopt;  // a breakdown on the window: the whole area decides
  }
  if (!s.converged || s.elements_in_contact == 0 ||
      detail::contact_on_inner_window_edge(area.mesh, *window, s.pressure_Pa))
    return std::nullopt;
  solved->mesh = mesh;
  solved->pressure_Pa = s.pressure_Pa;
  std::vector<double> pressure = detail::paste_window(area.mesh, s.pressure_Pa, *window);
  // The check on the whole area: by the bound from the patch's earlier check where it proves no
  // overlap outside the window (the half-space's A33, on the tangent plane or on a conformal area's
  // developed mesh alike), which leaves the whole-area residual the window's; otherwise one product
  // there, kept as the next steps' earlier check.
  std::shared_ptr<const detail::WholeAreaCheck> check;
  if (earlier) {
    if (!warm.influence || !warm.influence->fits(area.mesh.dx1_m, area.mesh.dx2_m, options.material))
      warm.influence.emplace(area.mesh.dx1_m, area.mesh.dx2_m, options.material);
    if (detail::window_solution_holds_outside(area.mesh, area.h_m, *window, pressure, *earlier, *warm.influence))
      check = earlier;
  }
  if (!check) {
    auto made = std::make_shared<detail::WholeAreaCheck>();
    const double residual =
        warm.plan(area.mesh, options).complementarity_residual(area.h_m, 0.0, pressure, &made->displacement_m);
    if (!(residual <= 10.0 * options.normal.tolerance)) return std::nullopt;
    made->mesh = area.mesh;
    made->pressure_Pa = pressure;
    made->support = detail::pressure_support(area.mesh, pressure);
    s.residual = residual;
    check = std::move(made);
  }
  s.pressure_Pa = std::move(pressure);
  // Loaded elements on the area's border: its first and last rows and columns.
  const Mesh& m = area.mesh;
  const auto loaded = [&](int i1, int i2) { return s.pressure_Pa[m.index(i1, i2)] > 0.0; };
  s.touches_border = false;
  for (int i1 = 0; i1 < m.n1 && !s.touches_border; ++i1) s.touches_border = loaded(i1, 0) || loaded(i1, m.n2 - 1);
  for (int i2 = 0; i2 < m.n2 && !s.touches_border; ++i2) s.touches_border = loaded(0, i2) || loaded(m.n1 - 1, i2);
  return WindowedSolution{std::move(s), mesh.size(), std::move(check), std::move(solved)};
}

// The normal problem of a region on one contact surface's area. h is measured at this position
// (negative where the bodies overlap): the approach is zero; where `lift_m` is given (the other
// patches' elastic coupling, solve_coupled) h + lift is solved, and the area keeps its geometric h.
// With a start (`initial`: in a time step the last pressure, predicted) first on its window (with
// the `earlier` check's bound); else (or if the check fails) on the whole potential area.
struct SurfaceStart {
  std::vector<double> initial;
  std::shared_ptr<const detail::WholeAreaCheck> earlier;
  detail::WheelsetWarmStart::StartSources from;  // the solutions `initial` combines
};
SurfaceSolution solve_surface(TangentPlaneArea area, const std::vector<double>& lift_m, WheelSide side,
                              const InterpenetrationRegion& region, const WheelsetOptions& options,
                              detail::WheelsetWarmStart& warm, const SurfaceStart& start) {
  SurfaceSolution p;
  p.area = std::move(area);
  std::vector<double> geometric_h;
  if (!lift_m.empty()) {
    geometric_h = p.area.h_m;
    for (std::size_t e = 0; e < lift_m.size(); ++e) p.area.h_m[e] += lift_m[e];
  }
  std::optional<WindowedSolution> windowed =
      solve_in_contact_window(p.area, start.initial, start.from, start.earlier, options, warm);
  if (windowed) {
    p.normal = std::move(windowed->normal);
    p.check = std::move(windowed->check);
    p.solved = std::move(windowed->solved);
  } else {
    auto solved = std::make_shared<SolvedMesh>();
    p.normal = detail::NormalSolverAccess::solve_at_approach(warm.plan(p.area.mesh, options), p.area.h_m, 0.0,
                                                             start.initial, nullptr, &solved->displacement_m,
                                                             start.from.kind);
    solved->mesh = p.area.mesh;
    solved->pressure_Pa = p.normal.pressure_Pa;
    p.solved = std::move(solved);
  }
  p.solved_mesh_elements = windowed ? windowed->window_elements : p.area.mesh.size();
  if (!lift_m.empty()) p.area.h_m = std::move(geometric_h);
  if (!p.normal.converged) {
    throw Error(ErrorKind::not_converged,
                fmt::format("wheelset: the normal problem of the {} wheel's patch at y_p = {:.2f} mm did not "
                            "converge in {} iterations (residual {:.2g})",
                            side_name(side), region.rail_profile_y_m / kMm, p.normal.iterations, p.normal.residual));
  }
  return p;
}

// The weights of the elastic coupling between a wheel's patches (n × n, patch_coupling_weight of
// their overlaps' distance); empty when no two are coupled.
std::vector<double> coupling_weights(const WheelContactSearch& search, const std::vector<NormalPatch>& patches,
                                     const PatchCouplingOptions& options) {
  const std::size_t n = patches.size();
  if (n < 2 || options.end_distance_m <= 0.0) return {};
  std::vector<double> weight(n * n, 0.0);
  bool coupled = false;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const double w = detail::patch_coupling_weight(
          detail::overlap_distance_m(search, patches[i].region, patches[j].region), options);
      weight[i * n + j] = weight[j * n + i] = w;
      coupled = coupled || w > 0.0;
    }
  return coupled ? weight : std::vector<double>{};
}

// The normal problems of a wheel's coupled patches (docs/WHEELSET.md §5 "Coupled patches"):
// Gauss–Seidel sweeps over the patches, each solved with its h raised by the displacement the
// others' latest pressures impose (patch_coupling.hpp; before a patch's first solve its start, in a
// time step the last step's coupled pressure), from its own last pressure, until no patch's normal
// force moves by more than the normal solver's tolerance (its own precision: 5e-6 in a wheelset) of
// the wheel's. A patch blending two surfaces has both lifted by the others' primary surfaces.
constexpr int kMaximumCouplingSweeps = 20;
void solve_coupled(const std::vector<double>& weight, WheelSide side, const WheelsetPosition& position,
                   std::vector<NormalPatch>& patches, const std::vector<SurfaceStart>& starts,
                   const WheelsetOptions& options, detail::WheelsetWarmStart& warm) {
  const std::size_t n = patches.size();
  std::vector<detail::SurfacePoints> points(n), planar_points(n);
  for (std::size_t i = 0; i < n; ++i) {
    points[i] = detail::surface_points(patches[i].region, patches[i].area);
    if (patches[i].planar) planar_points[i] = detail::surface_points(patches[i].region, patches[i].planar->area);
  }
  // The displacement the others' pressures (solved, or their starts) impose on patch i's surface.
  const auto lift = [&](std::size_t i, const TangentPlaneArea& area, const detail::SurfacePoints& target,
                        bool solved) {
    std::vector<double> u(area.h_m.size(), 0.0);
    for (std::size_t j = 0; j < n; ++j) {
      if (j == i || weight[i * n + j] <= 0.0) continue;
      const bool j_solved = solved || j < i;
      const std::vector<double>& pressure = j_solved ? patches[j].normal.pressure_Pa : starts[j].initial;
      if (pressure.empty()) continue;
      detail::add_coupling_displacement(detail::pressure_blocks(patches[j].area, points[j], pressure), target,
                                        weight[i * n + j], options.material, area.h_m, u);
    }
    return u;
  };
  std::vector<double> force(n, 0.0);
  for (int sweep = 0;; ++sweep) {
    double change = 0.0, total = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      NormalPatch& p = patches[i];
      const std::vector<double> u = lift(i, p.area, points[i], sweep > 0);
      p.coupling_lift_m = 0.0;
      for (std::size_t e = 0; e < u.size(); ++e)
        if (p.area.h_m[e] < 0.0) p.coupling_lift_m = std::max(p.coupling_lift_m, u[e]);
      const SurfaceStart start =
          sweep == 0 ? starts[i] : SurfaceStart{p.normal.pressure_Pa, p.check, {p.solved, nullptr, 0.0}};
      static_cast<SurfaceSolution&>(p) = solve_surface(std::move(p.area), u, side, p.region, options, warm, start);
      if (p.planar) {
        const std::vector<double> v = lift(i, p.planar->area, planar_points[i], sweep > 0);
        const SurfaceStart planar_start =
            sweep == 0 ? SurfaceStart{}
                       : SurfaceStart{p.planar->normal.pressure_Pa, p.planar->check, {p.planar->solved, nullptr, 0.0}};
        p.planar = solve_surface(std::move(p.planar->area), v, side, p.region, options, warm, planar_start);
      }
      change = std::max(change, std::abs(p.normal.normal_force_N - force[i]));
      force[i] = p.normal.normal_force_N;
      total += force[i];
    }
    if (sweep > 0 && change <= options.normal.tolerance * total) return;
    if (sweep == kMaximumCouplingSweeps) {
      throw Error(ErrorKind::not_converged,
                  fmt::format("wheelset: the elastic coupling of the {} wheel's {} patches at y = {:.3f} mm, z = "
                              "{:.4f} mm did not settle in {} sweeps (last change {:.3g} N of {:.6g} N)",
                              side_name(side), n, position.lateral_displacement_m / kMm,
                              position.vertical_displacement_m / kMm, kMaximumCouplingSweeps, change, total));
    }
  }
}

// Each patch starts from the linear prediction of its last solutions (initial_pressure).
std::vector<NormalPatch> solve_normal(const WheelsetTrack& track, WheelSide side, const WheelsetPosition& position,
                                      const WheelsetOptions& options, detail::WheelsetWarmStart& warm) {
  validate(position);
  std::optional<detail::StageClock::Scope> stage(std::in_place, warm.stage_clock, detail::WheelsetStage::search);
  const WheelContactSearch search = detail::contact_search(
      track, warm.locus_at(track, side, position, options.search.locus_step_m), position, options.search);
  stage.emplace(warm.stage_clock, detail::WheelsetStage::area);
  std::vector<NormalPatch> patches;
  for (const InterpenetrationRegion& region : search.regions) {
    // Bodies pressed this far into each other carry more than the largest normal force accepted
    // (kMaximumNormalForce_N, 1e7 N: about 2 mm on S1002/UIC60), and the normal solver cannot
    // resolve it: a position like this is a wrong input (a vertical position in the wrong unit or
    // frame), refused before any mesh is built.
    require(region.max_interpenetration_m <= kMaximumOverlap_m, [&] {
      return fmt::format("wheelset: the {} wheel overlaps its rail by {:.3f} mm at y = {:.3f} mm, z = {:.3f} mm; at "
                         "most {:g} mm is accepted (about 1e7 N, the largest normal force): check the vertical "
                         "position z (mm above the nominal height, not the axle height)",
                         side_name(side), region.max_interpenetration_m / kMm, position.lateral_displacement_m / kMm,
                         position.vertical_displacement_m / kMm, kMaximumOverlap_m / kMm);
    });
    NormalPatch p;
    p.region = region;
    p.conformal_weight = conformal_surface_weight(options.contact_surface, options.contact_surface_switch, region);
    const bool conformal = p.conformal_weight > 0.0;
    p.area = conformal ? track.conformal_contact_area(position, region, options.element_size_m)
                       : track.potential_contact_area(position, region, options.element_size_m);
    if (conformal && p.conformal_weight < 1.0) {
      p.planar.emplace();
      p.planar->area = track.potential_contact_area(position, region, options.element_size_m);
    }
    patches.push_back(std::move(p));
  }
  // Each patch's primary surface starts from the prediction of its last solutions; a blend's planar
  // surface afresh.
  stage.emplace(warm.stage_clock, detail::WheelsetStage::normal);
  std::vector<SurfaceStart> starts;
  for (const NormalPatch& p : patches) {
    const detail::WheelsetWarmStart::Previous* earlier = warm.nearest(side, p.region.rail_profile_y_m);
    SurfaceStart start;
    start.initial = warm.initial_pressure(side, p.region.rail_profile_y_m, p.area.mesh, &position, &start.from);
    // By position a patch is solved once per evaluation, from the last steps' pressures: the time
    // step's preconditioner. By load every solve keeps the default one: the height iteration's
    // secants between its trials need the trials' errors alike (with the time step's on the first
    // trial only, a balanced step took 3-11 % more normal solves, docs/NORMAL.md "Preconditioner").
    if (!options.loads && !start.initial.empty()) start.from.kind = detail::StartKind::time_step_prediction;
    start.earlier = earlier ? earlier->check : nullptr;
    starts.push_back(std::move(start));
  }
  const std::vector<double> weight = coupling_weights(search, patches, options.patch_coupling);
  if (!weight.empty()) {
    solve_coupled(weight, side, position, patches, starts, options, warm);
  } else {
    for (std::size_t i = 0; i < patches.size(); ++i) {
      NormalPatch& p = patches[i];
      static_cast<SurfaceSolution&>(p) = solve_surface(std::move(p.area), {}, side, p.region, options, warm, starts[i]);
      if (p.planar) p.planar = solve_surface(std::move(p.planar->area), {}, side, p.region, options, warm, {});
    }
  }
  warm.remember(side, position, patches);
  return patches;
}

// Tangential solve of one patch with one solver (creepages at the patch's own origin, the centre
// of pressure): the tractions when the options keep them.
PatchSolverResult solve_tangential(TangentialSolver solver, const ContactPatch& patch, const Creepage& creepage,
                                   const WheelsetOptions& options) {
  const TangentialModel model = detail::patch_tangential_model(solver, patch, options);
  TangentialSolution t = model.solve(creepage, options.friction_coefficient,
                                     options.keep_tractions ? TangentialOutput::fields : TangentialOutput::forces);
  PatchSolverResult r;
  r.solver = solver;
  r.forces = t.forces;
  r.flexibility = model.flexibility().value_or(Flexibility{0.0, 0.0, 0.0});
  r.coupling = model.coupling();
  r.adhesion_fraction = t.adhesion_fraction;
  if (options.keep_tractions) {
    r.p1_Pa = std::move(t.p1_Pa);
    r.p2_Pa = std::move(t.p2_Pa);
    r.slip = std::move(t.slip);
  }
  return r;
}

}  // namespace

WheelsetMotion wheelset_motion(const WheelsetState& state, double nominal_radius_m) {
  const WheelsetVelocity& v = state.velocity;
  WheelsetMotion m;
  m.forward_speed_m_per_s = v.forward_speed_m_per_s;
  m.lateral_velocity_m_per_s = v.lateral_velocity_m_per_s;
  m.vertical_velocity_m_per_s = v.vertical_velocity_m_per_s;
  m.roll_rad = state.position.roll_rad;
  m.yaw_rad = state.position.yaw_rad;
  m.roll_rate_rad_per_s = v.roll_rate_rad_per_s;
  m.yaw_rate_rad_per_s = v.yaw_rate_rad_per_s;
  m.wheel_angular_velocity_rad_per_s =
      std::isnan(v.wheel_angular_velocity_rad_per_s)
          ? wheel_angular_velocity_for_rolling(v.forward_speed_m_per_s, nominal_radius_m, v.extra_longitudinal_creepage)
          : v.wheel_angular_velocity_rad_per_s;
  return m;
}

namespace {

// A conformal patch's tangential solutions (docs/WHEELSET.md §4 "Conformal contact"): its strips'
// creepages in their own frames, each solver on the developed patch.
void solve_conformal(const InterpenetrationRegion& region, const SurfaceSolution& n, const WheelsetMotion& motion,
                     const Vector3& centre, const WheelsetOptions& options, WheelsetPatch& patch) {
  const Mesh& mesh = n.area.mesh;
  for (int i2 = 0; i2 < mesh.n2; ++i2)
    for (int i1 = 0; i1 < mesh.n1; ++i1)
      if (n.normal.pressure_Pa[mesh.index(i1, i2)] > 0.0) {
        patch.strips.push_back(n.area.strips[static_cast<std::size_t>(i2)]);
        break;
      }
  const StripCreepages creepages =
      detail::conformal_strip_creepages(motion, centre, region, n.area, patch.rolling_speed_m_per_s);
  for (TangentialSolver s : options.solvers) {
    detail::ConformalSolve solved =
        detail::solve_conformal_patch(s, region, n.area, n.normal.pressure_Pa, creepages, options);
    patch.pressure_centre_x1_m = solved.pressure_centre_x1_m;
    patch.pressure_centre_x2_m = solved.pressure_centre_x2_m;
    patch.solvers.push_back(std::move(solved.result));
    if (options.keep_tractions) patch.patch = std::move(solved.patch);
  }
}

// A planar patch's tangential solutions (its creepage and normal force already in `patch`), with
// its origin moved to the centre of pressure; `elements` are those in contact.
void solve_planar(WheelSide side, const InterpenetrationRegion& region, const Mesh& mesh,
                  const std::vector<double>& pressure_Pa, const std::vector<std::size_t>& elements,
                  const WheelsetOptions& options, WheelsetPatch& patch) {
  // The left wheel's patches are solved as the mirror image of a right wheel's (x2 -> −x2, so
  // η, φ, F2, M3 change sign): both wheels then see the same discretisation, and the left wheel
  // is the mirrored right wheel to rounding (nH-FastSim's coarse blocks and FastSim's strips are
  // laid out from one side of the patch).
  const bool mirror = side == WheelSide::left;
  const double s2 = mirror ? -1.0 : 1.0;
  Mesh solve_mesh = mesh;
  // The right wheel's fields as they are; the left wheel's mirrored copies.
  std::vector<double> mirrored_pressure;
  std::vector<std::size_t> mirrored_elements;
  if (mirror) {
    // Row i2 (constant x2) becomes row n2 - 1 - i2; an element keeps its place along the row.
    solve_mesh.x2_first_m = -mesh.x2(mesh.n2 - 1);
    const auto n1 = static_cast<std::size_t>(mesh.n1), n2 = static_cast<std::size_t>(mesh.n2);
    mirrored_pressure.resize(pressure_Pa.size());
    for (std::size_t i2 = 0; i2 < n2; ++i2)
      std::copy_n(pressure_Pa.begin() + static_cast<std::ptrdiff_t>(i2 * n1), n1,
                  mirrored_pressure.begin() + static_cast<std::ptrdiff_t>((n2 - 1 - i2) * n1));
    // The elements row by row from the last row: in increasing order on the mirrored mesh.
    mirrored_elements.reserve(elements.size());
    for (auto row_end = elements.end(); row_end != elements.begin();) {
      const std::size_t row = *(row_end - 1) / n1, row_first = row * n1;  // one division per row
      auto row_begin = row_end;
      while (row_begin != elements.begin() && *(row_begin - 1) >= row_first) --row_begin;
      for (auto k = row_begin; k != row_end; ++k) mirrored_elements.push_back((n2 - 1 - row) * n1 + (*k - row_first));
      row_end = row_begin;
    }
  }
  const std::vector<double>& solve_pressure = mirror ? mirrored_pressure : pressure_Pa;
  const std::vector<std::size_t>& solve_elements = mirror ? mirrored_elements : elements;
  // nH-FastSim's coarse patch with its blocks anchored to the reference point (not to the patch's
  // corner, which jumps by an element as elements enter): the forces then change continuously.
  // Otherwise the patch cropped to its elements.
  CoarseBlocks blocks{1, 1};
  if (std::find(options.solvers.begin(), options.solvers.end(), TangentialSolver::nh_fastsim) != options.solvers.end() &&
      elements.size() >= kMinimumElementsForK2) {
    // The aligned crop keeps the elements, so NhFastSim's automatic blocks are these.
    const int factor = options.nh_fastsim.flexibility_coarsening;
    blocks = factor > 0 ? CoarseBlocks{factor, factor} : detail::automatic_coarse_blocks(elements.size());
  }
  ContactPatch contact =
      blocks != CoarseBlocks{1, 1}
          ? detail::block_aligned_patch(solve_mesh, solve_pressure, solve_elements, options.material, blocks)
          : detail::cropped_patch(solve_mesh, solve_pressure, solve_elements, options.material);
  // The patch's origin moved to the centre of pressure (x1c, x2c from the reference point):
  // the rigid slip (ξ − φ x2, η + φ x1) gives the creepages there.
  patch.pressure_centre_x1_m = -contact.x1_shift_m();
  patch.pressure_centre_x2_m = -s2 * contact.x2_shift_m();
  const Creepage c{patch.creepage.xi, s2 * patch.creepage.eta, s2 * patch.creepage.phi};  // in the solve frame
  const double x2c = s2 * patch.pressure_centre_x2_m;
  const Creepage at_centre{c.xi - c.phi * x2c, c.eta + c.phi * patch.pressure_centre_x1_m, c.phi};
  // Classical FastSim and nH-FastSim's small-patch fallback take the patch's equivalent ellipse;
  // nH-FastSim runs per lobe on a patch of several (NhFastSimPerLobe, docs/WHEELSET.md §8).
  for (TangentialSolver s : options.solvers) {
    PatchSolverResult r = solve_tangential(s, contact, at_centre, options);
    r.forces.F2_N *= s2;
    r.forces.M3_Nm *= s2;
    for (double& p2 : r.p2_Pa) p2 *= s2;
    r.force_track_N = combine(region, r.forces.F1_N, r.forces.F2_N, patch.normal_force_N);
    patch.solvers.push_back(std::move(r));
  }
  if (options.keep_tractions) patch.patch = std::move(contact);
}

// A field over a mesh as an Eigen array, for its vectorised reductions (minCoeff, maxCoeff): a
// scalar loop carries the running extreme from element to element, over a potential area's 10 000+
// elements.
Eigen::Map<const Eigen::ArrayXd> as_array(const std::vector<double>& field) {
  return {field.data(), static_cast<Eigen::Index>(field.size())};
}

// One patch on one contact surface with its creepages and tangential solutions.
WheelsetPatch finish_patch(WheelSide side, const WheelsetMotion& motion, const Vector3& centre,
                           const InterpenetrationRegion& region, const SurfaceSolution& n,
                           const WheelsetOptions& options, detail::StageClock* clock) {
  WheelsetPatch patch;
  patch.side = side;
  patch.region = region;
  std::optional<detail::StageClock::Scope> stage(std::in_place, clock, detail::WheelsetStage::kinematics);
  // The creepage point Q on the undeformed wheel surface: the reference point P moved into the
  // rail along the normal by the approach, the largest rigid overlap of the patch (as Kalker's
  // CONTACT takes it; docs/WHEEL_RAIL.md §12).
  patch.approach_m = std::max(0.0, -as_array(n.area.h_m).minCoeff());
  for (std::size_t i = 0; i < 3; ++i)
    patch.creepage_point_track_m[i] = region.reference_point_track_m[i] - patch.approach_m * region.x3_axis[i];
  ContactFrame frame;
  for (std::size_t i = 0; i < 3; ++i) frame.point_from_wheelset_centre_m[i] = patch.creepage_point_track_m[i] - centre[i];
  frame.x1 = region.x1_axis;
  frame.x2 = region.x2_axis;
  frame.x3 = region.x3_axis;
  patch.creepage = kinematic_creepage(motion, frame);
  check_kinematic_creepage(patch.creepage, motion, frame, side);
  patch.rolling_speed_m_per_s = rolling_speed_m_per_s(motion, frame);
  patch.rolling_radius_m = distance_from_axle_m(frame.point_from_wheelset_centre_m, motion);
  stage.reset();
  patch.normal_force_N = n.normal.normal_force_N;
  patch.pressure_force_track_N = pressure_force_track_N(region, n);
  patch.surface = n.area.strips.empty() ? ContactSurface::planar : ContactSurface::conformal;
  patch.elements_in_contact = n.normal.elements_in_contact;
  patch.normal_iterations = n.normal.iterations;
  patch.normal_mesh_elements = n.solved_mesh_elements;
  const Mesh& mesh = n.area.mesh;
  patch.area_m2 = static_cast<double>(patch.elements_in_contact) * mesh.element_area_m2();
  const std::vector<double>& pressure_Pa = n.normal.pressure_Pa;
  patch.max_pressure_Pa = std::max(0.0, as_array(pressure_Pa).maxCoeff());
  stage.emplace(clock, detail::WheelsetStage::tangential);
  std::vector<std::size_t> elements;
  elements.reserve(patch.elements_in_contact);
  for (std::size_t k = 0; k < pressure_Pa.size(); ++k)
    if (pressure_Pa[k] > 0.0) elements.push_back(k);
  if (elements.empty()) {
    // A patch that has just appeared: overlap, but no element in contact yet. Zero forces.
    for (TangentialSolver s : options.solvers) {
      PatchSolverResult r;
      r.solver = s;
      patch.solvers.push_back(r);
    }
    return patch;
  }
  if (!n.area.strips.empty())
    solve_conformal(region, n, motion, centre, options, patch);
  else
    solve_planar(side, region, mesh, n.normal.pressure_Pa, elements, options, patch);
  return patch;
}

// A patch's numbers blended between its planar (weight 1 − w) and conformal (w) solutions
// (ContactSurface::automatic); counts, strips and tractions are the conformal patch's.
WheelsetPatch blended(const WheelsetPatch& planar, WheelsetPatch conformal, double w) {
  const auto mix = [w](double a, double b) { return (1.0 - w) * a + w * b; };
  const auto mix3 = [&](const Vector3& a, Vector3& b) {
    for (std::size_t i = 0; i < 3; ++i) b[i] = mix(a[i], b[i]);
  };
  WheelsetPatch& p = conformal;
  p.creepage = {mix(planar.creepage.xi, p.creepage.xi), mix(planar.creepage.eta, p.creepage.eta),
                mix(planar.creepage.phi, p.creepage.phi)};
  mix3(planar.creepage_point_track_m, p.creepage_point_track_m);
  p.approach_m = mix(planar.approach_m, p.approach_m);
  p.rolling_radius_m = mix(planar.rolling_radius_m, p.rolling_radius_m);
  p.rolling_speed_m_per_s = mix(planar.rolling_speed_m_per_s, p.rolling_speed_m_per_s);
  p.normal_force_N = mix(planar.normal_force_N, p.normal_force_N);
  mix3(planar.pressure_force_track_N, p.pressure_force_track_N);
  p.area_m2 = mix(planar.area_m2, p.area_m2);
  p.max_pressure_Pa = mix(planar.max_pressure_Pa, p.max_pressure_Pa);
  p.pressure_centre_x1_m = mix(planar.pressure_centre_x1_m, p.pressure_centre_x1_m);
  p.pressure_centre_x2_m = mix(planar.pressure_centre_x2_m, p.pressure_centre_x2_m);
  for (std::size_t s = 0; s < p.solvers.size(); ++s) {
    const PatchSolverResult& a = planar.solvers[s];
    PatchSolverResult& b = p.solvers[s];
    b.forces = {mix(a.forces.F1_N, b.forces.F1_N), mix(a.forces.F2_N, b.forces.F2_N), mix(a.forces.M3_Nm, b.forces.M3_Nm)};
    mix3(a.force_track_N, b.force_track_N);
    b.flexibility = {mix(a.flexibility.L1, b.flexibility.L1), mix(a.flexibility.L2, b.flexibility.L2),
                     mix(a.flexibility.L3, b.flexibility.L3)};
    b.coupling = {mix(a.coupling.xi_per_eta, b.coupling.xi_per_eta), mix(a.coupling.xi_per_phi_m, b.coupling.xi_per_phi_m),
                  mix(a.coupling.eta_per_xi, b.coupling.eta_per_xi), mix(a.coupling.eta_per_phi_m, b.coupling.eta_per_phi_m)};
    b.adhesion_fraction = mix(a.adhesion_fraction, b.adhesion_fraction);
  }
  return conformal;
}

// The patches of a wheel with their creepages and tangential solutions.
WheelResult finish_wheel(const WheelsetTrack& track, WheelSide side, const WheelsetState& state,
                         std::vector<NormalPatch>& normal, const WheelsetOptions& options,
                         detail::StageClock* clock) {
  const detail::StageClock::Scope stage(clock, detail::WheelsetStage::assembly);
  WheelResult wheel;
  wheel.side = side;
  wheel.vertical_displacement_m = state.position.vertical_displacement_m;
  const WheelsetMotion motion = wheelset_motion(state, track.parameters().nominal_rolling_radius_m);
  const Vector3 centre{0.0, state.position.lateral_displacement_m,
                       track.nominal_axle_height_m() + state.position.vertical_displacement_m};
  for (const NormalPatch& n : normal) {
    WheelsetPatch patch = finish_patch(side, motion, centre, n.region, n, options, clock);
    patch.conformal_weight = n.conformal_weight;
    patch.coupling_lift_m = n.coupling_lift_m;
    if (n.planar) {
      WheelsetPatch planar = finish_patch(side, motion, centre, n.region, *n.planar, options, clock);
      std::shared_ptr<const WheelsetPatch> conformal_surface;
      if (options.keep_tractions) {
        auto own = std::make_shared<WheelsetPatch>(patch);
        own->conformal_weight = 1.0;
        conformal_surface = std::move(own);
      }
      patch = blended(planar, std::move(patch), n.conformal_weight);
      if (options.keep_tractions) {
        patch.planar_surface = std::make_shared<const WheelsetPatch>(std::move(planar));
        patch.conformal_surface = std::move(conformal_surface);
      }
    }
    wheel.patches.push_back(std::move(patch));
  }
  detail::sum_wheel_forces(wheel, options.solvers.size());
  return wheel;
}

double normal_vertical_force(const std::vector<NormalPatch>& patches) {
  double f = 0.0;
  for (const NormalPatch& p : patches) f += pressure_force_track_N(p)[2];
  return f;
}

// The vertical part of the contact force beyond the pressure's (on a conformal patch the strips'
// tractions turned into the track frame).
double tangential_vertical_force(const WheelResult& wheel, std::size_t solver) {
  double f = 0.0;
  for (const WheelsetPatch& p : wheel.patches) f += p.solvers[solver].force_track_N[2] - p.pressure_force_track_N[2];
  return f;
}

// A height iteration at the deepest overlap accepted (kMaximumOverlap_m) whose wheel still carries
// less than its target: refused.
void require_overlap_within_limit(WheelSide side, double overlap_m, double force_N, double target_N) {
  require(overlap_m < kMaximumOverlap_m || force_N >= target_N, [&] {
    return fmt::format("wheelset: the {} wheel would need an overlap of more than {:g} mm to carry {:g} N (at "
                       "{:g} mm it carries {:g} N)",
                       side_name(side), kMaximumOverlap_m / kMm, target_N, overlap_m / kMm, force_N);
  });
}

// The vertical displacement at which the wheel first touches its rail, from its contact locus (a
// stage of the contact search).
double first_touch(const WheelsetTrack& track, WheelSide side, const WheelsetPosition& position,
                   const WheelsetOptions& options, detail::WheelsetWarmStart& warm) {
  const detail::StageClock::Scope stage(warm.stage_clock, detail::WheelsetStage::search);
  return detail::touching_vertical_displacement_m(track,
                                                  warm.locus_at(track, side, position, options.search.locus_step_m));
}

// The wheel's height at which its normal forces carry `target_N` vertically: Newton-like steps on
// the overlap δ below first touch, F ∝ δ^(3/2) (Hertz) first, then secant steps. overlap_m: the
// first guess of δ in, the δ found out (corrected by a Newton step with the contact stiffness).
double solve_height(const WheelsetTrack& track, WheelSide side, WheelsetPosition position, double target_N,
                    const WheelsetOptions& options, double& overlap_m, std::vector<NormalPatch>& patches,
                    int& iterations, detail::WheelsetWarmStart& warm) {
  const detail::StageClock::Scope height_stage(warm.stage_clock, detail::WheelsetStage::height);
  const double touching = first_touch(track, side, position, options, warm);
  double delta = overlap_m;
  detail::HeightIteration height;
  double& stiffness = warm.stiffness_N_per_m[side == WheelSide::right ? 0 : 1];
  height.seed_stiffness_N_per_m = stiffness;
  // The bracket of δ around the target (force below it at lo_m, above at hi_m), and the trial
  // nearest to it: where the force jumps across the target (two patches merging into one planar
  // patch, docs/WHEELSET.md §3) the bracket is halved until it closes on the jump.
  double lo_m = 0.0, hi_m = std::numeric_limits<double>::infinity(), F_lo = 0.0, F_hi = 0.0;
  double best_residual = std::numeric_limits<double>::infinity(), best_delta = 0.0;
  std::vector<NormalPatch> best;
  for (iterations = 1; iterations <= kMaximumLoadIterations; ++iterations) {
    position.vertical_displacement_m = touching - delta;
    patches = solve_normal(track, side, position, options, warm);
    const double force = normal_vertical_force(patches);
    if (std::abs(force - target_N) <= options.load_tolerance * target_N) {
      if (height.stiffness_N_per_m > 0.0) stiffness = height.stiffness_N_per_m;
      // The overlap out is the root's Newton estimate, free of where within the tolerance the
      // iteration stopped: the next step's prediction extrapolates it.
      overlap_m = stiffness > 0.0 ? delta + (target_N - force) / stiffness : delta;
      return position.vertical_displacement_m;
    }
    if (force > 0.0 && std::abs(force - target_N) < best_residual) {
      best_residual = std::abs(force - target_N);
      best_delta = delta;
      best = patches;
    }
    if (force > 0.0 && force < target_N && delta >= lo_m) lo_m = delta, F_lo = force;
    if (force > target_N && delta <= hi_m) hi_m = delta, F_hi = force;
    double next = height.next_overlap_m(delta, force, target_N, iterations);
    const double slope = height.stiffness_N_per_m > 0.0 ? height.stiffness_N_per_m : stiffness;
    // A jump: more than the stiffness explains by 1e-4 of the target (not the solver's rounding
    // around a root that the load tolerance asks to 1e-10).
    if (std::isfinite(hi_m) && lo_m > 0.0 && slope > 0.0 &&
        F_hi - F_lo > 1.5 * slope * (hi_m - lo_m) + 1e-4 * target_N) {
      if ((hi_m - lo_m) * slope <= kBracketTolerance * target_N) {
        // Closed on the jump: the trial nearest to the target.
        patches = std::move(best);
        position.vertical_displacement_m = touching - best_delta;
        overlap_m = best_delta;
        return position.vertical_displacement_m;
      }
      next = 0.5 * (lo_m + hi_m);
    }
    require_overlap_within_limit(side, delta, force, target_N);
    delta = next;
  }
  throw Error(ErrorKind::not_converged,
              fmt::format("wheelset: the vertical load {:g} N of the {} wheel was not met in {} iterations",
                          target_N, side_name(side), kMaximumLoadIterations));
}

// One wheel's height at which its whole contact force carries `load_N`, on its own (independent
// wheels, no roll to balance; docs/WHEELSET.md §5 "By load"): Newton steps on the overlap δ against
// the total vertical force F(δ) = N(δ) + T(δ), the normal forces' and the tangential forces'
// vertical parts. Each trial solves the normal problem once and, when N + T is within
// kTangentialTrialRange of the load, the tangential problem (until then T keeps its first guess: a
// fresh evaluation's first trials). The stiffness dF/dδ is the secant of N scaled by F/N: T jumps
// where an element enters the patch, N barely. A bracket of δ across which F changes by more than
// 1.5 times what the stiffness explains holds such a jump, and is halved. Settled when |F − load|
// is within the balance's tolerance (1e-5 of the load; 1e-3 after kStrictBalancePasses tangential
// solves) or the bracket has closed to kBracketTolerance of the load: the wheel is then the trial
// nearest to the load. overlap_m: δ's first guess in, the root's Newton estimate out;
// tangential_N: T's first guess in, the answer's T out.
void balance_wheel_total(const WheelsetTrack& track, WheelSide side, const WheelsetState& state, double load_N,
                         const WheelsetOptions& options, double& overlap_m, double& tangential_N, WheelResult& wheel,
                         detail::WheelsetWarmStart& warm) {
  constexpr double kTangentialTrialRange = 1e-2;  // of the load
  // After this many trials every trial solves T: where F jumps across the load by more than the
  // range (two patches merging into one planar patch, docs/WHEELSET.md §3), no trial comes within
  // it, and the bracket that closes on the jump needs trials on both sides.
  constexpr int kTrialsBeforeEveryT = 6;
  const std::size_t k = side == WheelSide::right ? 0 : 1;
  const std::size_t solver = balance_index(options);
  const detail::StageClock::Scope height_stage(warm.stage_clock, detail::WheelsetStage::height);
  const double touching = first_touch(track, side, state.position, options, warm);
  WheelsetState trial = state;
  double delta = overlap_m, T = tangential_N;
  int tangential_trials = 0;
  double lo_m = 0.0, hi_m = std::numeric_limits<double>::infinity();  // F < load at lo_m, > at hi_m
  // The contact stiffness dF/dδ: the last evaluation's, then the secants of this one's trials.
  double& stiffness = warm.stiffness_N_per_m[k];
  const bool seeded = stiffness > 0.0;  // by the last evaluation
  double previous_delta = 0.0, previous_N = 0.0;
  double F_lo = 0.0, F_hi = 0.0;  // the total vertical force at lo_m and hi_m
  // The trial with the tangential part solved that came closest to the load.
  double best_residual = std::numeric_limits<double>::infinity(), best_delta = 0.0, best_F = 0.0, best_T = 0.0;
  WheelResult best;
  bool bracketed = false;
  for (int iteration = 1; iteration <= kMaximumLoadIterations; ++iteration) {
    trial.position.vertical_displacement_m = touching - delta;
    std::vector<NormalPatch> patches = solve_normal(track, side, trial.position, options, warm);
    const double N = normal_vertical_force(patches);
    const bool with_T =
        N > 0.0 && (std::abs(N + T - load_N) <= kTangentialTrialRange * load_N || iteration > kTrialsBeforeEveryT);
    if (with_T) {
      wheel = finish_wheel(track, side, trial, patches, options, warm.stage_clock);
      T = tangential_vertical_force(wheel, solver);
      ++tangential_trials;
    }
    const double F = N + T;
    // The stiffness from the secant of the normal force, which T's jumps do not reach, scaled by
    // F/N (T moves in proportion to N: its friction-limited part does).
    if (N > 0.0 && previous_N > 0.0 && delta != previous_delta) {
      const double secant = (N - previous_N) / (delta - previous_delta) * (F / N);
      if (secant > 0.0) stiffness = secant;
    }
    if (with_T) {
      if (std::abs(F - load_N) < best_residual) {
        best_residual = std::abs(F - load_N);
        best_delta = delta;
        best_F = F;
        best_T = T;
        best = std::move(wheel);  // the next trial that solves T writes `wheel` anew
      }
      if (F < load_N && delta >= lo_m) {
        lo_m = delta;
        F_lo = F;
      }
      if (F > load_N && delta <= hi_m) {
        hi_m = delta;
        F_hi = F;
      }
      const double tolerance = std::max(options.load_tolerance, tangential_trials <= kStrictBalancePasses
                                                                    ? kTangentialBalanceTolerance
                                                                    : kCoarseTangentialBalanceTolerance);
      // The bracket has closed: no trial can come closer than the best.
      bracketed = std::isfinite(hi_m) && lo_m > 0.0;
      const bool closed = bracketed && (hi_m - lo_m) * stiffness <= kBracketTolerance * load_N;
      if (best_residual <= tolerance * load_N || closed) {
        wheel = std::move(best);
        wheel.load_iterations = iteration;
        overlap_m = best_delta + (load_N - best_F) / stiffness;
        tangential_N = best_T;
        return;
      }
    }
    // As the height iteration of solve_height: the first step with the last evaluation's stiffness
    // (a time step), or two of Hertz's (afresh: F grows faster than linearly, and a secant from
    // below would overshoot), then Newton's.
    double next;
    if (!(F > 0.0))
      next = 2.0 * delta;
    else if (!(stiffness > 0.0) || (!seeded && iteration <= 2))
      next = delta * std::pow(load_N / F, 2.0 / 3.0);
    else
      next = delta + (load_N - F) / stiffness;
    next = std::clamp(next, 0.25 * delta, 4.0 * delta);
    // A bracket across which F changes by more than 1.5 times what the stiffness explains holds a
    // jump of T (an element entering the patch): Newton's steps from either side would land across
    // it again and again; it is halved instead.
    const bool jump = bracketed && F_hi - F_lo > 1.5 * stiffness * (hi_m - lo_m);
    if (std::isfinite(hi_m) && (jump || !(next > lo_m && next < hi_m))) next = 0.5 * (lo_m + hi_m);
    require_overlap_within_limit(side, delta, F, load_N);
    previous_delta = delta;
    previous_N = N;
    delta = std::min(next, kMaximumOverlap_m);
  }
  throw Error(ErrorKind::not_converged,
              fmt::format("wheelset: the vertical load {:g} N of the {} wheel was not met in {} iterations ({})",
                          load_N, side_name(side), kMaximumLoadIterations,
                          std::isfinite(best_residual)
                              ? fmt::format("the total vertical force, with the tangential forces' part, came "
                                            "within {:.3g} N of it",
                                            best_residual)
                              : std::string("the normal forces never came within 1 % of it")));
}

}  // namespace

const char* contact_surface_name(ContactSurface surface) {
  switch (surface) {
    case ContactSurface::planar: return "planar";
    case ContactSurface::conformal: return "conformal";
    case ContactSurface::automatic: return "auto";
  }
  return "?";
}

ContactSurface parse_contact_surface(const std::string& name) {
  for (ContactSurface s : {ContactSurface::planar, ContactSurface::conformal, ContactSurface::automatic})
    if (name == contact_surface_name(s)) return s;
  throw Error(fmt::format("unknown contact surface '{}' (contact surfaces: planar, conformal, auto)", name));
}

void validate(const ContactSurfaceSwitch& s) {
  require(std::isfinite(s.planar_up_to) && std::isfinite(s.conformal_from) && s.planar_up_to >= 0.0 &&
              s.planar_up_to < s.conformal_from && s.conformal_from <= 10.0,
          [&] {
            return fmt::format("wheelset: the automatic contact surface's switch (planar up to {:g}, conformal from "
                               "{:g}; contact angle variation / cos γ, rad) needs 0 <= planar_up_to < conformal_from "
                               "<= 10",
                               s.planar_up_to, s.conformal_from);
          });
}

double conformal_surface_weight(ContactSurface surface, const ContactSurfaceSwitch& s,
                                const InterpenetrationRegion& region) {
  if (surface != ContactSurface::automatic) return surface == ContactSurface::conformal ? 1.0 : 0.0;
  const double measure = region.contact_angle_spread_rad / std::cos(region.contact_angle_rad);
  if (!std::isfinite(measure)) return 1.0;
  return detail::smoothstep((measure - s.planar_up_to) / (s.conformal_from - s.planar_up_to));
}

void validate(const PatchCouplingOptions& o) {
  require(std::isfinite(o.full_distance_m) && std::isfinite(o.end_distance_m) && o.full_distance_m >= 0.0 &&
              o.end_distance_m >= o.full_distance_m && o.end_distance_m <= 0.05,
          [&] {
            return fmt::format("wheelset: the patch coupling's distances {:g} mm (full) and {:g} mm (end) must "
                               "satisfy 0 <= full <= end <= 50 mm (both 0: no coupling)",
                               o.full_distance_m / kMm, o.end_distance_m / kMm);
          });
}

void validate(const WheelsetOptions& o) {
  validate(o.material);
  require(std::isfinite(o.friction_coefficient) && o.friction_coefficient > 0.0 && o.friction_coefficient <= 2.0,
          [&] {
            return fmt::format("wheelset: the friction coefficient {} must lie in (0, 2]", o.friction_coefficient);
          });
  require(std::isfinite(o.element_size_m) && o.element_size_m >= 0.02e-3 && o.element_size_m <= 5e-3, [&] {
    return fmt::format("wheelset: the element size {:g} mm must lie in [0.02, 5] mm", o.element_size_m / kMm);
  });
  require(!o.solvers.empty(), "wheelset: at least one tangential solver is needed");
  if (o.balance_solver) {
    require(std::find(o.solvers.begin(), o.solvers.end(), *o.balance_solver) != o.solvers.end(), [&] {
      std::string run;
      for (TangentialSolver s : o.solvers) run += fmt::format("{}{}", run.empty() ? "" : ", ", solver_name(s));
      return fmt::format("wheelset: the balance solver {} is not among the solvers run ({}): name one of them",
                         solver_name(*o.balance_solver), run);
    });
  }
  validate(o.rolling);
  validate(o.search);
  validate(o.patch_coupling);
  validate(o.contact_surface_switch);
  if (o.loads) {
    validate_normal_force(o.loads->right_N, "wheelset: the right wheel's vertical load");
    validate_normal_force(o.loads->left_N, "wheelset: the left wheel's vertical load");
  }
  require(std::isfinite(o.load_tolerance) && o.load_tolerance >= 1e-12 && o.load_tolerance <= 1e-2,
          "wheelset: the load tolerance must lie in [1e-12, 1e-2]");
}

Wheelset::Wheelset(WheelsetTrack track, WheelsetOptions options)
    : track_(std::move(track)), options_(std::move(options)), warm_(std::make_unique<detail::WheelsetWarmStart>()) {
  validate(options_);
}
Wheelset::~Wheelset() = default;
Wheelset::Wheelset(const Wheelset& other)
    : track_(other.track_),
      options_(other.options_),
      warm_(std::make_unique<detail::WheelsetWarmStart>()),
      time_stages_(other.time_stages_) {}
Wheelset& Wheelset::operator=(const Wheelset& other) {
  if (this != &other) {
    track_ = other.track_;
    options_ = other.options_;
    warm_ = std::make_unique<detail::WheelsetWarmStart>();
    time_stages_ = other.time_stages_;
    stage_times_ = {};
  }
  return *this;
}
Wheelset::Wheelset(Wheelset&&) noexcept = default;
void Wheelset::reset_warm_start() { warm_ = std::make_unique<detail::WheelsetWarmStart>(); }
void Wheelset::time_stages(bool on) {
  time_stages_ = on;
  stage_times_ = {};
}
Wheelset& Wheelset::operator=(Wheelset&&) noexcept = default;

void validate(const WheelsetVelocity& v, const WheelsetVelocityNames& names) {
  // "--yaw-rate 10 rad/s" for an option, "wheelset: yaw_rate_rad_per_s = 10 rad/s" for a field or key.
  const auto given = [](const std::string& name, double value, const char* unit) {
    if (name.starts_with("--")) return fmt::format("{} {:g}{}", name, value, unit);
    const bool field = name.find_first_of(".:") == std::string::npos;  // a WheelsetVelocity field
    return fmt::format("{}{} = {:g}{}", field ? "wheelset: " : "", name, value, unit);
  };
  const auto check = [&](double value, const std::string& name, double limit, const char* unit, const char* reason) {
    require(std::isfinite(value) && std::abs(value) <= limit, [&] {
      return fmt::format("{} must lie in [{:g}, {:g}]{} ({})", given(name, value, unit), -limit, limit, unit, reason);
    });
  };
  require(std::isfinite(v.forward_speed_m_per_s) && v.forward_speed_m_per_s > 0.0 &&
              v.forward_speed_m_per_s <= kMaximumForwardSpeed_m_per_s,
          [&] {
            return fmt::format("{} must lie in (0, {:g}] m/s (the creepages are velocities divided by it, a wheelset at "
                               "rest has no steady rolling contact; the rail speed record is 160 m/s)",
                               given(names.forward_speed, v.forward_speed_m_per_s, " m/s"), kMaximumForwardSpeed_m_per_s);
          });
  check(v.lateral_velocity_m_per_s, names.lateral_velocity, kMaximumCentreVelocity_m_per_s, " m/s",
        "hunting of 10 mm at 10 Hz is 0.6 m/s");
  check(v.vertical_velocity_m_per_s, names.vertical_velocity, kMaximumCentreVelocity_m_per_s, " m/s",
        "a wheel flat's impact is about 1 m/s");
  check(v.roll_rate_rad_per_s, names.roll_rate, kMaximumRollYawRate_rad_per_s, " rad/s",
        "a wheelset's roll and yaw oscillate by milliradians at up to 10 Hz");
  check(v.yaw_rate_rad_per_s, names.yaw_rate, kMaximumRollYawRate_rad_per_s, " rad/s",
        "hunting's yaw of 10 mrad at 10 Hz is 0.6 rad/s");
  if (!std::isnan(v.wheel_angular_velocity_rad_per_s))
    check(v.wheel_angular_velocity_rad_per_s, names.wheel_angular_velocity, kMaximumWheelAngularVelocity_rad_per_s,
          " rad/s", "200 m/s on a wheel of 0.2 m radius; V / r0 = 43 rad/s at 20 m/s");
  check(v.extra_longitudinal_creepage, names.extra_longitudinal_creepage, kMaximumCreepage, "",
        "the range of any creepage: beyond, the wheel slides rather than rolls");
  if (v.free_rolling) {
    require(std::isnan(v.wheel_angular_velocity_rad_per_s) && v.extra_longitudinal_creepage == 0.0, [&] {
      return fmt::format("{}: free rolling solves the wheels' angular velocity; it cannot be given as well ({}, {})",
                         names.free_rolling,
                         given(names.wheel_angular_velocity, v.wheel_angular_velocity_rad_per_s, " rad/s"),
                         given(names.extra_longitudinal_creepage, v.extra_longitudinal_creepage, ""));
    });
  }
}

namespace {

// The moment about the axle of the wheels' tangential forces (solver `solver`), each acting at
// its patch's reference point: zero in free rolling.
double axle_moment_Nm(const WheelsetTrack& track, const WheelsetResult& r, std::size_t solver) {
  const Vector3 a = axle_direction(r.state.position.roll_rad, r.state.position.yaw_rad);
  double moment = 0.0;
  for (const WheelResult& w : r.wheels) {
    const Vector3 centre{0.0, r.state.position.lateral_displacement_m,
                         track.nominal_axle_height_m() + w.vertical_displacement_m};
    for (const WheelsetPatch& p : w.patches) {
      const Vector3& f = p.solvers[solver].force_track_N;
      Vector3 q{};
      for (std::size_t i = 0; i < 3; ++i) q[i] = p.region.reference_point_track_m[i] - centre[i];
      const Vector3 m{q[1] * f[2] - q[2] * f[1], q[2] * f[0] - q[0] * f[2], q[0] * f[1] - q[1] * f[0]};
      moment += m[0] * a[0] + m[1] * a[1] + m[2] * a[2];
    }
  }
  return moment;
}

// The evaluation's stage clock in the warm start while the evaluation runs (none after it).
struct RunningStageClock {
  RunningStageClock(detail::WheelsetWarmStart& warm, detail::StageClock* clock) : warm_(warm) {
    warm_.stage_clock = clock;
  }
  ~RunningStageClock() { warm_.stage_clock = nullptr; }
  RunningStageClock(const RunningStageClock&) = delete;
  RunningStageClock& operator=(const RunningStageClock&) = delete;
  detail::WheelsetWarmStart& warm_;
};

}  // namespace

WheelsetResult Wheelset::evaluate(const WheelsetState& input) {
  std::optional<detail::StageClock> clock;
  if (time_stages_) clock.emplace(stage_times_);
  const RunningStageClock running(*warm_, clock ? &*clock : nullptr);
  validate(input.position);
  validate(input.velocity);
  if (!input.velocity.free_rolling) return evaluate_rolling(input);

  // Free rolling (docs/WHEELSET.md §5): the wheels' angular velocity Ω at which the moment of the
  // tangential forces about the axle vanishes. Secant steps from pure rolling at r0; the moment
  // falls with Ω (a faster wheel brakes less, drives more), nearly linearly while the patches
  // adhere.
  constexpr int kMaximumFreeRollingIterations = 12;
  const std::size_t solver = balance_index(options_);
  WheelsetState state = input;
  state.velocity.free_rolling = false;
  const double r0 = track_.parameters().nominal_rolling_radius_m;
  double omega = input.velocity.forward_speed_m_per_s / r0;
  double previous_omega = 0.0, previous_moment = 0.0;
  for (int iteration = 1; iteration <= kMaximumFreeRollingIterations; ++iteration) {
    state.velocity.wheel_angular_velocity_rad_per_s = omega;
    WheelsetResult r = evaluate_rolling(state);
    double vertical = 0.0;
    for (const WheelResult& w : r.wheels) vertical += w.solver_force_track_N.empty() ? 0.0 : w.solver_force_track_N[solver][2];
    if (!(vertical > 0.0)) {
      throw Error(ErrorKind::no_contact, "wheelset: free rolling needs a wheel in contact with its rail to balance the "
                                         "wheels' rotation (neither wheel touches its rail)");
    }
    const double moment = axle_moment_Nm(track_, r, solver);
    // Settled when the moment is below 1e-6 of the one the friction could give (μ F_z r0).
    const double tolerance = 1e-6 * options_.friction_coefficient * vertical * r0;
    if (std::abs(moment) <= tolerance) {
      r.state.velocity = input.velocity;
      r.state.velocity.wheel_angular_velocity_rad_per_s = omega;
      r.free_rolling_iterations = iteration;
      return r;
    }
    double next = omega * (1.0 + 1e-4);  // the first step: ξ changes by about 1e-4
    if (iteration > 1 && moment != previous_moment)
      next = omega - moment * (omega - previous_omega) / (moment - previous_moment);
    previous_omega = omega;
    previous_moment = moment;
    omega = next;
  }
  throw Error(ErrorKind::not_converged,
              fmt::format("wheelset: free rolling: the moment of the wheels' tangential forces about the axle did not "
                          "vanish in {} evaluations (last {:.3g} N m at {:.6g} rad/s)",
                          kMaximumFreeRollingIterations, previous_moment, previous_omega));
}

namespace {

// A rigid axle's roll (WheelLoads::balance_roll): the wheels' heights must agree. The first step
// turns the axle about its centre (the left wheel rises by roll × its lever); then secant steps,
// since in flange contact each wheel's own height also moves with the roll. A pass that left the
// roll where it was (its heights agreed, then the tangential forces moved them) takes the first
// kind of step again: a secant through one roll has no slope.
struct RollBalance {
  double previous_roll = 0.0, previous_mismatch = 0.0;

  // True when the heights agree (kHeightTolerance_m); otherwise `roll` moves to the next guess.
  bool settle(int pass, const std::array<double, 2>& heights, double lever_m, double& roll) {
    const double mismatch = heights[1] - heights[0];
    double next = roll + mismatch / (2.0 * lever_m);
    if (pass > 0 && mismatch != previous_mismatch && roll != previous_roll)
      next = roll - mismatch * (roll - previous_roll) / (mismatch - previous_mismatch);
    previous_roll = roll;
    previous_mismatch = mismatch;
    if (std::abs(mismatch) < kHeightTolerance_m) return true;
    roll = next;
    return false;
  }
};

// One wheel's tangential part T of its vertical balance, a fixed point T = g(T) with g'(T) near −1
// in flange contact (F2 saturated, γ steep): secant steps on the residual r(T) = g(T) − T, which
// falls with T, kept inside the bracket of the T values seen with r > 0 and r < 0 (bisection when a
// secant step leaves it). The discretisation makes g jump where elements enter the patch: when the
// bracket has shrunk to kBracketTolerance of the load around such a jump, its middle is the answer.
struct TangentialBalance {
  double value_N = 0.0;  // T, the guess the pass solves the height with
  double previous_N = 0.0, previous_residual_N = 0.0;
  double lo_N = -std::numeric_limits<double>::infinity(), hi_N = std::numeric_limits<double>::infinity();

  // The next guess after the pass's g(T). `state_kept`: the pass solved the state of the passes
  // before it (balancing the roll: the roll had settled). A pass that moved the roll changes g, and
  // the bracket of the passes before no longer holds: it starts again, and that pass adds nothing
  // to it (g(0) at the first pass's roll once bracketed the answer of another roll, 1.3 % of the
  // load off, on S1002/UIC60 at y = −6.5 mm).
  void step(int pass, double g_N, bool state_kept) {
    const double T = value_N, residual = g_N - T;
    if (!state_kept) {
      lo_N = -std::numeric_limits<double>::infinity();
      hi_N = std::numeric_limits<double>::infinity();
    } else {
      if (residual > 0.0) lo_N = std::max(lo_N, T);
      if (residual < 0.0) hi_N = std::min(hi_N, T);
    }
    double next = g_N;
    if (pass > 0 && residual != previous_residual_N)
      next = T - residual * (T - previous_N) / (residual - previous_residual_N);
    if (std::isfinite(lo_N) && std::isfinite(hi_N) && !(next > lo_N && next < hi_N)) next = 0.5 * (lo_N + hi_N);
    previous_N = T;
    previous_residual_N = residual;
    value_N = next;
  }
  [[nodiscard]] bool bracket_closed(double load_N) const { return hi_N - lo_N <= kBracketTolerance * load_N; }
};

constexpr std::array<WheelSide, 2> kSides{WheelSide::right, WheelSide::left};

// By position: each wheel's patches at the state's overlap.
void evaluate_by_position(const WheelsetTrack& track, const WheelsetOptions& options, detail::WheelsetWarmStart& warm,
                          WheelsetResult& result) {
  for (std::size_t k = 0; k < 2; ++k) {
    std::vector<NormalPatch> normal = solve_normal(track, kSides[k], result.state.position, options, warm);
    result.wheels[k] = finish_wheel(track, kSides[k], result.state, normal, options, warm.stage_clock);
  }
}

// By load: each wheel's height (or, balancing roll, the axle's height and roll) so that the
// vertical force of its patches equals its load; optionally with the tangential forces' vertical
// components, from the previous pass. In a time step (a state near the last one, the warm start)
// the heights and the tangential parts start from the last ones.
void balance_loads(const WheelsetTrack& track, const WheelsetOptions& options, detail::WheelsetWarmStart& warm,
                   bool stepped, WheelsetResult& result);

void evaluate_by_load(const WheelsetTrack& track, const WheelsetOptions& options, detail::WheelsetWarmStart& warm,
                      WheelsetResult& result) {
  if (warm.near_last_position(result.state.position)) {
    // A time step: from the last heights, stiffnesses and tangential parts. Should those guesses
    // lead the iteration to a height that cannot be solved (a trial overlap whose potential area
    // runs off the rail profile, where the state itself can be), the state is solved afresh.
    WheelsetResult stepped = result;
    try {
      balance_loads(track, options, warm, true, stepped);
      result = std::move(stepped);
      return;
    } catch (const Error&) {
    }
  }
  balance_loads(track, options, warm, false, result);
}

void balance_loads(const WheelsetTrack& track, const WheelsetOptions& options, detail::WheelsetWarmStart& warm,
                   bool stepped, WheelsetResult& result) {
  const detail::StageClock::Scope height_stage(warm.stage_clock, detail::WheelsetStage::height);
  const WheelsetState input = result.state;
  const std::array<double, 2> loads{options.loads->right_N, options.loads->left_N};
  if (!stepped) warm.stiffness_N_per_m = {0.0, 0.0};
  const detail::WheelsetWarmStart::HeightGuess guess = warm.predicted(input.position);
  std::array<TangentialBalance, 2> tangential{};
  if (stepped && options.tangential_forces_in_vertical_balance)
    for (std::size_t k = 0; k < 2; ++k) tangential[k].value_N = guess.tangential_vertical_N[k];
  std::array<double, 2> overlap = stepped ? guess.overlap_m : std::array<double, 2>{0.08e-3, 0.08e-3};
  RollBalance roll;
  std::array<double, 2> heights{0.0, 0.0};
  std::array<std::vector<NormalPatch>, 2> normal;
  std::array<int, 2> iterations{0, 0}, solves{0, 0};
  WheelsetState state = input;
  // A time step balancing the roll starts from the roll predicted from the last steps (the input's
  // roll is only the first guess of a fresh evaluation).
  if (stepped && options.loads->balance_roll) state.position.roll_rad = guess.roll_rad;
  const auto remember = [&] {
    result.state = state;
    warm.older_position = stepped ? warm.last_position : std::nullopt;
    warm.older_overlap_m = warm.overlap_m;
    warm.older_tangential_vertical_N = warm.tangential_vertical_N;
    warm.older_roll_rad = warm.roll_rad;
    warm.roll_rad = state.position.roll_rad;
    warm.overlap_m = overlap;
    for (std::size_t k = 0; k < 2; ++k) warm.tangential_vertical_N[k] = tangential[k].value_N;
    warm.last_position = input.position;
  };
  if (!options.loads->balance_roll && options.tangential_forces_in_vertical_balance) {
    // Independent wheels: each wheel's total vertical force balanced on its own.
    for (std::size_t k = 0; k < 2; ++k) {
      balance_wheel_total(track, kSides[k], state, loads[k], options, overlap[k], tangential[k].value_N,
                          result.wheels[k], warm);
      heights[k] = result.wheels[k].vertical_displacement_m;
    }
    state.position.vertical_displacement_m = 0.5 * (heights[0] + heights[1]);
    remember();
    return;
  }
  // Balancing the roll, or the normal forces alone: passes, each solving both wheels' heights to
  // their loads less the tangential parts T, then the tangential problems and the next T and roll.
  for (int pass = 0; pass < kMaximumBalanceIterations; ++pass) {
    for (std::size_t k = 0; k < 2; ++k) {
      heights[k] = solve_height(track, kSides[k], state.position, loads[k] - tangential[k].value_N, options, overlap[k],
                                normal[k], iterations[k], warm);
      solves[k] += iterations[k];
    }
    const bool roll_settled =
        !options.loads->balance_roll ||
        roll.settle(pass, heights, track.wheel_profile_origin_y_m(WheelSide::left), state.position.roll_rad);
    bool settled = roll_settled;
    state.position.vertical_displacement_m = 0.5 * (heights[0] + heights[1]);
    std::array<double, 2> new_tangential{0.0, 0.0};
    const double tolerance = pass < kStrictBalancePasses ? kTangentialBalanceTolerance : kCoarseTangentialBalanceTolerance;
    for (std::size_t k = 0; k < 2; ++k) {
      WheelsetState wheel_state = state;
      wheel_state.position.vertical_displacement_m = heights[k];
      result.wheels[k] = finish_wheel(track, kSides[k], wheel_state, normal[k], options, warm.stage_clock);
      result.wheels[k].load_iterations = solves[k];
      if (options.tangential_forces_in_vertical_balance)
        new_tangential[k] = tangential_vertical_force(result.wheels[k], balance_index(options));
      settled = settled && std::abs(new_tangential[k] - tangential[k].value_N) <=
                               std::max(options.load_tolerance, tolerance) * loads[k];
    }
    if (settled) break;
    for (std::size_t k = 0; k < 2; ++k) {
      // The next pass's load differs by the change of T: its overlap guessed with the contact
      // stiffness (Newton), so that the pass's first normal solve is close.
      const double previous_T = tangential[k].value_N;
      tangential[k].step(pass, new_tangential[k], roll_settled);
      if (warm.stiffness_N_per_m[k] > 0.0)
        overlap[k] = std::clamp(overlap[k] + (previous_T - tangential[k].value_N) / warm.stiffness_N_per_m[k],
                                0.5 * overlap[k], 2.0 * overlap[k]);
    }
    if (roll_settled && tangential[0].bracket_closed(loads[0]) && tangential[1].bracket_closed(loads[1]))
      break;
    if (pass + 1 >= kMaximumBalanceIterations) {
      throw Error(ErrorKind::not_converged,
                  fmt::format("wheelset: the vertical balance of the wheels did not settle in {} passes (the "
                              "tangential forces' vertical part still changes by {:.3g} N and {:.3g} N)",
                              kMaximumBalanceIterations, new_tangential[0] - tangential[0].previous_N,
                              new_tangential[1] - tangential[1].previous_N));
    }
  }
  remember();
}

// The wheelset's totals (a lifted wheel refused unless allowed), every number finite.
void assemble_totals(const WheelsetOptions& options, const WheelsetState& input, WheelsetResult& result) {
  for (std::size_t k = 0; k < 2; ++k) {
    if (result.wheels[k].patches.empty() && !options.allow_wheel_lift) {
      throw Error(ErrorKind::no_contact,
                  fmt::format("wheelset: the {} wheel does not touch its rail at y = {:.3f} mm, z = {:.3f} mm "
                              "(lifted; allow_wheel_lift accepts this with zero forces)",
                              side_name(kSides[k]), input.position.lateral_displacement_m / kMm,
                              input.position.vertical_displacement_m / kMm));
    }
  }
  detail::sum_wheelset_forces(result, options.solvers.size());
}

}  // namespace

WheelsetResult Wheelset::evaluate_rolling(const WheelsetState& input) {
  WheelsetResult result;
  result.state = input;
  ++warm_->evaluation;
  if (options_.loads)
    evaluate_by_load(track_, options_, *warm_, result);
  else
    evaluate_by_position(track_, options_, *warm_, result);
  assemble_totals(options_, input, result);
  return result;
}

WheelsetTrack default_wheelset_track() {
  const WheelRailSetup setup = read_wheel_rail_setup(default_wheel_rail_setup_path());
  return WheelsetTrack(read_profile(setup.wheel_profile, ProfileReadOptions{.role = ProfileKind::wheel}), read_profile(setup.rail_profile, ProfileReadOptions{.role = ProfileKind::rail}), setup.track);
}

}  // namespace railcontact
