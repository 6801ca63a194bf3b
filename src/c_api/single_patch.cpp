// The single-patch solver behind rc_solver (railcontact/railcontact.h, docs/C_API.md): settings,
// patch preparation (ellipse, Hertz, grid, wheel-rail patch of a flexibility table), evaluation
// with the four methods, the Jacobian by central differences.
#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "c_api/c_api_internal.hpp"
#include "railcontact/hertz.hpp"
#include "railcontact/kalker.hpp"
#include "railcontact/normal.hpp"
#include "railcontact/wheel_rail.hpp"

namespace railcontact::c_api {

rc_status status_of(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::invalid_input: return RC_INVALID_INPUT;
    case ErrorKind::no_contact: return RC_NO_CONTACT;
    case ErrorKind::several_patches: return RC_SEVERAL_PATCHES;
    case ErrorKind::not_converged: return RC_NOT_CONVERGED;
    case ErrorKind::io: return RC_IO;
    case ErrorKind::internal: return RC_INTERNAL;
  }
  return RC_INTERNAL;
}

rc_status copy_message(const std::string& message, char* buffer, std::size_t size, std::size_t* length) noexcept {
  if (length != nullptr) *length = message.size();
  if (size == 0) return message.empty() ? RC_OK : RC_BUFFER_TOO_SMALL;
  if (buffer == nullptr) return RC_INVALID_INPUT;
  const std::size_t n = std::min(size - 1, message.size());
  std::memcpy(buffer, message.data(), n);
  buffer[n] = '\0';
  return n < message.size() ? RC_BUFFER_TOO_SMALL : RC_OK;
}

