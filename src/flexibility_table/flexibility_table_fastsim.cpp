// nH-FastSim from a flexibility table: normal solve + FastSim, or FastSim on a cached patch.
#include "railcontact/flexibility_table.hpp"

#include <fmt/format.h>

#include <cmath>

#include "railcontact/error.hpp"

namespace railcontact {
namespace {

WheelRailPatchOptions table_patch_options(const FlexibilityTable& table) {
  WheelRailPatchOptions options;
  options.material = table.metadata().material;
  options.target_elements = table.metadata().target_elements;
  options.reference = table.metadata().contact_reference;
  return options;
}

}  // namespace

FlexibilityTableFastSim::Patch::Patch(const FlexibilityTable& table, WheelRailPatch patch)
    : patch_(std::make_shared<const WheelRailPatch>(std::move(patch))),
      values_(table.lookup_for_patch(patch_->lateral_displacement_m, patch_->vertical_load_N, patch_->area_m2)),
      nh_fastsim_(patch_->patch, NhFastSimFlexibilities{values_.flexibility, values_.f11_N, values_.f22_N, values_.f23_Nm, values_.coupling}) {}

TangentialForces FlexibilityTableFastSim::Patch::forces(const Creepage& creepage, double mu) const {
  return nh_fastsim_.forces(creepage, mu);
}

FastSimResult FlexibilityTableFastSim::Patch::solve(const Creepage& creepage, double mu) const {
  return nh_fastsim_.solve(creepage, mu);
}

Creepage FlexibilityTableFastSim::Patch::creepage_from_normalised(double xi_normalised, double eta_normalised,
                                                                  double phi_per_m, double mu) const {
  if (!(std::isfinite(mu) && mu > 0.0)) throw Error(fmt::format("normalised creepage: mu must be positive (got {})", mu));
  return nh_fastsim_.creepage_from_normalised(xi_normalised, eta_normalised, phi_per_m, mu, patch_->normal_force_N);
}

FlexibilityTableFastSim::FlexibilityTableFastSim(FlexibilityTable table, WheelRailPair pair)
    : FlexibilityTableFastSim(table, std::move(pair), table_patch_options(table)) {}

FlexibilityTableFastSim::FlexibilityTableFastSim(FlexibilityTable table, WheelRailPair pair,
                                                 const WheelRailPatchOptions& patch_options)
    : table_(std::move(table)), pair_(std::move(pair)), patch_options_(patch_options) {
  require(!table_.empty(), "flexibility table: the table is empty");
  table_.check_profiles(pair_);
  table_.check_material(patch_options_.material, table_.metadata().collocation_offset);
}

FlexibilityTableFastSim::Patch FlexibilityTableFastSim::prepare(double y_m, double vertical_load_N) const {
  (void)table_.lookup(y_m, vertical_load_N);  // range and gaps first: before the normal solve
  WheelRailPatchOptions options = patch_options_;
  options.vertical_load_N = vertical_load_N;
  return Patch(table_, solve_wheel_rail_patch(pair_, y_m, options));
}

TangentialForces FlexibilityTableFastSim::forces(double y_m, double vertical_load_N, const Creepage& creepage,
                                                 double mu) const {
  return prepare(y_m, vertical_load_N).forces(creepage, mu);
}

}  // namespace railcontact
