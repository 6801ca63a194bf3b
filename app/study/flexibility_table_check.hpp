#pragma once
// `railcontact flextable check`: the force error of a flexibility table against nH-FastSim with
// on-the-fly flexibilities (docs/FLEXTABLE.md §4). At each check point (y, Fz) the normal problem
// is solved once; on that patch FastSim runs with the flexibilities of K2 (on the fly) and with
// the table's (interpolated, scaled with the patch's area), for the creepage families of the
// paper (ξ' = 0.1, 0.5, 1.0; η' = 0.5 with spin; ξ' = η' = 0.5 with spin; μ = 0.3).
#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

#include "railcontact/flexibility_table.hpp"

namespace railcontact::study {

struct CreepageFamily {
  std::string name;
  double xi_normalised = 0.0;   // ξ' (Eq 22)
  double eta_normalised = 0.0;  // η' (Eq 23)
  bool spin_from_conicity = false;  // φ from Eq 24 (of the patch), else 0
};

// ξ' = 0.1, 0.5, 1.0; η' = 0.5 with spin; ξ' = η' = 0.5 with spin.
std::vector<CreepageFamily> paper_creepage_families();

struct FlexibilityTableCheckOptions {
  // Empty: the midpoints of the table's y intervals that have two solved nodes and no contact jump.
  std::vector<double> y_m;
  // Empty: the table's loads and, with several, the geometric midpoints between them.
  std::vector<double> vertical_loads_N;
  double mu = 0.3;
  int target_elements = 0;  // 0: the table's
  FlexibilityInterpolation interpolation = FlexibilityInterpolation::area_scaled;
  // Also solve the exact problem (Coulomb, `exact`) at every point and family: the error of the
  // table and of on-the-fly nH-FastSim against it (a few exact solves per point: slower).
  bool against_exact = false;
};

struct FlexibilityTableCheckPoint {
  double y_m = 0.0, vertical_load_N = 0.0;
  std::size_t elements_in_contact = 0;
  Flexibility on_the_fly, table;  // L of K2 on this patch; L of the table for this patch
  double f11_on_the_fly_N = 0.0, f22_on_the_fly_N = 0.0, f11_table_N = 0.0, f22_table_N = 0.0;
  // Per family: |F_table − F_on-the-fly| / |F_on-the-fly| (F = (F1, F2)) with the same raw
  // creepages (ξ, η from the on-the-fly f11, f22): the error of the table's flexibilities alone.
  std::vector<double> force_difference;
  // The same with the table's run normalised by the table's f11, f22 (as `run --flextable` does).
  std::vector<double> force_difference_table_normalised;
  // With against_exact, per family: |F - F_exact| / |F_exact| of the table's run and of on the fly.
  std::vector<double> table_error_against_exact, on_the_fly_error_against_exact;
};

struct FlexibilityTableCheck {
  std::vector<CreepageFamily> families;
  std::vector<FlexibilityTableCheckPoint> points;
  std::vector<std::string> skipped;  // check points that could not be solved, with the reason
  // Over all points and families (force_difference and force_difference_table_normalised):
  double max_force_difference = 0.0, mean_force_difference = 0.0;
  std::size_t max_point = 0, max_family = 0;
  double max_force_difference_table_normalised = 0.0, mean_force_difference_table_normalised = 0.0;
  // With against_exact: over all points and families.
  double max_table_error_against_exact = 0.0, max_on_the_fly_error_against_exact = 0.0;
  double mean_table_error_against_exact = 0.0, mean_on_the_fly_error_against_exact = 0.0;
};

// Throws Error when the table does not belong to the pair, a check point lies outside the table,
// or the options are bad; points whose patch cannot be solved are skipped (listed).
FlexibilityTableCheck check_flexibility_table(const FlexibilityTable& table, const WheelRailPair& pair,
                                              const FlexibilityTableCheckOptions& options, std::ostream* progress = nullptr);

}  // namespace railcontact::study