namespace {

void check_range(double value, double low, double high, bool low_open, const char* field, const char* unit) {
  const bool ok = std::isfinite(value) && (low_open ? value > low : value >= low) && value <= high;
  require(ok, [&] {
    return fmt::format("rc_settings.{} = {}{} is outside {}{}, {}]{}", field, value, unit, low_open ? "(" : "[", low,
                       high, unit);
  });
}

void check_int(int value, int low, int high, const char* field) {
  require(value >= low && value <= high,
          [&] { return fmt::format("rc_settings.{} = {} is outside [{}, {}]", field, value, low, high); });
}

// Values of an rc_patch: finite, and the kind known.
void validate_patch(const rc_patch& p) {
  require(p.kind >= RC_GEOMETRY_ELLIPSE && p.kind <= RC_GEOMETRY_GRID,
          [&] { return fmt::format("rc_patch.kind = {} is not an rc_geometry (0 ellipse, 1 hertz, 2 grid)", p.kind); });
  require(std::isfinite(p.normal_force_N),
          [&] { return fmt::format("rc_patch.normal_force_N = {} is not finite", p.normal_force_N); });
  const auto finite_positive = [](double v, const char* field, const char* unit) {
    require(std::isfinite(v) && v > 0,
            [&] { return fmt::format("rc_patch.{} = {}{} must be positive and finite", field, v, unit); });
  };
  if (p.kind == RC_GEOMETRY_ELLIPSE) {
    validate_semi_axis(p.a_m, "rc_patch.a_m");
    validate_semi_axis(p.b_m, "rc_patch.b_m");
    // F3 is 0 for rc_solver_set_patch_at_approach: the axis ratio alone, the pressure once F3 is found.
    validate_ellipse(p.a_m, p.b_m, p.normal_force_N,
                     fmt::format("rc_patch.a_m = {:g} m and rc_patch.b_m = {:g} m", p.a_m, p.b_m));
  } else if (p.kind == RC_GEOMETRY_HERTZ) {
    validate_relative_curvature(p.A_per_m, "rc_patch.A_per_m");
    validate_relative_curvature(p.B_per_m, "rc_patch.B_per_m");
  } else {
    finite_positive(p.grid_dx1_m, "grid_dx1_m", " m");
    finite_positive(p.grid_dx2_m, "grid_dx2_m", " m");
    require(p.grid_n1 >= 2 && p.grid_n2 >= 2 && p.grid_n1 <= 4096 && p.grid_n2 <= 4096, [&] {
      return fmt::format("rc_patch: the grid has {} x {} elements; 2 to 4096 per axis are allowed", p.grid_n1,
                         p.grid_n2);
    });
    require(p.grid_h_m != nullptr, "rc_patch.grid_h_m is null: a grid needs its undeformed distances");
    const std::size_t n = static_cast<std::size_t>(p.grid_n1) * static_cast<std::size_t>(p.grid_n2);
    for (std::size_t k = 0; k < n; ++k)
      require(std::isfinite(p.grid_h_m[k]), [&] {
        return fmt::format("rc_patch.grid_h_m[{}] = {} m is not finite", k, p.grid_h_m[k]);
      });
  }
}

Material material_of(const rc_settings& s) { return Material{s.youngs_modulus_Pa, s.poisson_ratio}; }

RollingOptions rolling_options(const rc_settings& s) {
  RollingOptions o;
  o.collocation_offset = s.collocation_offset;
  o.tolerance = s.tolerance;
  o.max_newton_iterations = s.max_newton_iterations;
  o.krylov_tolerance = s.krylov_tolerance;
  o.max_krylov_iterations = s.max_krylov_iterations;
  o.regularisation = s.regularisation;
  return o;
}

// The elements of an ellipse with the settings' mesh.
ContactElements ellipse_elements(const rc_settings& s, double a, double b) {
  switch (s.mesh_mode) {
    case RC_MESH_ELEMENTS_IN_CONTACT:
      return elliptical_contact_with_count(a, b, static_cast<int>(std::lround(s.mesh_value)),
                                           EllipseMeshLayout::rolling_resolved);
    case RC_MESH_ELEMENTS_ACROSS:
      return elliptical_contact(a, b, static_cast<int>(std::lround(s.mesh_value)));
    default: {
      const double n1 = std::ceil(2 * a / s.mesh_value), n2 = std::ceil(2 * b / s.mesh_value);
      require(n1 >= 2 && n2 >= 2 && n1 * n2 <= 4e6, [&] {
        return fmt::format("rc_settings.mesh_value = {} m gives {} x {} elements over the ellipse's box "
                           "2a x 2b = {} x {} m; 2 per axis to 4e6 in all are allowed",
                           s.mesh_value, n1, n2, 2 * a, 2 * b);
      });
      return elliptical_contact(a, b, static_cast<int>(n1), static_cast<int>(n2));
    }
  }
}

// Largest pressure and the equivalent ellipse (same area, axis ratio of the patch's extents).
void describe_patch(const ContactPatch& patch, rc_normal_result& n, double& a_eq, double& b_eq) {
  const Mesh& mesh = patch.mesh();
  double p_max = 0;
  for (std::size_t e = 0; e < patch.elements().count(); ++e) p_max = std::max(p_max, patch.pressure_Pa()[e]);
  n.normal_force_N = patch.normal_force_N();
  n.area_m2 = patch.area_m2();
  n.max_pressure_Pa = p_max;
  n.dx1_m = mesh.dx1_m;
  n.dx2_m = mesh.dx2_m;
  n.x1_first_m = mesh.x1_first_m;
  n.x2_first_m = mesh.x2_first_m;
  n.n1 = mesh.n1;
  n.n2 = mesh.n2;
  n.elements_in_contact = static_cast<int>(patch.elements().count());
  const std::array<double, 2> ab = equivalent_ellipse_semi_axes(patch);
  a_eq = ab[0];
  b_eq = ab[1];
}

// The settings' tangential model on a patch whose normal results are set (and, from a flexibility
// table, its given flexibilities).
void prepare_method(const rc_settings& s, PreparedPatch& p) {
  TangentialModelOptions o;
  o.solver = method_of(s.method, "rc_settings.method");
  o.nh_fastsim.bound.skew = s.bound_skew;
  o.nh_fastsim.bound.slip_direction = slip_direction_of(s.slip_direction);
  o.nh_fastsim.flexibility_coarsening = s.flexibility_coarsening;
  o.nh_fastsim.collocation_offset = s.collocation_offset;
  o.given_flexibilities = p.given;
  o.ellipse_semi_axes_m = std::array<double, 2>{p.a_m, p.b_m};
  o.rolling = rolling_options(s);
  p.model.emplace(p.patch, o);
}

}  // namespace

