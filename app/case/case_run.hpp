#pragma once
// Runs a case end to end: patch -> (K2 -> flexibilities) -> the requested tangential solvers.
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "case/case.hpp"
#include "railcontact/flexibility_table.hpp"
#include "railcontact/kalker.hpp"
#include "railcontact/contact_patch.hpp"

namespace railcontact {

struct SolverRun {
  TangentialSolver kind = TangentialSolver::exact;
  TangentialForces forces;
  double time_s = 0.0;                 // the whole solver, flexibilities included
  // Part of time_s spent preparing the model (TangentialModel): nh-fastsim its K2 (or the table's
  // flexibilities) and FastSim's set-up, fastsim Eq 9 and FastSim's set-up; reported for these two.
  double flexibility_time_s = 0.0;
  int iterations = 0;                  // Newton (exact solvers), GMRES for K2 (nh-fastsim), 0 (fastsim)
  int krylov_iterations = 0;
  std::optional<Flexibility> flexibility;  // FastSim solvers
  std::string flexibility_source;          // "K2" or "table" (nh-fastsim), "Eq 9" (fastsim)
  double adhesion_fraction = 0.0;
  // Per contact element (patch order):
  std::vector<double> p1_Pa, p2_Pa;
  std::vector<std::uint8_t> slip;
};

struct PatchSummary {
  std::string geometry;                // "ellipse" or "wheel-rail"
  double a_m = 0.0, b_m = 0.0;         // ellipse semi-axes, or the equivalent ellipse of a wheel-rail patch
  double normal_force_N = 0.0;
  double area_m2 = 0.0;
  double max_pressure_Pa = 0.0;
  std::size_t elements_in_contact = 0;
  int n1 = 0, n2 = 0;
  double dx1_m = 0.0, dx2_m = 0.0;
  double extent_x1_m = 0.0, extent_x2_m = 0.0;
  // Wheel-rail patches only:
  double lateral_displacement_m = 0.0, contact_angle_rad = 0.0, rolling_radius_m = 0.0, spin_per_m = 0.0;
};

struct CaseResult {
  Case input;
  ContactPatch patch;
  PatchSummary summary;
  Creepage creepage;                          // the raw creepages used (after normalisation)
  std::optional<Matrix3> creepage_matrix;  // K2 when nh-fastsim ran or normalisation needed it
  std::vector<SolverRun> runs;
  // With a flexibility table: its name and target elements, and its values at (y, Fz) scaled to
  // this patch's area (nh-fastsim's L and the normalisation's f11, f22 come from them).
  std::optional<FlexibilityTableValues> flexibility_table_values;
  std::string flexibility_table_file;  // FlexibilityTable::source(): empty for a table not read from a file
  int flexibility_table_target_elements = 0;
  [[nodiscard]] const SolverRun* find(TangentialSolver kind) const;
};

struct CaseRunOptions {
  // Wheel-rail cases only: nh-fastsim takes its flexibilities L1-L3, and normalised creepages
  // their f11, f22, from this table (interpolated at the case's y and Fz for its patch) instead
  // of K2 (docs/FLEXTABLE.md §6). Throws Error for an ellipse case, a table of other profiles,
  // material or nH-FastSim recipe (FlexibilityTable::check_recipe: the case's [solvers]
  // flexibility_coarsening, 0 = automatic, and alpha), and y or Fz outside the table.
  std::shared_ptr<const FlexibilityTable> flexibility_table;
};

// The checks run_case makes before any work: every value of the case against the library's
// ranges, the error naming the case key. Throws railcontact::Error (invalid_input).
void validate_case(const Case& input);

// Throws railcontact::Error on bad input or a solver that does not converge. Progress lines go
// to `progress` when given.
CaseResult run_case(const Case& input, std::ostream* progress = nullptr);
CaseResult run_case(const Case& input, const CaseRunOptions& options, std::ostream* progress = nullptr);

// The built-in default case (`railcontact run` without a file).
Case default_case();

}  // namespace railcontact
