// The main job: a case from patch to creep forces with every requested solver.
#include "case/case_run.hpp"

#include <chrono>
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <fmt/ostream.h>

#include "railcontact/tangential.hpp"
#include "railcontact/tangential_model.hpp"
#include "railcontact/contact_patch.hpp"
#include "railcontact/error.hpp"
#include "railcontact/hertz.hpp"
#include "railcontact/wheel_rail.hpp"

namespace railcontact {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

void summarise(const ContactPatch& patch, PatchSummary& s) {
  s.normal_force_N = patch.normal_force_N();
  s.area_m2 = patch.area_m2();
  s.elements_in_contact = patch.elements().count();
  s.n1 = patch.mesh().n1;
  s.n2 = patch.mesh().n2;
  s.dx1_m = patch.mesh().dx1_m;
  s.dx2_m = patch.mesh().dx2_m;
  double x1_min = 1e300, x1_max = -1e300, x2_min = 1e300, x2_max = -1e300;
  for (std::size_t e = 0; e < patch.elements().count(); ++e) {
    s.max_pressure_Pa = std::max(s.max_pressure_Pa, patch.pressure_Pa()[e]);
    x1_min = std::min(x1_min, patch.x1(e));
    x1_max = std::max(x1_max, patch.x1(e));
    x2_min = std::min(x2_min, patch.x2(e));
    x2_max = std::max(x2_max, patch.x2(e));
  }
  s.extent_x1_m = x1_max - x1_min + s.dx1_m;
  s.extent_x2_m = x2_max - x2_min + s.dx2_m;
}

// Elliptical Hertzian patch from the semi-axes or from the curvatures (Hertz).
ContactPatch elliptical_patch(const Case& c, PatchSummary& s) {
  double a = 0, b = 0;
  if (c.ellipse.a_m && c.ellipse.b_m) {
    a = *c.ellipse.a_m;
    b = *c.ellipse.b_m;
  } else {
    const HertzContact h = hertz_from_curvatures(*c.ellipse.A_per_m, *c.ellipse.B_per_m, c.normal_force_N, c.material);
    a = h.a_m;
    b = h.b_m;
  }
  require(a / b >= 0.01 && a / b <= 100,
          [&] { return fmt::format("{}: the ellipse's a/b = {} lies outside [0.01, 100]", c.source, a / b); });
  s.geometry = "ellipse";
  s.a_m = a;
  s.b_m = b;
  const ContactElements elements =
      elliptical_contact_with_count(a, b, c.target_elements, EllipseMeshLayout::rolling_resolved);
  return hertzian_patch(elements, a, b, c.normal_force_N, c.material);
}

// The profile pair of a wheel-rail case (the shipped one unless files are named).
WheelRailPair case_pair(const Case& c) {
  if (c.wheel_rail.wheel_file.empty() && c.wheel_rail.rail_file.empty()) return default_wheel_rail_pair();
  return load_wheel_rail_pair(
      c.wheel_rail.wheel_file.empty() ? default_wheel_profile_path() : std::filesystem::path(c.wheel_rail.wheel_file),
      c.wheel_rail.rail_file.empty() ? default_rail_profile_path() : std::filesystem::path(c.wheel_rail.rail_file));
}

// A flexibility table must belong to the case: its pair, material, nH-FastSim recipe (flexibility
// coarsening and collocation offset, as the case gives them), y and Fz. Each check names the table
// file, the field that differs and both values.
void check_table_fits(const FlexibilityTable& table, const Case& c, const WheelRailPair& pair) {
  table.check_profiles(pair);
  table.check_material(c.material, c.rolling.collocation_offset);
  table.check_recipe(c.flexibility_coarsening, c.rolling.collocation_offset);
  table.check_contact_reference(c.wheel_rail.reference);
  (void)table.lookup(c.wheel_rail.y_m, c.normal_force_N);  // range and gaps
}

// The wheel-rail patch of METHOD.md §9; [load] normal_force is the vertical wheel load Fz. With a
// flexibility table, its values for the patch are returned in `table_values`.
ContactPatch wheel_rail_patch(const Case& c, const WheelRailPair& pair, PatchSummary& s, const FlexibilityTable* table,
                              std::optional<FlexibilityTableValues>& table_values) {
  WheelRailPatchOptions options;
  options.vertical_load_N = c.normal_force_N;
  options.target_elements = c.target_elements;
  options.material = c.material;
  options.reference = c.wheel_rail.reference;
  const WheelRailPatch wr = solve_wheel_rail_patch(pair, c.wheel_rail.y_m, options);
  if (table != nullptr) table_values = table->lookup_for_patch(c.wheel_rail.y_m, c.normal_force_N, wr.area_m2);
  s.geometry = "wheel-rail";
  s.lateral_displacement_m = wr.lateral_displacement_m;
  s.contact_angle_rad = wr.contact_angle_rad;
  s.rolling_radius_m = wr.rolling_radius_m;
  s.spin_per_m = wr.spin_per_m;
  // The equivalent ellipse (classical FastSim on a non-elliptical patch, Eq 9).
  const std::array<double, 2> ab = equivalent_ellipse_semi_axes(wr.patch);
  s.a_m = ab[0];
  s.b_m = ab[1];
  return wr.patch;
}

// [a, b] contains x (false for NaN).
bool within(double x, double a, double b) { return x >= a && x <= b; }

// The case's values against the library's ranges, before any solve, each error naming the case
// key (docs/CASE_FILES.md), its value and the allowed range. The library checks the same ranges
// again (and names its own parameters) for callers of the API.
void check_values(const Case& input) {
  const std::string& file = input.source;
  const Material& m = input.material;
  require(within(m.youngs_modulus_Pa, kMinimumYoungsModulus_Pa, kMaximumYoungsModulus_Pa), [&] {
    return fmt::format("{}: [material] Young's modulus E = {:g} Pa (E, or 2 G (1 + nu) from G) must lie in [{:g}, {:g}] Pa",
                       file, m.youngs_modulus_Pa, kMinimumYoungsModulus_Pa, kMaximumYoungsModulus_Pa);
  });
  require(within(m.poisson_ratio, 0.0, 0.5), [&] {
    return fmt::format("{}: [material] nu = {:g} must lie in [0, 0.5]", file, m.poisson_ratio);
  });
  validate_normal_force(input.normal_force_N,
                        fmt::format("{}: [load] normal_force{}", file,
                                    input.geometry == GeometryKind::wheel_rail ? " (the vertical wheel load Fz)" : ""));
  require(input.mu > 0 && std::isfinite(input.mu),
          [&] { return fmt::format("{}: [friction] mu = {:g} must be positive", file, input.mu); });
  if (input.geometry == GeometryKind::ellipse) {
    // The ellipse's ranges (contact_patch.hpp, hertz.hpp) with its keys' names; the ellipse that
    // the curvatures give is checked by Hertz's solution, its message naming A, B, F3 and E.
    const EllipseGeometry& e = input.ellipse;
    if (e.a_m && e.b_m) {
      validate_semi_axis(*e.a_m, fmt::format("{}: [geometry] a", file));
      validate_semi_axis(*e.b_m, fmt::format("{}: [geometry] b", file));
      validate_ellipse(*e.a_m, *e.b_m, input.normal_force_N,
                       fmt::format("{}: [geometry] a = {:g} m and b = {:g} m", file, *e.a_m, *e.b_m));
    } else if (e.A_per_m && e.B_per_m) {
      validate_relative_curvature(*e.A_per_m, fmt::format("{}: [geometry] A", file));
      validate_relative_curvature(*e.B_per_m, fmt::format("{}: [geometry] B", file));
      try {
        (void)hertz_from_curvatures(*e.A_per_m, *e.B_per_m, input.normal_force_N, input.material);
      } catch (const Error& error) {
        throw Error(error.kind(), fmt::format("{}: [geometry] {}", file, error.what()));
      }
    }
  }
  if (input.geometry == GeometryKind::wheel_rail)
    require(input.target_elements >= kMinimumWheelRailElements && input.target_elements <= kMaximumWheelRailElements,
            [&] {
              return fmt::format("{}: [mesh] elements = {} must lie in [{}, {}] for a wheel-rail case (with fewer, the "
                                 "elements are too large for the patch and the profiles: the potential contact area "
                                 "reaches beyond the rail head, and the patch area is up to 15 % off)",
                                 file, input.target_elements, kMinimumWheelRailElements, kMaximumWheelRailElements);
            });
  const RollingOptions& r = input.rolling;
  require(within(r.collocation_offset, kMinimumCollocationOffset, 1.0), [&] {
    return fmt::format("{}: [solvers] alpha = {:g} must lie in [{:g}, 1] (closer to -1 the steady-rolling operator is "
                       "too ill-conditioned for the Krylov solver)",
                       file, r.collocation_offset, kMinimumCollocationOffset);
  });
  require(within(r.regularisation, kMinimumRegularisation, kMaximumRegularisation), [&] {
    return fmt::format("{}: [solvers] regularisation = {:g} must lie in [{:g}, {:g}] (a slip per unit rolling speed; "
                       "the paper uses 1e-08)",
                       file, r.regularisation, kMinimumRegularisation, kMaximumRegularisation);
  });
  require(r.tolerance > 0.0 && r.tolerance <= kMaximumRollingTolerance, [&] {
    return fmt::format("{}: [solvers] tolerance = {:g} must lie in (0, {:g}]", file, r.tolerance,
                       kMaximumRollingTolerance);
  });
}

void check_input(const Case& input, const FlexibilityTable* table) {
  validate_case(input);
  if (table != nullptr && input.geometry != GeometryKind::wheel_rail)
    throw Error(fmt::format("the {} applies to wheel-rail cases only ({} is an ellipse case)", table->name(), input.source));
}

// The contact patch (the ellipse, or the wheel-rail patch with the table's values for it) and its
// summary. A flexibility table is checked against the case before any solve.
void solve_patch(const Case& input, const FlexibilityTable* table, CaseResult& result, std::ostream* progress) {
  std::optional<WheelRailPair> pair;
  if (input.geometry == GeometryKind::wheel_rail) {
    pair = case_pair(input);
    if (table != nullptr) check_table_fits(*table, input, *pair);  // before any solve
  }
  if (progress) fmt::print(*progress, "  contact patch ...\n");
  result.patch = input.geometry == GeometryKind::ellipse
                     ? elliptical_patch(input, result.summary)
                     : wheel_rail_patch(input, *pair, result.summary, table, result.flexibility_table_values);
  summarise(result.patch, result.summary);
}

// The options of one tangential model for the case (railcontact/tangential_model.hpp).
TangentialModelOptions model_options(TangentialSolver kind, const Case& input, const CaseResult& result) {
  TangentialModelOptions o;
  o.solver = kind;
  o.nh_fastsim.bound = TractionBound{input.bound_skew, input.slip_direction};
  o.nh_fastsim.flexibility_coarsening = input.flexibility_coarsening;
  o.nh_fastsim.collocation_offset = input.rolling.collocation_offset;
  o.rolling = input.rolling;
  // Classical FastSim: the flexibilities of the ellipse, or the wheel-rail patch's equivalent one (Eq 9).
  o.ellipse_semi_axes_m = std::array<double, 2>{result.summary.a_m, result.summary.b_m};
  if (const std::optional<FlexibilityTableValues>& t = result.flexibility_table_values)
    o.given_flexibilities = NhFastSimFlexibilities{t->flexibility, t->f11_N, t->f22_N, t->f23_Nm, t->coupling};
  return o;
}

// nH-FastSim prepared once (its K2, or the table's flexibilities), if the normalisation or the
// nh-fastsim solver needs it, and the time its set-up took (it counts towards nh-fastsim's).
struct NhFastSimSetUp {
  std::optional<TangentialModel> model;  // the nh-fastsim solver's (per lobe on a wheel-rail patch of several)
  // The whole patch's nH-FastSim: K2 for the report and f11, f22 for the normalisation (the model's
  // own unless it runs per lobe).
  std::optional<NhFastSim> whole_patch;
  double time_s = 0.0;
  [[nodiscard]] const NhFastSim* whole() const {
    if (whole_patch) return &*whole_patch;
    return model ? model->nh_fastsim() : nullptr;
  }
};

NhFastSimSetUp set_up_nh_fastsim(const Case& input, CaseResult& result, std::ostream* progress) {
  const bool tabled = result.flexibility_table_values.has_value();
  const bool normalised = input.creepage.xi_normalised || input.creepage.eta_normalised;
  const bool wants_nh = std::find(input.solvers.begin(), input.solvers.end(), TangentialSolver::nh_fastsim) != input.solvers.end();
  NhFastSimSetUp setup;
  if (!normalised && !wants_nh) return setup;
  if (progress) *progress << (tabled ? "  nH-FastSim from the flexibility table ...\n" : "  creepage matrix K2 ...\n");
  const auto start = Clock::now();
  const TangentialModelOptions options = model_options(TangentialSolver::nh_fastsim, input, result);
  if (wants_nh) setup.model.emplace(result.patch, options);
  if (setup.whole() == nullptr) {
    if (options.given_flexibilities)
      setup.whole_patch.emplace(result.patch, *options.given_flexibilities, options.nh_fastsim);
    else
      setup.whole_patch.emplace(result.patch, options.nh_fastsim);
  }
  setup.time_s = seconds_since(start);
  result.creepage_matrix = setup.whole()->creepage_matrix();
  return setup;
}

// The raw creepages of the case: normalised ones (Eq 22-23) with f11, f22 of nH-FastSim's K2 (or
// the table's); spin from conicity (Eq 24).
void resolve_creepage(const Case& input, const NhFastSim* nh, CaseResult& result) {
  const bool normalised = input.creepage.xi_normalised || input.creepage.eta_normalised;
  const Creepage normalised_creepage = normalised ? nh->creepage_from_normalised(input.creepage.xi_normalised.value_or(0.0),
                                                                                input.creepage.eta_normalised.value_or(0.0),
                                                                                0.0, input.mu, result.patch.normal_force_N())
                                                  : Creepage{};
  if (input.creepage.xi_normalised) result.creepage.xi = normalised_creepage.xi;
  if (input.creepage.eta_normalised) result.creepage.eta = normalised_creepage.eta;
  if (input.creepage.phi_from_conicity) result.creepage.phi = result.summary.spin_per_m;
}

// One requested solver on the result's patch and creepages, timed (nh-fastsim: with its set-up,
// which is its flexibility time; the others' preparation is theirs).
SolverRun run_solver(TangentialSolver kind, const Case& input, const CaseResult& result, const NhFastSimSetUp& nh,
                     std::ostream* progress) {
  if (progress) fmt::print(*progress, "  {} ...\n", solver_name(kind));
  const auto start = Clock::now();
  const bool nh_fastsim = kind == TangentialSolver::nh_fastsim;
  const TangentialModel model = nh_fastsim ? *nh.model : TangentialModel(result.patch, model_options(kind, input, result));
  SolverRun run;
  run.kind = kind;
  run.flexibility_time_s = nh_fastsim ? nh.time_s : seconds_since(start);
  run.flexibility = model.flexibility();
  run.flexibility_source = nh_fastsim && result.flexibility_table_values ? std::string("table") : model.flexibility_source();
  TangentialSolution t = model.solve(result.creepage, input.mu, TangentialOutput::fields);
  run.forces = t.forces;
  // Newton's iterations for the exact solvers, K2's GMRES iterations for nh-fastsim.
  run.iterations = nh_fastsim ? model.preparation_krylov_iterations() : t.newton_iterations;
  run.krylov_iterations = t.krylov_iterations;
  run.p1_Pa = std::move(t.p1_Pa);
  run.p2_Pa = std::move(t.p2_Pa);
  run.slip = std::move(t.slip);
  run.adhesion_fraction = t.adhesion_fraction;
  run.time_s = seconds_since(start) + (nh_fastsim ? nh.time_s : 0.0);
  return run;
}

}  // namespace