TangentialSolver method_of(int value, std::string_view field) {
  static_assert(RC_METHOD_NH_FASTSIM == static_cast<int>(TangentialSolver::nh_fastsim) &&
                RC_METHOD_FASTSIM == static_cast<int>(TangentialSolver::fastsim) &&
                RC_METHOD_EXACT == static_cast<int>(TangentialSolver::exact) &&
                RC_METHOD_EXACT_REGULARISED == static_cast<int>(TangentialSolver::exact_regularised));
  return tangential_solver_of(value, field, "an rc_method");
}

SlipDirection slip_direction_of(int value, const char* structure) {
  switch (value) {
    case RC_SLIP_RADIAL: return SlipDirection::radial;
    case RC_SLIP_FLEXIBILITY_WEIGHTED: return SlipDirection::flexibility_weighted;
    case RC_SLIP_RIGID: return SlipDirection::rigid_slip;
    case RC_SLIP_ELASTIC: return SlipDirection::elastic_slip;
    default: break;
  }
  throw Error(fmt::format("{}.slip_direction = {} is not an rc_slip_direction (0 radial, 1 flexibility-weighted, "
                          "2 rigid-slip, 3 elastic-slip)",
                          structure, value));
}

void validate_settings(const rc_settings& s) {
  check_range(s.youngs_modulus_Pa, kMinimumYoungsModulus_Pa, kMaximumYoungsModulus_Pa, false, "youngs_modulus_Pa",
              " Pa");
  check_range(s.poisson_ratio, 0.0, 0.5, false, "poisson_ratio", "");
  check_range(s.friction_coefficient, 0.0, 10.0, true, "friction_coefficient", "");
  method_of(s.method, "rc_settings.method");
  switch (s.mesh_mode) {
    case RC_MESH_ELEMENTS_IN_CONTACT: check_range(s.mesh_value, 10, 1e6, false, "mesh_value", " elements in contact"); break;
    case RC_MESH_ELEMENTS_ACROSS: check_range(s.mesh_value, 2, 2000, false, "mesh_value", " elements across"); break;
    case RC_MESH_ELEMENT_SIZE: check_range(s.mesh_value, 0.0, 1.0, true, "mesh_value", " m (element size)"); break;
    default:
      throw Error(fmt::format("rc_settings.mesh_mode = {} is not an rc_mesh_mode (0 elements in contact, "
                              "1 elements across, 2 element size)",
                              s.mesh_mode));
  }
  check_range(s.bound_skew, 0.0, 1.0, false, "bound_skew", "");
  check_int(s.flexibility_coarsening, 0, kMaximumCoarsening, "flexibility_coarsening");
  slip_direction_of(s.slip_direction);
  check_range(s.collocation_offset, kMinimumCollocationOffset, 1.0, false, "collocation_offset", "");
  check_range(s.normal_tolerance, 0.0, 1e-2, true, "normal_tolerance", "");
  check_int(s.normal_max_iterations, 1, 1000000, "normal_max_iterations");
  check_range(s.jacobian_step_creepage, 1e-10, 1e-2, false, "jacobian_step_creepage", "");
  check_range(s.jacobian_step_spin_per_m, 1e-8, 1.0, false, "jacobian_step_spin_per_m", " 1/m");
  // The exact solvers' options: railcontact's own check names the RollingOptions field; NaN first.
  for (const double v : {s.tolerance, s.krylov_tolerance, s.regularisation})
    require(std::isfinite(v), [&] { return fmt::format("rc_settings: an exact solver option is {}", v); });
  validate(rolling_options(s));
}

bool PatchKey::operator==(const PatchKey& o) const {
  return by_approach == o.by_approach && approach_m == o.approach_m && patch.kind == o.patch.kind && patch.normal_force_N == o.patch.normal_force_N && patch.a_m == o.patch.a_m &&
         patch.b_m == o.patch.b_m && patch.A_per_m == o.patch.A_per_m && patch.B_per_m == o.patch.B_per_m &&
         patch.grid_dx1_m == o.patch.grid_dx1_m && patch.grid_dx2_m == o.patch.grid_dx2_m &&
         patch.grid_n1 == o.patch.grid_n1 && patch.grid_n2 == o.patch.grid_n2 && h_m == o.h_m;
}

