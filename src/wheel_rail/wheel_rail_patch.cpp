// The wheel–rail normal-contact pipeline of one wheelset position (docs/WHEEL_RAIL.md §1–2):
// contact point → F3 = Fz / cos γ → mesh from a Hertz estimate → normal solve → mesh refined
// until about target_elements elements are in contact → connected regions → the single patch.
#include "railcontact/wheel_rail.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "hertz/hertz_estimate.hpp"
#include "railcontact/error.hpp"
#include "railcontact/tangential.hpp"
#include "railcontact/wheelset_geometry.hpp"
#include "tangential/cropped_patch.hpp"
#include "wheel_rail/wheel_height.hpp"

namespace railcontact {

namespace {

constexpr double kMm = 1e-3;
// Margin factor of the potential area (h < margin × δ) once δ is known from a solve.
constexpr double kKnownApproachMargin = 1.15;

void validate(const WheelRailPatchOptions& o) {
  validate_normal_force(o.vertical_load_N, "wheel-rail patch: the vertical wheel load");
  require(o.target_elements >= kMinimumWheelRailElements && o.target_elements <= kMaximumWheelRailElements, [&] {
    return fmt::format(
        "wheel-rail patch: the target number of elements in contact target_elements = {} must lie in [{}, {}] (with "
        "fewer the elements are too coarse for the patch and for the profiles)",
        o.target_elements, kMinimumWheelRailElements, kMaximumWheelRailElements);
  });
  require(std::isfinite(o.element_count_tolerance) && o.element_count_tolerance > 0.0 &&
              o.element_count_tolerance < 1.0,
          "wheel-rail patch: the element-count tolerance must lie in (0, 1)");
  require(o.max_mesh_passes >= 1, "wheel-rail patch: at least one mesh pass is needed");
  require(o.max_enlargements >= 0, "wheel-rail patch: max_enlargements must be non-negative");
  require(!o.initial_approach_m || (std::isfinite(*o.initial_approach_m) && *o.initial_approach_m > 0.0),
          "wheel-rail patch: the initial approach must be positive");
  require(std::isfinite(o.significant_load_fraction) && o.significant_load_fraction >= 0.0 &&
              o.significant_load_fraction < 1.0,
          "wheel-rail patch: the significant load fraction must lie in [0, 1)");
  require(std::isfinite(o.load_tolerance) && o.load_tolerance > 0.0 && o.load_tolerance <= 0.01, [&] {
    return fmt::format("wheel-rail patch: the load tolerance {:g} must lie in (0, 0.01]", o.load_tolerance);
  });
  require(o.reference == ContactReference::smooth || o.reference == ContactReference::first_touch,
          "wheel-rail patch: unknown contact reference");
  validate(o.search);
  validate(o.material);
}

// Element sizes for an element area S and patch extents L1 x L2 (PatchMeshLayout).
struct ElementSizes {
  double dx1_m, dx2_m;
};
ElementSizes element_sizes(double element_area_m2, double extent_x1_m, double extent_x2_m, PatchMeshLayout layout) {
  const double dx1_over_dx2 = layout == PatchMeshLayout::square ? 1.0 : std::min(1.0, extent_x1_m / extent_x2_m);
  return {std::sqrt(element_area_m2 * dx1_over_dx2), std::sqrt(element_area_m2 / dx1_over_dx2)};
}

// Extents of a region along X1 and X2, edge to edge.
struct Extents {
  double x1_m, x2_m;
};
Extents extents(const Mesh& mesh, const ContactRegion& region) {
  const detail::IndexBox box = detail::bounding_box(mesh, region.elements);
  return {(box.hi1 - box.lo1 + 1) * mesh.dx1_m, (box.hi2 - box.lo2 + 1) * mesh.dx2_m};
}

// "67.5 % of the load at x2 = +0.3 mm, 32.5 % at x2 = +10.6 mm"
std::string load_shares(const std::vector<ContactRegion>& regions, std::size_t count) {
  std::string text;
  for (std::size_t k = 0; k < count; ++k)
    text += fmt::format("{}{:.1f} %{} at x2 = {:+.1f} mm", k == 0 ? "" : ", ", 100.0 * regions[k].load_fraction,
                        k == 0 ? " of the load" : "", regions[k].x2_centre_m / kMm);
  return text;
}

// The potential contact area failed (h < margin × δ reaches beyond the profiles, or a normal line
// of its mesh misses a profile). Either the patch itself does not fit on the profiles (the load is
// too large for them) or only the mesh does not: its border of whole elements reaches beyond them
// when the elements are large (few elements in contact). Which one: the same area with elements
// 2, 4, 8, 16 times smaller (4 ... 256 times as many in contact, up to kMaximumWheelRailElements);
// the first that fits gives the number of elements to ask for.
Error potential_area_error(const WheelRailPair& pair, const WheelRailContactPoint& contact, double approach_m,
                           const PotentialAreaOptions& failed, const Error& error, const std::string& where,
                           const WheelRailPatchOptions& options) {
  for (int factor = 2; factor <= 16; factor *= 2) {
    const double count = static_cast<double>(options.target_elements) * factor * factor;
    if (count > kMaximumWheelRailElements) break;
    PotentialAreaOptions finer = failed;
    finer.dx1_m = failed.dx1_m / factor;
    finer.dx2_m = failed.dx2_m / factor;
    try {
      (void)potential_contact_area(pair, contact, approach_m, finer);
    } catch (const Error&) {
      continue;
    }
    return Error(error.kind(),
                 fmt::format("wheel-rail patch at {}: elements of {:.3f} x {:.3f} mm (target_elements = {} elements in "
                             "contact) are too large for these profiles at Fz = {:g} N: the potential contact area with "
                             "its border of whole elements reaches beyond them ({}); use more elements (about {:g} fit)",
                             where, failed.dx1_m / kMm, failed.dx2_m / kMm, options.target_elements,
                             options.vertical_load_N, error.what(), count));
  }
  return Error(error.kind(), fmt::format("wheel-rail patch at {}: {} (the load Fz = {:g} N is too large for these "
                                         "profiles: the patch does not fit on them)",
                                         where, error.what(), options.vertical_load_N));
}

// Non-convergence of a normal solve is an error of kind not_converged naming the position.
void require_converged(const NormalSolution& normal, const std::string& where) {
  if (!normal.converged)
    throw Error(ErrorKind::not_converged,
                fmt::format("wheel-rail patch at {}: the normal solver did not converge in {} iterations "
                            "(residual {:.2g})",
                            where, normal.iterations, normal.residual));
}

struct Solve {
  PotentialContactArea area;
  NormalSolution normal;
  std::vector<ContactRegion> regions;
};

// The smooth reference (docs/WHEEL_RAIL.md §6): the wheel's height at which its interpenetration
// regions, each solved by position in its own tangent plane, carry Fz vertically; each region's
// reference point and contact angle are the wheelset's (WheelsetTrack::contact_search), so the
// patch is the wheelset's right-wheel patch at zero roll and yaw.
constexpr int kMaximumHeightIterations = 30;

// One interpenetration region's normal problem at the wheel's height; its solver plan and last
// pressure start the next iteration's solve when the mesh stays the same.
struct RegionSolve {
  InterpenetrationRegion region;
  TangentPlaneArea area;
  NormalSolution normal;
  std::unique_ptr<NormalContactSolver> solver;
};

bool same_mesh(const Mesh& a, const Mesh& b) {
  return a.n1 == b.n1 && a.n2 == b.n2 && a.dx1_m == b.dx1_m && a.dx2_m == b.dx2_m && a.x1_first_m == b.x1_first_m &&
         a.x2_first_m == b.x2_first_m;
}

std::vector<RegionSolve> solve_regions(const WheelsetTrack& track, const WheelsetPosition& position, double dx1_m,
                                       double dx2_m, const WheelRailPatchOptions& options, const std::string& where,
                                       std::vector<RegionSolve>& previous, int& solves) {
  const WheelContactSearch search = track.contact_search(WheelSide::right, position, options.search);
  std::vector<RegionSolve> out;
  for (const InterpenetrationRegion& region : search.regions) {
    RegionSolve s;
    s.region = region;
    s.area = track.potential_contact_area(position, region, dx1_m, dx2_m, 2);
    std::vector<double> initial;
    for (RegionSolve& p : previous) {
      if (p.solver && same_mesh(p.area.mesh, s.area.mesh)) {
        s.solver = std::move(p.solver);
        initial = std::move(p.normal.pressure_Pa);
        break;
      }
    }
    if (!s.solver) s.solver = std::make_unique<NormalContactSolver>(s.area.mesh, options.material, options.normal);
    // h is measured at this height (negative where the bodies overlap): the approach is zero.
    s.normal = s.solver->solve_at_approach(s.area.h_m, 0.0, initial);
    ++solves;
    require_converged(s.normal, where);
    out.push_back(std::move(s));
  }
  return out;
}

double vertical_force(const std::vector<RegionSolve>& solves) {
  double f = 0.0;
  for (const RegionSolve& s : solves) f += s.normal.normal_force_N * s.region.x3_axis[2];
  return f;
}

// "67.5 % of the load at y_rail = -1.2 mm, 32.5 % at y_rail = -31.0 mm"
std::string region_load_shares(const std::vector<RegionSolve>& solves, double total_N) {
  std::string text;
  for (std::size_t k = 0; k < solves.size(); ++k)
    text += fmt::format("{}{:.1f} %{} at y_rail = {:+.1f} mm", k == 0 ? "" : ", ",
                        100.0 * solves[k].normal.normal_force_N * solves[k].region.x3_axis[2] / total_N,
                        k == 0 ? " of the load" : "", solves[k].region.rail_profile_y_m / kMm);
  return text;
}

// The wheel's height at which its patches carry the load (the vertical overlap below first touch,
// started from the first-touch approach along its normal, then the steps of a wheelset's height by
// load, wheel_rail/wheel_height.hpp): the solves of every region there. Sets the load iterations,
// the solves made and the height in r.
std::vector<RegionSolve> solve_height_by_load(const WheelsetTrack& track, double y_m, const WheelRailPatchOptions& options,
                                              const Solve& first_touch, const std::string& where, WheelRailPatch& r) {
  WheelsetPosition position;
  position.lateral_displacement_m = y_m;
  const double touching = track.touching_vertical_displacement_m(WheelSide::right, position);
  const double target = options.vertical_load_N;
  const double dx1 = first_touch.area.mesh.dx1_m, dx2 = first_touch.area.mesh.dx2_m;
  double delta = first_touch.normal.approach_m / std::cos(r.contact.contact_angle_rad);
  detail::HeightIteration height;
  std::vector<RegionSolve> solves, previous;
  int solves_done = 0;
  for (r.load_iterations = 1;; ++r.load_iterations) {
    if (r.load_iterations > kMaximumHeightIterations)
      throw Error(ErrorKind::not_converged,
                  fmt::format("wheel-rail patch at {}: the wheel's height carrying Fz = {:g} N was not found in {} "
                              "iterations",
                              where, target, kMaximumHeightIterations));
    position.vertical_displacement_m = touching - delta;
    previous = std::move(solves);
    solves = solve_regions(track, position, dx1, dx2, options, where, previous, solves_done);
    const double force = vertical_force(solves);
    if (std::abs(force - target) <= options.load_tolerance * target) break;
    if (delta >= detail::kMaximumWheelOverlap_m && force < target)
      throw Error(fmt::format("wheel-rail patch at {}: the wheel would need an overlap of more than {:g} mm to carry "
                              "Fz = {:g} N (at {:g} mm it carries {:g} N)",
                              where, detail::kMaximumWheelOverlap_m / kMm, target, delta / kMm, force));
    delta = height.next_overlap_m(delta, force, target, r.load_iterations);
  }
  r.mesh_passes += solves_done;
  r.vertical_displacement_m = position.vertical_displacement_m;
  return solves;
}

// The most loaded patch of the solves, sorted first by decreasing vertical load (several
// significant ones refused unless allowed); one patch alone solved again to carry the load exactly.
RegionSolve& main_patch(std::vector<RegionSolve>& solves, double total, const WheelRailPatchOptions& options,
                        const std::string& where, WheelRailPatch& r) {
  const double target = options.vertical_load_N;
  std::sort(solves.begin(), solves.end(), [](const RegionSolve& a, const RegionSolve& b) {
    return a.normal.normal_force_N * a.region.x3_axis[2] > b.normal.normal_force_N * b.region.x3_axis[2];
  });
  r.patches = static_cast<std::size_t>(std::count_if(solves.begin(), solves.end(), [&](const RegionSolve& s) {
    return s.normal.normal_force_N * s.region.x3_axis[2] > options.significant_load_fraction * total;
  }));
  if (r.patches > 1 && !options.allow_several_patches) {
    throw Error(ErrorKind::several_patches,
                fmt::format("{} gives several contact patches ({} patches: {}); several patches are out of scope "
                            "for a single wheel-rail patch (railcontact wheelset solves them all)",
                            where, r.patches, region_load_shares(solves, total)));
  }
  RegionSolve& main = solves.front();
  if (solves.size() == 1) {
    // One patch carries the load exactly (F3 cos γ = Fz, frictionless equilibrium as with the
    // first-touch reference) on the same mesh and h: its approach moves by the height
    // iteration's tolerance.
    main.normal = main.solver->solve(main.area.h_m, target / main.region.x3_axis[2]);
    ++r.mesh_passes;
    require_converged(main.normal, where);
  }
  return main;
}

// The patch's numbers from the main region's solve: angle, spin, F3, the crop (in whole coarse
// blocks), centre of pressure, extents, and h and the approach from h's lowest point.
void describe_main_patch(const WheelRailPair& pair, RegionSolve& main, double total, std::size_t regions,
                         const WheelRailPatchOptions& options, const std::string& where, WheelRailPatch& r) {
  r.region = main.region;
  r.contact_angle_rad = main.region.contact_angle_rad;
  r.rolling_radius_m = main.region.rolling_radius_m;
  r.spin_per_m = conicity_spin_per_m(r.contact_angle_rad, WheelSide::right,
                                     2.0 * pair.parameters().nominal_rolling_radius_m);
  r.normal_force_N = main.normal.normal_force_N;
  r.dropped_load_fraction =
      regions == 1 ? 0.0 : std::max(0.0, 1.0 - main.normal.normal_force_N * main.region.x3_axis[2] / total);
  const Mesh& mesh = main.area.mesh;
  std::vector<std::size_t> elements;
  double max_pressure = 0.0;
  for (std::size_t k = 0; k < mesh.size(); ++k) {
    if (main.normal.pressure_Pa[k] > 0.0) elements.push_back(k);
    max_pressure = std::max(max_pressure, main.normal.pressure_Pa[k]);
  }
  if (elements.empty())
    throw Error(ErrorKind::no_contact, fmt::format("wheel-rail patch at {}: no element in contact", where));
  // Cropped in whole blocks of nH-FastSim's automatic coarsening, counted from the reference point
  // (as a wheelset's patch): the coarse patch of its flexibilities then changes continuously with y
  // instead of with the patch's corner, which jumps by an element as elements enter (flexibility
  // tables: docs/FLEXTABLE.md §4). The elements and pressures are those of the plain crop.
  r.patch = detail::cropped_patch(mesh, main.normal.pressure_Pa, elements, options.material);
  const CoarseBlocks blocks = NhFastSim::automatic_coarse_blocks(r.patch);
  if (blocks != CoarseBlocks{1, 1})
    r.patch = detail::block_aligned_patch(mesh, main.normal.pressure_Pa, elements, options.material, blocks);
  r.pressure_centre_x1_m = -r.patch.x1_shift_m();
  r.pressure_centre_x2_m = -r.patch.x2_shift_m();
  // The tangent-plane point O + x2 X2 with X2 = (−cos γ, sin γ) in the rail profile frame.
  r.pressure_centre_y_rail_m = main.region.rail_profile_y_m - r.pressure_centre_x2_m * std::cos(r.contact_angle_rad);
  r.pressure_centre_contact_angle_rad = std::atan(-pair.rail().dz_dy(r.pressure_centre_y_rail_m));
  const detail::IndexBox box = detail::bounding_box(mesh, elements);
  r.extent_x1_m = (box.hi1 - box.lo1 + 1) * mesh.dx1_m;
  r.extent_x2_m = (box.hi2 - box.lo2 + 1) * mesh.dx2_m;
  r.elements_in_contact = elements.size();
  r.area_m2 = static_cast<double>(r.elements_in_contact) * mesh.element_area_m2();
  r.max_pressure_Pa = max_pressure;
  r.iterations = main.normal.iterations;
  // h from its lowest point: the same normal problem with the approach δ − min h.
  const double lowest = *std::min_element(main.area.h_m.begin(), main.area.h_m.end());
  r.approach_m = main.normal.approach_m - lowest;
  r.normal = std::move(main.normal);
  r.normal.approach_m = r.approach_m;
  r.potential_area = mesh;
  r.potential_h_m = std::move(main.area.h_m);
  for (double& h : r.potential_h_m) h -= lowest;
  r.regions = contact_regions(mesh, r.normal.pressure_Pa);
}

// The patch with the smooth reference, from the first-touch solution's element sizes and approach.
void smooth_reference_patch(const WheelRailPair& pair, double y_m, const WheelRailPatchOptions& options,
                            const Solve& first_touch, const std::string& where, WheelRailPatch& r) {
  const WheelsetTrack track(pair);
  std::vector<RegionSolve> solves = solve_height_by_load(track, y_m, options, first_touch, where, r);
  const double total = vertical_force(solves);
  RegionSolve& main = main_patch(solves, total, options, where, r);
  describe_main_patch(pair, main, total, solves.size(), options, where, r);
}

// The contact of first touch at y: its point, angle, rolling radius and spin (Eq 24, signed: the
// modelled pair is the right wheel, docs/WHEEL_RAIL.md §3), and the normal force F3 = Fz / cos γ of
// the frictionless vertical equilibrium (METHOD.md §9).
WheelRailPatch first_touch_contact(const WheelRailPair& pair, double y_m, const WheelRailPatchOptions& options,
                                   const std::string& where) {
  WheelRailPatch r;
  r.contact = pair.contact_point(y_m);
  r.lateral_displacement_m = y_m;
  r.contact_angle_rad = r.contact.contact_angle_rad;
  r.rolling_radius_m = r.contact.rolling_radius_m;
  r.spin_per_m = conicity_spin_per_m(r.contact_angle_rad, WheelSide::right,
                                     2.0 * pair.parameters().nominal_rolling_radius_m);
  r.vertical_load_N = options.vertical_load_N;
  const double cos_gamma = std::cos(r.contact_angle_rad);
  require(cos_gamma > 0.05, [&] {
    return fmt::format("wheel-rail patch at {}: the contact angle {:.3f} rad is too steep", where, r.contact_angle_rad);
  });
  // Frictionless equilibrium of the vertical forces (METHOD.md §9): F3 cos γ = Fz.
  r.normal_force_N = options.vertical_load_N / cos_gamma;
  validate_normal_force(r.normal_force_N, fmt::format("wheel-rail patch at {}: the normal force F3 = Fz / cos γ of Fz = {:g} N and "
                                        "γ = {:.3f} rad",
                                        where, options.vertical_load_N, r.contact_angle_rad));
  return r;
}

// A target too fine for the load, refused before the first-touch solves (seconds with 200000
// elements): the smooth reference meshes the track's overlap with the first-touch element sizes, at
// least kMinimumTangentPlaneElement_m.
void require_elements_for_smooth_reference(const HertzContact& estimate, const WheelRailPatchOptions& options,
                                           const std::string& where) {
  const double element_area_m2 = M_PI * estimate.a_m * estimate.b_m / options.target_elements;
  const auto target = static_cast<double>(options.target_elements);
  const ElementSizes dx = element_sizes(element_area_m2, 2.0 * estimate.a_m, 2.0 * estimate.b_m, options.layout);
  const double smallest = std::min(dx.dx1_m, dx.dx2_m);
  if (smallest < kMinimumTangentPlaneElement_m) {
    // The element area scales as 1 / target_elements: the target whose smallest side is the minimum.
    const double fitting = target * (smallest / kMinimumTangentPlaneElement_m) * (smallest / kMinimumTangentPlaneElement_m);
    const std::string advice =
        fitting >= kMinimumWheelRailElements
            ? fmt::format("about {:.0f} elements or fewer fit at this load, or give a larger load", std::floor(fitting))
            : fmt::format("even the fewest, {}, are too small at this load: give a larger load",
                          kMinimumWheelRailElements);
    throw Error(fmt::format("{} elements of {:.2g} x {:.2g} mm at {} (target_elements = {} in a patch of about "
                            "{:.3g} mm2 at Fz = {:g} N) are smaller than the {:g} mm the smooth contact reference "
                            "takes: {}",
                            kWheelRailElementsTooSmall, dx.dx1_m / kMm, dx.dx2_m / kMm, where,
                            options.target_elements, M_PI * estimate.a_m * estimate.b_m / (kMm * kMm),
                            options.vertical_load_N, kMinimumTangentPlaneElement_m / kMm, advice));
  }
}

// The normal problem on potential areas meshed for the patch: re-meshed (at most max_mesh_passes)
// until about target_elements are in contact, a wider margin when the patch touches the area's
// border; the solve closest to the target.
Solve solve_mesh_passes(const WheelRailPair& pair, const HertzContact& estimate, const WheelRailPatchOptions& options,
                        const std::string& where, WheelRailPatch& r) {
  const double F3 = r.normal_force_N;
  double approach_m = options.initial_approach_m.value_or(estimate.approach_m);
  double margin = PotentialAreaOptions{}.margin_factor;
  double element_area_m2 = M_PI * estimate.a_m * estimate.b_m / options.target_elements;
  double extent1 = 2.0 * estimate.a_m, extent2 = 2.0 * estimate.b_m;
  const auto target = static_cast<double>(options.target_elements);
  std::optional<Solve> best;
  int enlargements = 0;

  for (int pass = 0; pass < options.max_mesh_passes;) {
    const ElementSizes dx = element_sizes(element_area_m2, extent1, extent2, options.layout);
    PotentialAreaOptions area_options;
    area_options.dx1_m = dx.dx1_m;
    area_options.dx2_m = dx.dx2_m;
    area_options.margin_factor = margin;
    Solve s;
    try {
      s.area = potential_contact_area(pair, r.contact, approach_m, area_options);
    } catch (const Error& e) {
      // An area too large for the memory is refused as it is, with the mesh size asked for.
      if (std::string_view(e.what()).starts_with(kPotentialAreaTooLarge))
        throw Error(fmt::format("wheel-rail patch at {} with target_elements = {} at Fz = {:g} N: {}", where,
                                options.target_elements, options.vertical_load_N, e.what()));
      throw potential_area_error(pair, r.contact, approach_m, area_options, e, where, options);
    }
    s.normal = solve_normal_contact(s.area.mesh, s.area.h_m, F3, options.material, options.normal);
    ++r.mesh_passes;
    require_converged(s.normal, where);
    if (s.normal.touches_border) {
      // The undeformed interpenetration h < δ holds every patch: cover it with a wider margin.
      require(enlargements < options.max_enlargements, [&] {
        return fmt::format(
            "wheel-rail patch at {}: the potential contact area cannot hold the patch (it still touches "
            "the border of a {} x {} mesh after {} enlargements)",
            where, s.area.mesh.n1, s.area.mesh.n2, enlargements);
      });
      // The truncated patch's δ overestimates the true one: grow by at most a factor 2 × 1.5.
      ++enlargements;
      margin *= 1.5;
      approach_m = std::clamp(s.normal.approach_m, approach_m, 2.0 * approach_m);
      continue;
    }
    s.regions = contact_regions(s.area.mesh, s.normal.pressure_Pa);
    const auto count = static_cast<double>(s.normal.elements_in_contact);
    const double approach_solved_m = s.normal.approach_m;
    const Extents e = extents(s.area.mesh, s.regions.front());
    const auto misfit = [&](const Solve& t) {
      return std::abs(static_cast<double>(t.normal.elements_in_contact) / target - 1.0);
    };
    const bool within = misfit(s) <= options.element_count_tolerance;
    if (!best || misfit(s) < misfit(*best)) best = std::move(s);
    if (within) break;
    // Elements in contact ∝ area / S: scale S (each dx by sqrt(count / target)).
    element_area_m2 *= count / target;
    extent1 = e.x1_m;
    extent2 = e.x2_m;
    // δ is now known to discretisation accuracy and the patch lies in h < δ: a tighter margin
    // keeps the next mesh small (a patch that still touches the border enlarges it again).
    approach_m = approach_solved_m;
    margin = kKnownApproachMargin;
    ++pass;
  }

  require(best.has_value(), [&] { return fmt::format("wheel-rail patch at {}: no normal solution", where); });
  return std::move(*best);
}

// The first-touch reference's patch: the main region of the solve (several significant regions
// refused unless allowed), cropped, with its centre of pressure and extents.
void first_touch_patch(const WheelRailPair& pair, const WheelRailPatchOptions& options, Solve& s,
                       const std::string& where, WheelRailPatch& r) {
  const double cos_gamma = std::cos(r.contact_angle_rad);
  const Mesh& mesh = s.area.mesh;
  const ContactRegion& main = s.regions.front();
  r.patches = static_cast<std::size_t>(std::count_if(s.regions.begin(), s.regions.end(), [&](const ContactRegion& g) {
    return g.load_fraction > options.significant_load_fraction;
  }));
  if (r.patches > 1 && !options.allow_several_patches) {
    throw Error(ErrorKind::several_patches, fmt::format("{} gives several contact patches ({} patches: {}); several patches are out of scope "
                            "for now",
                            where, r.patches, load_shares(s.regions, r.patches)));
  }
  double max_pressure = 0.0;
  for (std::size_t k : main.elements) max_pressure = std::max(max_pressure, s.normal.pressure_Pa[k]);
  r.patch = detail::cropped_patch(mesh, s.normal.pressure_Pa, main.elements, options.material);
  r.dropped_load_fraction = 1.0 - main.load_fraction;
  r.pressure_centre_x1_m = main.x1_centre_m;
  r.pressure_centre_x2_m = main.x2_centre_m;
  // The tangent-plane point C + x2 X2 with X2 = (−cos γ, sin γ) in the rail profile frame.
  r.pressure_centre_y_rail_m = r.contact.y_rail_m - main.x2_centre_m * cos_gamma;
  r.pressure_centre_contact_angle_rad = std::atan(-pair.rail().dz_dy(r.pressure_centre_y_rail_m));
  const Extents e = extents(mesh, main);
  r.extent_x1_m = e.x1_m;
  r.extent_x2_m = e.x2_m;
  r.elements_in_contact = main.elements.size();
  r.area_m2 = static_cast<double>(r.elements_in_contact) * mesh.element_area_m2();
  r.max_pressure_Pa = max_pressure;
  r.approach_m = s.normal.approach_m;
  r.iterations = s.normal.iterations;
  r.normal = std::move(s.normal);
  r.potential_area = mesh;
  r.potential_h_m = std::move(s.area.h_m);
  r.regions = std::move(s.regions);
}

}  // namespace

const char* contact_reference_name(ContactReference reference) {
  return reference == ContactReference::smooth ? "smooth" : "first-touch";
}

ContactReference parse_contact_reference(const std::string& name) {
  if (name == "smooth") return ContactReference::smooth;
  if (name == "first-touch") return ContactReference::first_touch;
  throw Error(fmt::format("contact reference \"{}\": expected \"smooth\" or \"first-touch\"", name));
}

WheelRailPatch solve_wheel_rail_patch(const WheelRailPair& pair, double y_m, const WheelRailPatchOptions& options) {
  validate(options);
  require(std::isfinite(y_m), "wheel-rail patch: the lateral displacement y must be finite");
  const std::string where = fmt::format("y = {:.3f} mm", y_m / kMm);
  WheelRailPatch r = first_touch_contact(pair, y_m, options, where);
  const double F3 = r.normal_force_N;
  // First estimate: Hertz for the local curvatures. B <= 0 (laterally conformal or concave) has
  // no Hertzian contact; a small positive B then only seeds the mesh passes.
  const double A = r.contact.A_per_m, B = r.contact.B_per_m;
  // Hertz's closed form without its physical ranges (hertz_estimate): a nearly conformal contact
  // has B below kMinimumRelativeCurvature_per_m, and the estimate is only a seed.
  if (B > 0.0) r.local_hertz = detail::hertz_estimate(A, B, F3, options.material);
  const HertzContact estimate = B > 0.0 ? r.local_hertz : detail::hertz_estimate(A, 0.05 * A, F3, options.material);

  if (options.reference == ContactReference::smooth) require_elements_for_smooth_reference(estimate, options, where);
  Solve best = solve_mesh_passes(pair, estimate, options, where, r);
  r.reference = options.reference;
  if (options.reference == ContactReference::smooth)
    smooth_reference_patch(pair, y_m, options, best, where, r);
  else
    first_touch_patch(pair, options, best, where, r);
  return r;
}

}  // namespace railcontact
