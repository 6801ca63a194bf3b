// Force error of a flexibility table against on-the-fly nH-FastSim (docs/FLEXTABLE.md §4).
#include "study/flexibility_table_check.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <cmath>

#include "railcontact/error.hpp"
#include "railcontact/tangential.hpp"

namespace railcontact::study {
namespace {

constexpr double kMm = 1e-3;

std::vector<double> default_y(const FlexibilityTable& table) {
  std::vector<double> y;
  const auto& grid = table.y_m();
  std::vector<std::uint8_t> jump(grid.size(), 0);
  for (const ContactJump& j : table.contact_jumps()) jump[j.interval] = 1;
  for (std::size_t k = 0; k + 1 < grid.size(); ++k) {
    bool solved = jump[k] == 0;
    for (std::size_t il = 0; il < table.vertical_loads_N().size(); ++il)
      solved = solved && table.node(k, il).status == FlexibilityNodeStatus::solved &&
               table.node(k + 1, il).status == FlexibilityNodeStatus::solved;
    if (solved) y.push_back(0.5 * (grid[k] + grid[k + 1]));
  }
  return y;
}

std::vector<double> default_loads(const FlexibilityTable& table) {
  const auto& loads = table.vertical_loads_N();
  std::vector<double> out;
  for (std::size_t k = 0; k < loads.size(); ++k) {
    out.push_back(loads[k]);
    if (k + 1 < loads.size()) out.push_back(std::sqrt(loads[k] * loads[k + 1]));
  }
  return out;
}

double relative_difference(const TangentialForces& table, const TangentialForces& reference) {
  return std::hypot(table.F1_N - reference.F1_N, table.F2_N - reference.F2_N) / std::hypot(reference.F1_N, reference.F2_N);
}

}  // namespace

std::vector<CreepageFamily> paper_creepage_families() {
  return {{"xi'=0.1", 0.1, 0.0, false},
          {"xi'=0.5", 0.5, 0.0, false},
          {"xi'=1.0", 1.0, 0.0, false},
          {"eta'=0.5+spin", 0.0, 0.5, true},
          {"xi'=eta'=0.5+spin", 0.5, 0.5, true}};
}

namespace {

void validate(const FlexibilityTableCheckOptions& options) {
  require(std::isfinite(options.mu) && options.mu > 0.0 && options.mu <= 2.0,
          [&] { return fmt::format("flextable check: mu must lie in (0, 2] (got {})", options.mu); });
  require(options.target_elements == 0 || (options.target_elements >= kMinimumWheelRailElements &&
                                           options.target_elements <= kMaximumWheelRailElements),
          [&] {
            return fmt::format("flextable check: --elements {} must lie in [{}, {}]", options.target_elements,
                               kMinimumWheelRailElements, kMaximumWheelRailElements);
          });
}

// The check patches: the table's material and contact reference, its mesh unless --elements.
WheelRailPatchOptions check_patch_options(const FlexibilityTable& table, const FlexibilityTableCheckOptions& options) {
  WheelRailPatchOptions patch_options;
  patch_options.material = table.metadata().material;
  patch_options.reference = table.metadata().contact_reference;  // the table's own reference
  patch_options.target_elements = options.target_elements > 0 ? options.target_elements : table.metadata().target_elements;
  return patch_options;
}

// nH-FastSim on the fly with the recipe the table was built with: the check then measures the
// table's interpolation alone.
NhFastSimOptions table_recipe(const FlexibilityTable& table) {
  NhFastSimOptions recipe;
  recipe.collocation_offset = table.metadata().collocation_offset;
  recipe.flexibility_coarsening = table.metadata().flexibility_coarsening;
  return recipe;
}

// One check point's patch with nH-FastSim on the fly and the table's lookup for it.
struct CheckPatch {
  const WheelRailPatch& patch;
  const NhFastSim& on_the_fly;
  const FlexibilityTableValues& table;
};

// Per creepage family (raw creepages from the on-the-fly f11, f22 at μ F3 saturation, Eq 22-23):
// the table's forces against on-the-fly ones, and with against_exact both against the exact solver.
void compare_families(const CheckPatch& at, const std::vector<CreepageFamily>& families, double mu,
                      bool against_exact, FlexibilityTableCheckPoint& point) {
  const FastSim& fastsim = at.on_the_fly.fastsim();
  const double saturation = 3.0 * mu * at.patch.normal_force_N;  // Eq 22-23
  for (const CreepageFamily& family : families) {
    const double phi = family.spin_from_conicity ? at.patch.spin_per_m : 0.0;
    const Creepage raw{family.xi_normalised * saturation / point.f11_on_the_fly_N,
                       family.eta_normalised * saturation / point.f22_on_the_fly_N, phi};
    const Creepage table_raw{family.xi_normalised * saturation / at.table.f11_N,
                             family.eta_normalised * saturation / at.table.f22_N, phi};
    const TangentialForces reference = fastsim.forces(raw, point.on_the_fly, mu, at.on_the_fly.coupling());
    const TangentialForces tabled = fastsim.forces(raw, point.table, mu, at.table.coupling);
    const TangentialForces table_normalised = fastsim.forces(table_raw, point.table, mu, at.table.coupling);
    point.force_difference.push_back(relative_difference(tabled, reference));
    point.force_difference_table_normalised.push_back(relative_difference(table_normalised, reference));
    if (against_exact) {
      const TangentialForces exact = solve_rolling_exact(at.patch.patch, raw, mu).forces;
      point.table_error_against_exact.push_back(relative_difference(tabled, exact));
      point.on_the_fly_error_against_exact.push_back(relative_difference(reference, exact));
    }
  }
}

// The check at (y, Fz) on a solved patch: both flexibilities and the families' force differences.
FlexibilityTableCheckPoint check_point(const FlexibilityTable& table, const WheelRailPatch& p, double y, double Fz,
                                       const FlexibilityTableCheckOptions& options, const NhFastSimOptions& recipe,
                                       const std::vector<CreepageFamily>& families) {
  const NhFastSim on_the_fly(p.patch, recipe);
  const FlexibilityTableValues v = table.lookup_for_patch(y, Fz, p.area_m2, options.interpolation);
  FlexibilityTableCheckPoint point;
  point.y_m = y;
  point.vertical_load_N = Fz;
  point.elements_in_contact = p.elements_in_contact;
  point.on_the_fly = on_the_fly.flexibility();
  point.table = v.flexibility;
  point.f11_on_the_fly_N = on_the_fly.flexibilities().f11_N;
  point.f22_on_the_fly_N = on_the_fly.flexibilities().f22_N;
  point.f11_table_N = v.f11_N;
  point.f22_table_N = v.f22_N;
  compare_families({p, on_the_fly, v}, families, options.mu, options.against_exact, point);
  return point;
}

// The sums of the means over all points and families (those against exact in the check itself).
struct DifferenceSums {
  double force_difference = 0.0, table_normalised = 0.0;
  std::size_t count = 0;
};

// A point's differences into the check's maxima (the largest with its point and family) and sums;
// the point is the next in check.points.
void add_to_statistics(const FlexibilityTableCheckPoint& point, bool against_exact, FlexibilityTableCheck& check,
                       DifferenceSums& sums) {
  for (std::size_t f = 0; f < check.families.size(); ++f) {
    const double d = point.force_difference[f];
    if (d > check.max_force_difference) {
      check.max_force_difference = d;
      check.max_point = check.points.size();
      check.max_family = f;
    }
    check.max_force_difference_table_normalised =
        std::max(check.max_force_difference_table_normalised, point.force_difference_table_normalised[f]);
    sums.force_difference += d;
    sums.table_normalised += point.force_difference_table_normalised[f];
    ++sums.count;
    if (against_exact) {
      check.max_table_error_against_exact = std::max(check.max_table_error_against_exact, point.table_error_against_exact[f]);
      check.max_on_the_fly_error_against_exact =
          std::max(check.max_on_the_fly_error_against_exact, point.on_the_fly_error_against_exact[f]);
      check.mean_table_error_against_exact += point.table_error_against_exact[f];
      check.mean_on_the_fly_error_against_exact += point.on_the_fly_error_against_exact[f];
    }
  }
}

void print_point(std::ostream& progress, const FlexibilityTableCheckPoint& point) {
  double worst = 0.0;
  for (double d : point.force_difference) worst = std::max(worst, d);
  fmt::print(progress, "  y = {:+.4f} mm, Fz = {:g} N: {} elements, max |dF|/|F| = {:.3f} %\n", point.y_m / kMm,
             point.vertical_load_N, point.elements_in_contact, 100 * worst);
}

}  // namespace

FlexibilityTableCheck check_flexibility_table(const FlexibilityTable& table, const WheelRailPair& pair,
                                              const FlexibilityTableCheckOptions& options, std::ostream* progress) {
  validate(options);
  table.check_profiles(pair);
  const std::vector<double> ys = options.y_m.empty() ? default_y(table) : options.y_m;
  const std::vector<double> loads = options.vertical_loads_N.empty() ? default_loads(table) : options.vertical_loads_N;
  require(!ys.empty(), [&] { return fmt::format("flextable check: the {} has no interval to check", table.name()); });
  // Range and gaps of every point first: a bad point fails before any solve.
  for (double y : ys)
    for (double Fz : loads) (void)table.lookup(y, Fz, options.interpolation);

  FlexibilityTableCheck check;
  check.families = paper_creepage_families();
  WheelRailPatchOptions patch_options = check_patch_options(table, options);
  const NhFastSimOptions recipe = table_recipe(table);
  DifferenceSums sums;
  for (double Fz : loads) {
    for (double y : ys) {
      patch_options.vertical_load_N = Fz;
      WheelRailPatch p;
      try {
        p = solve_wheel_rail_patch(pair, y, patch_options);
      } catch (const Error& e) {
        check.skipped.push_back(fmt::format("y = {:.4f} mm, Fz = {:g} N: {}", y / kMm, Fz, e.what()));
        if (progress) fmt::print(*progress, "  skipped {}\n", check.skipped.back());
        continue;
      }
      FlexibilityTableCheckPoint point = check_point(table, p, y, Fz, options, recipe, check.families);
      add_to_statistics(point, options.against_exact, check, sums);
      if (progress) print_point(*progress, point);
      check.points.push_back(std::move(point));
    }
  }
  require(!check.points.empty(), "flextable check: no check point could be solved");
  check.mean_force_difference = sums.force_difference / static_cast<double>(sums.count);
  check.mean_force_difference_table_normalised = sums.table_normalised / static_cast<double>(sums.count);
  check.mean_table_error_against_exact /= static_cast<double>(sums.count);
  check.mean_on_the_fly_error_against_exact /= static_cast<double>(sums.count);
  return check;
}

}  // namespace railcontact::study