PatchKey SinglePatchSolver::key_of(const rc_patch& patch) {
  PatchKey key;
  key.patch = patch;
  key.patch.grid_h_m = nullptr;
  if (patch.kind == RC_GEOMETRY_GRID)
    key.h_m.assign(patch.grid_h_m,
                   patch.grid_h_m + static_cast<std::size_t>(patch.grid_n1) * static_cast<std::size_t>(patch.grid_n2));
  else
    key.patch.grid_n1 = key.patch.grid_n2 = 0;
  return key;
}

SinglePatchSolver::SinglePatchSolver() { rc_settings_default(&settings_); }

void SinglePatchSolver::set_settings(const rc_settings& s) {
  validate_settings(s);
  const rc_settings& o = settings_;
  const bool same_preparation =
      s.youngs_modulus_Pa == o.youngs_modulus_Pa && s.poisson_ratio == o.poisson_ratio && s.method == o.method &&
      s.mesh_mode == o.mesh_mode && s.mesh_value == o.mesh_value && s.bound_skew == o.bound_skew &&
      s.slip_direction == o.slip_direction && s.flexibility_coarsening == o.flexibility_coarsening && s.collocation_offset == o.collocation_offset &&
      s.normal_tolerance == o.normal_tolerance && s.normal_max_iterations == o.normal_max_iterations;
  // The exact solvers' options enter their model only: the prepared patch keeps its normal solution
  // and the exact model is prepared again (nH-FastSim's and FastSim's models do not use them).
  const bool same_rolling = s.tolerance == o.tolerance && s.max_newton_iterations == o.max_newton_iterations &&
                            s.krylov_tolerance == o.krylov_tolerance &&
                            s.max_krylov_iterations == o.max_krylov_iterations && s.regularisation == o.regularisation;
  settings_ = s;
  if (!same_preparation) {
    prepared_.reset();
    key_.reset();
    last_.reset();
  } else if (!same_rolling && prepared_ && (s.method == RC_METHOD_EXACT || s.method == RC_METHOD_EXACT_REGULARISED)) {
    auto p = std::make_shared<PreparedPatch>(*prepared_);
    prepare_method(s, *p);
    prepared_ = std::move(p);
    last_.reset();
  }
}

std::shared_ptr<const PreparedPatch> SinglePatchSolver::prepare(const rc_settings& s, const rc_patch& patch,
                                                                const double* approach_m) {
  validate_patch(patch);
  const Material material = material_of(s);
  auto p = std::make_shared<PreparedPatch>();
  rc_normal_result& n = p->normal;
  double a_eq = 0, b_eq = 0;
  if (patch.kind == RC_GEOMETRY_GRID) {
    // The grid centred on the origin (the patch is re-centred on its pressure centre anyway).
    Mesh mesh;
    mesh.n1 = patch.grid_n1;
    mesh.n2 = patch.grid_n2;
    mesh.dx1_m = patch.grid_dx1_m;
    mesh.dx2_m = patch.grid_dx2_m;
    mesh.x1_first_m = -0.5 * (patch.grid_n1 - 1) * patch.grid_dx1_m;
    mesh.x2_first_m = -0.5 * (patch.grid_n2 - 1) * patch.grid_dx2_m;
    validate(mesh);
    const std::vector<double> h(patch.grid_h_m, patch.grid_h_m + mesh.size());
    NormalOptions options;
    options.tolerance = s.normal_tolerance;
    options.max_iterations = s.normal_max_iterations;
    GridPatch grid = approach_m != nullptr
                         ? single_grid_patch_at_approach(mesh, h, *approach_m, material, options, "rc_patch grid")
                         : single_grid_patch(mesh, h, patch.normal_force_N, material, options, "rc_patch grid");
    p->patch = std::move(grid.patch);
    const NormalSolution& normal = grid.normal;
    describe_patch(p->patch, n, a_eq, b_eq);
    n.approach_m = normal.approach_m;
    p->a_m = a_eq;
    p->b_m = b_eq;
  } else {
    double a = patch.a_m, b = patch.b_m, approach = 0;
    if (patch.kind == RC_GEOMETRY_HERTZ) {
      validate_normal_force(patch.normal_force_N, "rc_patch.normal_force_N");
      const HertzContact h = hertz_from_curvatures(patch.A_per_m, patch.B_per_m, patch.normal_force_N, material);
      a = h.a_m;
      b = h.b_m;
      approach = h.approach_m;
    } else {
      validate(material);
      validate_normal_force(patch.normal_force_N, "rc_patch.normal_force_N");
      approach = hertz_from_semi_axes(a, b, patch.normal_force_N, material).approach_m;
    }
    p->patch = hertzian_patch(ellipse_elements(s, a, b), a, b, patch.normal_force_N, material);
    describe_patch(p->patch, n, a_eq, b_eq);
    n.approach_m = approach;
    p->a_m = a;
    p->b_m = b;
  }
  n.a_m = p->a_m;
  n.b_m = p->b_m;
  prepare_method(s, *p);
  return p;
}

