// The one contact patch of a grid's normal problem (single_grid_patch, railcontact/normal.hpp): the
// normal solve by load or by approach, its regions, specks dropped, several patches refused.
#include <fmt/core.h>

#include <algorithm>
#include <string>

#include "railcontact/error.hpp"
#include "railcontact/normal.hpp"

namespace railcontact {
namespace {

GridPatch patch_of(const Mesh& mesh, NormalSolution normal, const Material& material, const NormalOptions& options,
                   std::string_view what) {
  if (!normal.converged)
    throw Error(ErrorKind::not_converged,
                fmt::format("{}: the normal solver did not converge in {} iterations (residual {:.3g}, tolerance {:.3g})",
                            what, normal.iterations, normal.residual, options.tolerance));
  const std::vector<ContactRegion> regions = contact_regions(mesh, normal.pressure_Pa);
  const auto significant = std::count_if(regions.begin(), regions.end(), [](const ContactRegion& r) {
    return r.load_fraction > kSpeckLoadFraction;
  });
  if (significant > 1)
    throw Error(ErrorKind::several_patches,
                fmt::format("{}: the normal solution has {} separate contact patches (loads {:.3g} and {:.3g} of F3); "
                            "the single-patch API needs one",
                            what, significant, regions[0].load_fraction, regions[1].load_fraction));
  // Specks (regions under 1 % of the load) are dropped, as by the wheel-rail stage.
  std::vector<double> pressure(mesh.size(), 0.0);
  for (const std::size_t k : regions.front().elements) pressure[k] = normal.pressure_Pa[k];
  return {ContactPatch(mesh, pressure, material), std::move(normal)};
}

}  // namespace

GridPatch single_grid_patch(const Mesh& mesh, const std::vector<double>& undeformed_distance_m, double normal_force_N,
                            const Material& material, const NormalOptions& options, std::string_view what) {
  return patch_of(mesh, solve_normal_contact(mesh, undeformed_distance_m, normal_force_N, material, options), material,
                  options, what);
}

GridPatch single_grid_patch_at_approach(const Mesh& mesh, const std::vector<double>& undeformed_distance_m,
                                        double approach_m, const Material& material, const NormalOptions& options,
                                        std::string_view what) {
  NormalSolution normal = solve_normal_contact_at_approach(mesh, undeformed_distance_m, approach_m, material, options);
  if (normal.elements_in_contact == 0)
    throw Error(ErrorKind::no_contact,
                fmt::format("{} at approach {} m: no element comes into contact (h - approach > 0 everywhere)", what,
                            approach_m));
  validate_normal_force(normal.normal_force_N, fmt::format("{} at approach {} m: the normal force found", what, approach_m));
  return patch_of(mesh, std::move(normal), material, options, what);
}

}  // namespace railcontact
