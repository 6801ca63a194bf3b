#pragma once
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
#include <memory>

#include "railcontact/creepage.hpp"
#include "railcontact/fastsim.hpp"
#include "railcontact/flexibility_table.hpp"
#include "railcontact/wheel_rail_patch.hpp"

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
    [[nodiscard]] const FastSim& fastsim() const { return fastsim_; }
    [[nodiscard]] double normal_force_N() const { return patch_->normal_force_N; }
    [[nodiscard]] double spin_per_m() const { return patch_->spin_per_m; }  // from conicity, Eq 24

   private:
    std::shared_ptr<const WheelRailPatch> patch_;
    FastSim fastsim_;
    FlexibilityTableValues values_;
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