std::shared_ptr<const PreparedPatch> SinglePatchSolver::prepare_wheel_rail(const rc_settings& s,
                                                                           const FlexibilityTableFastSim& table,
                                                                           double y_m, double vertical_load_N) {
  require(std::isfinite(y_m) && std::isfinite(vertical_load_N), [&] {
    return fmt::format("flexibility table patch: y = {} m and Fz = {} N must be finite", y_m, vertical_load_N);
  });
  table.table().check_material(material_of(s), s.collocation_offset);
  const FlexibilityTableFastSim::Patch prepared = table.prepare(y_m, vertical_load_N);
  const WheelRailPatch& wr = prepared.wheel_rail_patch();
  auto p = std::make_shared<PreparedPatch>();
  p->patch = wr.patch;
  double a_eq = 0, b_eq = 0;
  describe_patch(p->patch, p->normal, a_eq, b_eq);
  p->normal.approach_m = wr.approach_m;
  p->normal.contact_angle_rad = wr.contact_angle_rad;
  p->normal.spin_per_m = wr.spin_per_m;
  p->a_m = p->normal.a_m = a_eq;
  p->b_m = p->normal.b_m = b_eq;
  const FlexibilityTableValues& v = prepared.table_values();
  p->given = NhFastSimFlexibilities{v.flexibility, v.f11_N, v.f22_N, v.f23_Nm, v.coupling};
  prepare_method(s, *p);
  return p;
}

void SinglePatchSolver::set_patch(const rc_patch& patch) {
  validate_patch(patch);
  PatchKey key = key_of(patch);
  if (prepared_ && key_ && *key_ == key) return;
  prepared_.reset();
  key_.reset();
  last_.reset();
  prepared_ = prepare(settings_, patch);
  key_ = std::move(key);
}

void SinglePatchSolver::set_patch_at_approach(const rc_patch& given, double approach_m) {
  rc_patch patch = given;
  patch.normal_force_N = 0.0;  // ignored: F3 follows from the approach
  validate_patch(patch);
  require(std::isfinite(approach_m), [&] { return fmt::format("approach_m = {} m is not finite", approach_m); });
  if (patch.kind != RC_GEOMETRY_GRID) {
    // Hertz: for fixed curvatures the approach grows as F3^(2/3); for fixed semi-axes a, b it is
    // proportional to F3. The load at the approach follows from one reference solution.
    require(approach_m > 0.0, [&] {
      return fmt::format("approach_m = {} m must be positive for an ellipse or a Hertz patch", approach_m);
    });
    const Material material = material_of(settings_);
    validate(material);
    constexpr double reference_N = 1e5;
    double force = 0.0;
    if (patch.kind == RC_GEOMETRY_HERTZ) {
      const double reference =
          hertz_from_curvatures(patch.A_per_m, patch.B_per_m, reference_N, material).approach_m;
      force = reference_N * std::pow(approach_m / reference, 1.5);
    } else {
      const double reference = hertz_from_semi_axes(patch.a_m, patch.b_m, reference_N, material).approach_m;
      force = reference_N * approach_m / reference;
    }
    validate_normal_force(force, fmt::format("rc_patch at approach {} m: the normal force found", approach_m));
    patch.normal_force_N = force;
    set_patch(patch);
    return;
  }
  PatchKey key = key_of(patch);
  key.by_approach = true;
  key.approach_m = approach_m;
  if (prepared_ && key_ && *key_ == key) return;
  prepared_.reset();
  key_.reset();
  last_.reset();
  prepared_ = prepare(settings_, patch, &approach_m);
  key_ = std::move(key);
}