void validate_case(const Case& input) {
  check_values(input);
  validate(input.material);  // the library's checks too (whatever a future key adds)
  validate(input.rolling);
}

const SolverRun* CaseResult::find(TangentialSolver kind) const {
  for (const SolverRun& run : runs)
    if (run.kind == kind) return &run;
  return nullptr;
}

CaseResult run_case(const Case& input, std::ostream* progress) { return run_case(input, CaseRunOptions{}, progress); }

CaseResult run_case(const Case& input, const CaseRunOptions& run_options, std::ostream* progress) {
  const FlexibilityTable* table = run_options.flexibility_table.get();
  check_input(input, table);
  CaseResult result{input, {}, {}, input.creepage.raw, std::nullopt, {}, std::nullopt, {}, 0};
  if (table != nullptr) {
    result.flexibility_table_file = table->source();
    result.flexibility_table_target_elements = table->metadata().target_elements;
  }
  solve_patch(input, table, result, progress);
  const NhFastSimSetUp nh = set_up_nh_fastsim(input, result, progress);
  resolve_creepage(input, nh.whole(), result);
  for (TangentialSolver kind : input.solvers) result.runs.push_back(run_solver(kind, input, result, nh, progress));
  return result;
}

Case default_case() {
  // The paper's set-up (METHOD.md §9): S1002 on UIC60 1:40, y = 0, Fz = 98.1 kN, E = 2.1e11 Pa,
  // nu = 0.3, mu = 0.3, xi' = eta' = 0.5, spin from conicity.
  Case c;
  c.source = "built-in default case (S1002 / UIC60, y = 0, xi' = eta' = 0.5, spin from conicity)";
  c.geometry = GeometryKind::wheel_rail;
  c.material = Material{2.1e11, 0.3};
  c.normal_force_N = 98100.0;
  c.mu = 0.3;
  c.creepage.xi_normalised = 0.5;
  c.creepage.eta_normalised = 0.5;
  c.creepage.phi_from_conicity = true;
  c.target_elements = 3000;
  return c;
}

}  // namespace railcontact