void SinglePatchSolver::set_prepared(std::shared_ptr<const PreparedPatch> prepared, std::optional<PatchKey> key) {
  prepared_ = std::move(prepared);
  key_ = std::move(key);
  last_.reset();
}

std::shared_ptr<const PreparedPatch> SinglePatchSolver::prepared_for(const rc_patch& patch) const {
  if (!prepared_ || !key_) return nullptr;
  validate_patch(patch);
  return *key_ == key_of(patch) ? prepared_ : nullptr;
}

const PreparedPatch& SinglePatchSolver::require_patch() const {
  if (!prepared_) throw Error("no contact patch is set (rc_solver_set_patch or rc_solver_set_patch_flextable first)");
  return *prepared_;
}

Evaluation SinglePatchSolver::evaluate(const rc_creepage& c, bool with_fields) const {
  const PreparedPatch& p = require_patch();
  require(std::isfinite(c.xi) && std::isfinite(c.eta) && std::isfinite(c.phi_per_m), [&] {
    return fmt::format("rc_creepage (xi = {}, eta = {}, phi = {} 1/m) must be finite", c.xi, c.eta, c.phi_per_m);
  });
  const Creepage creepage{c.xi, c.eta, c.phi_per_m};
  const double mu = settings_.friction_coefficient;
  Evaluation e;
  e.creepage = c;
  const auto take = [&e](const TangentialForces& f, double adhesion) {
    e.forces.F1_N = f.F1_N;
    e.forces.F2_N = f.F2_N;
    e.forces.M3_Nm = f.M3_Nm;
    e.forces.adhesion_fraction = adhesion;
  };
  // FastSim marches without per-element output unless the fields are wanted (half the cost,
  // docs/BENCHMARKS.md "Python and C API overhead"); the exact solvers give them always.
  TangentialSolution t = p.model->solve(creepage, mu, with_fields ? TangentialOutput::fields : TangentialOutput::forces);
  take(t.forces, t.adhesion_fraction);
  e.has_fields = with_fields || !t.p1_Pa.empty();
  e.p1_Pa = std::move(t.p1_Pa);
  e.p2_Pa = std::move(t.p2_Pa);
  e.slip = std::move(t.slip);
  return e;
}

// The caller's creepages in the range of a contact (validate_creepage), before any solve; the
// Jacobian's differences may step past the range by their step.
static void validate_creepage(const rc_creepage& c) {
  railcontact::validate_creepage(Creepage{c.xi, c.eta, c.phi_per_m}, "rc_creepage", "phi_per_m");
}

rc_forces SinglePatchSolver::solve(const rc_creepage& creepage) {
  validate_creepage(creepage);
  last_.reset();
  last_ = evaluate(creepage, false);
  return last_->forces;
}

rc_forces SinglePatchSolver::jacobian(const rc_creepage& c, double J[9]) {
  validate_creepage(c);
  const double steps[3] = {settings_.jacobian_step_creepage, settings_.jacobian_step_creepage,
                           settings_.jacobian_step_spin_per_m};
  last_.reset();
  for (int j = 0; j < 3; ++j) {
    rc_creepage plus = c, minus = c;
    double* const plus_value[3] = {&plus.xi, &plus.eta, &plus.phi_per_m};
    double* const minus_value[3] = {&minus.xi, &minus.eta, &minus.phi_per_m};
    *plus_value[j] += steps[j];
    *minus_value[j] -= steps[j];
    const rc_forces fp = evaluate(plus, false).forces, fm = evaluate(minus, false).forces;
    const double h2 = *plus_value[j] - *minus_value[j];  // the step as represented
    J[0 * 3 + j] = (fp.F1_N - fm.F1_N) / h2;
    J[1 * 3 + j] = (fp.F2_N - fm.F2_N) / h2;
    J[2 * 3 + j] = (fp.M3_Nm - fm.M3_Nm) / h2;
  }
  return solve(c);
}

const Evaluation& SinglePatchSolver::last() const {
  (void)require_patch();
  if (!last_) throw Error("no creepages have been solved on this patch yet (rc_solver_solve first)");
  return *last_;
}

const Evaluation& SinglePatchSolver::last_with_fields() const {
  const Evaluation& e = last();
  if (!e.has_fields) last_ = evaluate(e.creepage, true);
  return *last_;
}

}  // namespace railcontact::c_api
