// The C API's functions (include/railcontact/railcontact.h, docs/C_API.md): each checks its
// pointers, runs under `guarded` (no exception crosses the boundary) and returns a status.
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <thread>

#include "c_api/c_api_internal.hpp"
#include "railcontact/wheel_rail.hpp"

using railcontact::Error;
using railcontact::ErrorKind;
using railcontact::require;
using railcontact::c_api::guarded;
using railcontact::c_api::LastError;
using railcontact::c_api::PatchKey;
using railcontact::c_api::PreparedPatch;
using railcontact::c_api::SinglePatchSolver;
using railcontact::c_api::StatusError;

namespace {

void require_pointer(const void* pointer, const char* what) {
  if (pointer == nullptr) throw Error(fmt::format("{} is null", what));
}

// Batch: a contiguous range of states on one worker (its own solver with the caller's settings).
struct BatchJob {
  const rc_patch* patches = nullptr;
  std::size_t patch_count = 0;
  const rc_creepage* creepages = nullptr;
  rc_forces* forces = nullptr;
  rc_normal_result* normal = nullptr;
  double* jacobians = nullptr;
  std::vector<rc_status>* statuses = nullptr;
  std::vector<std::string>* messages = nullptr;
};

void run_batch_range(const rc_settings& settings, const std::shared_ptr<const PreparedPatch>& shared,
                     const BatchJob& job, std::size_t begin, std::size_t end) noexcept {
  SinglePatchSolver worker;
  LastError error;
  const rc_status made = guarded(&error, [&] {
    worker.set_settings(settings);
    if (shared) worker.set_prepared(shared, SinglePatchSolver::key_of(job.patches[0]));
  });
  for (std::size_t k = begin; k < end; ++k) {
    rc_status status = made;
    if (status == RC_OK) {
      status = guarded(&error, [&] {
        if (!shared) worker.set_patch(job.patches[job.patch_count == 1 ? 0 : k]);
        if (job.jacobians != nullptr)
          job.forces[k] = worker.jacobian(job.creepages[k], job.jacobians + 9 * k);
        else
          job.forces[k] = worker.solve(job.creepages[k]);
        if (job.normal != nullptr) job.normal[k] = worker.require_patch().normal;
      });
    }
    (*job.statuses)[k] = status;
    if (status != RC_OK) {
      try {
        (*job.messages)[k] = error.message();
      } catch (...) {
      }
    }
  }
}

}  // namespace

extern "C" {

const char* rc_status_string(int status) {
  switch (status) {
    case RC_OK: return "ok";
    case RC_INVALID_INPUT: return "invalid input";
    case RC_NO_CONTACT: return "no contact";
    case RC_SEVERAL_PATCHES: return "several contact patches";
    case RC_NOT_CONVERGED: return "not converged";
    case RC_IO: return "input/output";
    case RC_INTERNAL: return "internal error";
    case RC_OUT_OF_MEMORY: return "out of memory";
    case RC_BUFFER_TOO_SMALL: return "buffer too small";
    case RC_CANCELLED: return "cancelled";
    default: return "unknown status";
  }
}

const char* rc_version_string(void) { return RC_VERSION_STRING; }

rc_status rc_version(int* major, int* minor, int* patch) {
  if (major != nullptr) *major = RC_VERSION_MAJOR;
  if (minor != nullptr) *minor = RC_VERSION_MINOR;
  if (patch != nullptr) *patch = RC_VERSION_PATCH;
  return RC_OK;
}

int rc_abi_version(void) { return RC_ABI_VERSION; }

rc_status rc_settings_default(rc_settings* s) {
  if (s == nullptr) return RC_INVALID_INPUT;
  *s = rc_settings{};
  s->youngs_modulus_Pa = 2.1e11;
  s->poisson_ratio = 0.3;
  s->friction_coefficient = 0.3;
  s->mesh_value = 2800;
  s->bound_skew = railcontact::TractionBound{}.skew;
  s->collocation_offset = 0.0;
  const railcontact::RollingOptions rolling;
  s->tolerance = rolling.tolerance;
  s->krylov_tolerance = rolling.krylov_tolerance;
  s->regularisation = rolling.regularisation;
  const railcontact::NormalOptions normal;
  s->normal_tolerance = normal.tolerance;
  s->jacobian_step_creepage = 1e-6;
  s->jacobian_step_spin_per_m = 1e-4;
  s->method = RC_METHOD_NH_FASTSIM;
  s->mesh_mode = RC_MESH_ELEMENTS_IN_CONTACT;
  s->flexibility_coarsening = 0;
  s->slip_direction = RC_SLIP_RADIAL;  // NhFastSimOptions' (TractionBound's) default
  s->max_newton_iterations = rolling.max_newton_iterations;
  s->max_krylov_iterations = rolling.max_krylov_iterations;
  s->normal_max_iterations = normal.max_iterations;
  return RC_OK;
}

// ---- Solver ---------------------------------------------------------------------------------

rc_status rc_solver_create(rc_solver** solver) { return railcontact::c_api::create_handle(solver); }

rc_status rc_solver_destroy(rc_solver* solver) {
  delete solver;
  return RC_OK;
}

rc_status rc_solver_last_error(const rc_solver* solver, char* buffer, size_t size, size_t* length) {
  return railcontact::c_api::last_error(solver, buffer, size, length);
}

rc_status rc_solver_set_settings(rc_solver* solver, const rc_settings* settings) {
  if (solver == nullptr) return RC_INVALID_INPUT;
  return guarded(&solver->error, [&] {
    require_pointer(settings, "rc_solver_set_settings: settings");
    solver->solver.set_settings(*settings);
  });
}

rc_status rc_solver_get_settings(const rc_solver* solver, rc_settings* settings) {
  if (solver == nullptr || settings == nullptr) return RC_INVALID_INPUT;
  *settings = solver->solver.settings();
  return RC_OK;
}

rc_status rc_solver_set_patch(rc_solver* solver, const rc_patch* patch) {
  if (solver == nullptr) return RC_INVALID_INPUT;
  return guarded(&solver->error, [&] {
    require_pointer(patch, "rc_solver_set_patch: patch");
    solver->solver.set_patch(*patch);
  });
}

rc_status rc_solver_set_patch_at_approach(rc_solver* solver, const rc_patch* patch, double approach_m) {
  if (solver == nullptr) return RC_INVALID_INPUT;
  return guarded(&solver->error, [&] {
    require_pointer(patch, "rc_solver_set_patch_at_approach: patch");
    solver->solver.set_patch_at_approach(*patch, approach_m);
  });
}

rc_status rc_solver_set_ellipse(rc_solver* solver, double a_m, double b_m, double normal_force_N) {
  rc_patch patch{};
  patch.kind = RC_GEOMETRY_ELLIPSE;
  patch.a_m = a_m;
  patch.b_m = b_m;
  patch.normal_force_N = normal_force_N;
  return rc_solver_set_patch(solver, &patch);
}

rc_status rc_solver_set_hertz(rc_solver* solver, double A_per_m, double B_per_m, double normal_force_N) {
  rc_patch patch{};
  patch.kind = RC_GEOMETRY_HERTZ;
  patch.A_per_m = A_per_m;
  patch.B_per_m = B_per_m;
  patch.normal_force_N = normal_force_N;
  return rc_solver_set_patch(solver, &patch);
}

rc_status rc_solver_set_grid(rc_solver* solver, int n1, int n2, double dx1_m, double dx2_m, const double* h_m,
                             double normal_force_N) {
  rc_patch patch{};
  patch.kind = RC_GEOMETRY_GRID;
  patch.grid_n1 = n1;
  patch.grid_n2 = n2;
  patch.grid_dx1_m = dx1_m;
  patch.grid_dx2_m = dx2_m;
  patch.grid_h_m = h_m;
  patch.normal_force_N = normal_force_N;
  return rc_solver_set_patch(solver, &patch);
}

rc_status rc_solver_normal_result(const rc_solver* solver, rc_normal_result* result) {
  if (solver == nullptr) return RC_INVALID_INPUT;
  return guarded(&solver->error, [&] {
    require_pointer(result, "rc_solver_normal_result: result");
    *result = solver->solver.require_patch().normal;
  });
}

rc_status rc_solver_solve(rc_solver* solver, const rc_creepage* creepage, rc_forces* forces) {
  if (solver == nullptr) return RC_INVALID_INPUT;
  return guarded(&solver->error, [&] {
    require_pointer(creepage, "rc_solver_solve: creepage");
    require_pointer(forces, "rc_solver_solve: forces");
    *forces = solver->solver.solve(*creepage);
  });
}

rc_status rc_creep_forces(rc_solver* solver, const rc_patch* patch, const rc_creepage* creepage, rc_forces* forces,
                          rc_normal_result* normal) {
  if (solver == nullptr) return RC_INVALID_INPUT;
  return guarded(&solver->error, [&] {
    require_pointer(patch, "rc_creep_forces: patch");
    require_pointer(creepage, "rc_creep_forces: creepage");
    require_pointer(forces, "rc_creep_forces: forces");
    solver->solver.set_patch(*patch);
    *forces = solver->solver.solve(*creepage);
    if (normal != nullptr) *normal = solver->solver.require_patch().normal;
  });
}

rc_status rc_solver_jacobian(rc_solver* solver, const rc_creepage* creepage, rc_forces* forces, double jacobian[9]) {
  if (solver == nullptr) return RC_INVALID_INPUT;
  return guarded(&solver->error, [&] {
    require_pointer(creepage, "rc_solver_jacobian: creepage");
    require_pointer(jacobian, "rc_solver_jacobian: jacobian");
    const rc_forces f = solver->solver.jacobian(*creepage, jacobian);
    if (forces != nullptr) *forces = f;
  });
}

rc_status rc_solver_traction_size(const rc_solver* solver, int* n1, int* n2, size_t* count) {
  if (solver == nullptr) return RC_INVALID_INPUT;
  return guarded(&solver->error, [&] {
    const rc_normal_result& n = solver->solver.require_patch().normal;
    if (n1 != nullptr) *n1 = n.n1;
    if (n2 != nullptr) *n2 = n.n2;
    if (count != nullptr) *count = static_cast<size_t>(n.n1) * static_cast<size_t>(n.n2);
  });
}

rc_status rc_solver_tractions(const rc_solver* solver, size_t size, double* p1_Pa, double* p2_Pa, double* p3_Pa,
                              int* slip) {
  if (solver == nullptr) return RC_INVALID_INPUT;
  return guarded(&solver->error, [&] {
    const PreparedPatch& p = solver->solver.require_patch();
    const railcontact::c_api::Evaluation& e = solver->solver.last_with_fields();
    const std::size_t n = p.patch.mesh().size();
    if (size < n)
      throw StatusError{RC_BUFFER_TOO_SMALL,
                        fmt::format("rc_solver_tractions: the buffers hold {} values; the patch's mesh has {} x {} = {} "
                                    "(rc_solver_traction_size)",
                                    size, p.normal.n1, p.normal.n2, n)};
    if (p1_Pa != nullptr) std::fill(p1_Pa, p1_Pa + n, 0.0);
    if (p2_Pa != nullptr) std::fill(p2_Pa, p2_Pa + n, 0.0);
    if (p3_Pa != nullptr) std::fill(p3_Pa, p3_Pa + n, 0.0);
    if (slip != nullptr) std::fill(slip, slip + n, 0);
    const std::vector<std::size_t>& indices = p.patch.elements().indices();
    for (std::size_t e_index = 0; e_index < indices.size(); ++e_index) {
      const std::size_t k = indices[e_index];
      if (p1_Pa != nullptr) p1_Pa[k] = e.p1_Pa[e_index];
      if (p2_Pa != nullptr) p2_Pa[k] = e.p2_Pa[e_index];
      if (p3_Pa != nullptr) p3_Pa[k] = p.patch.pressure_Pa()[e_index];
      if (slip != nullptr) slip[k] = e.slip[e_index] != 0 ? 1 : 0;
    }
  });
}

rc_status rc_batch_creep_forces(rc_solver* solver, size_t count, const rc_patch* patches, size_t patch_count,
                                const rc_creepage* creepages, int threads, rc_forces* forces, rc_normal_result* normal,
                                double* jacobians, int* statuses) {
  if (solver == nullptr) return RC_INVALID_INPUT;
  rc_status first_failure = RC_OK;
  const rc_status status = guarded(&solver->error, [&] {
    if (count == 0) return;
    require(count <= RC_MAX_BATCH_STATES, [&] {
      return fmt::format("rc_batch_creep_forces: count = {} states; at most RC_MAX_BATCH_STATES = {}", count,
                         RC_MAX_BATCH_STATES);
    });
    require_pointer(patches, "rc_batch_creep_forces: patches");
    require_pointer(creepages, "rc_batch_creep_forces: creepages");
    require_pointer(forces, "rc_batch_creep_forces: forces");
    if (patch_count != 1 && patch_count != count)
      throw Error(fmt::format("rc_batch_creep_forces: patch_count = {} must be 1 (one patch for all states) or count "
                              "= {}",
                              patch_count, count));
    if (threads < 0) throw Error(fmt::format("rc_batch_creep_forces: threads = {} must be >= 0", threads));
    std::size_t workers = threads == 0 ? std::max(1u, std::thread::hardware_concurrency()) : static_cast<std::size_t>(threads);
    workers = std::min({workers, count, std::size_t{1024}});
    const rc_settings settings = solver->solver.settings();
    // One patch for all: prepared once here, shared by the workers (its solvers only read it).
    std::shared_ptr<const PreparedPatch> shared;
    std::vector<rc_status> state_status(count, RC_OK);
    std::vector<std::string> messages(count);
    if (patch_count == 1) {
      LastError error;
      // The solver's own patch when it is this one (prepared with these settings), else a new one.
      const rc_status made = guarded(&error, [&] {
        shared = solver->solver.prepared_for(patches[0]);
        if (!shared) shared = SinglePatchSolver::prepare(settings, patches[0]);
      });
      if (made != RC_OK) {
        std::fill(state_status.begin(), state_status.end(), made);
        std::fill(messages.begin(), messages.end(), error.message());
      }
    }
    const BatchJob job{patches, patch_count, creepages, forces, normal, jacobians, &state_status, &messages};
    if (patch_count != 1 || shared) {
      std::vector<std::thread> pool;
      const std::size_t chunk = (count + workers - 1) / workers;
      for (std::size_t w = 1; w < workers && w * chunk < count; ++w)
        pool.emplace_back(run_batch_range, std::cref(settings), std::cref(shared), std::cref(job), w * chunk,
                          std::min(count, (w + 1) * chunk));
      run_batch_range(settings, shared, job, 0, std::min(count, chunk));
      for (std::thread& t : pool) t.join();
    }
    for (std::size_t k = 0; k < count; ++k) {
      if (statuses != nullptr) statuses[k] = state_status[k];
      if (state_status[k] != RC_OK && first_failure == RC_OK) {
        first_failure = state_status[k];
        solver->error.set(fmt::format("state {}: {}", k, messages[k]).c_str());
      }
    }
  });
  return status != RC_OK ? status : first_failure;
}

// ---- Flexibility table ---------------------------------------------------------------------

rc_status rc_flextable_create(rc_flextable** table) { return railcontact::c_api::create_handle(table); }

rc_status rc_flextable_destroy(rc_flextable* table) {
  delete table;
  return RC_OK;
}

rc_status rc_flextable_last_error(const rc_flextable* table, char* buffer, size_t size, size_t* length) {
  return railcontact::c_api::last_error(table, buffer, size, length);
}

namespace {

railcontact::WheelRailPair pair_of(const char* setup_path) {
  if (setup_path == nullptr) return railcontact::default_wheel_rail_pair();
  return railcontact::load_wheel_rail_pair(railcontact::read_wheel_rail_setup(setup_path));
}

std::vector<double> finite_values(const double* values, size_t count, std::size_t max_count, const char* what,
                                  const char* count_name) {
  require(count >= 1 && count <= max_count, [&] {
    return fmt::format("{} = {}: 1 to {} values are allowed", count_name, count, max_count);
  });
  require_pointer(values, what);
  std::vector<double> v(values, values + count);
  for (std::size_t k = 0; k < v.size(); ++k)
    if (!std::isfinite(v[k])) throw Error(fmt::format("{}[{}] = {} is not finite", what, k, v[k]));
  return v;
}

struct Cancelled {};

const railcontact::FlexibilityTableFastSim& loaded(const rc_flextable* table) {
  if (!table->table) throw Error("the flexibility table is empty (rc_flextable_build or rc_flextable_load first)");
  return *table->table;
}

}  // namespace

rc_status rc_flextable_build(rc_flextable* table, const char* setup_path, const double* y_m, size_t y_count,
                             const double* loads_N, size_t load_count, int target_elements, double youngs_modulus_Pa,
                             double poisson_ratio, rc_progress_callback progress, void* user_data) {
  if (table == nullptr) return RC_INVALID_INPUT;
  return guarded(&table->error, [&] {
    const std::vector<double> y = finite_values(y_m, y_count, railcontact::kMaximumFlexibilityTableYValues,
                                                "rc_flextable_build: y_m", "rc_flextable_build: y_count");
    const std::vector<double> loads = finite_values(loads_N, load_count, railcontact::kMaximumFlexibilityTableLoads,
                                                    "rc_flextable_build: loads_N", "rc_flextable_build: load_count");
    for (std::size_t k = 0; k < y.size(); ++k)
      require(std::abs(y[k]) <= railcontact::kMaximumWheelRailLateralDisplacement_m, [&] {
        return fmt::format("rc_flextable_build: y_m[{}] = {:g} m must lie in [{:g}, {:g}] m (a lateral displacement in "
                           "metres: beyond it the wheel is off its rail)",
                           k, y[k], -railcontact::kMaximumWheelRailLateralDisplacement_m,
                           railcontact::kMaximumWheelRailLateralDisplacement_m);
      });
    for (std::size_t k = 0; k < loads.size(); ++k)
      railcontact::validate_normal_force(loads[k], fmt::format("rc_flextable_build: loads_N[{}]", k));
    railcontact::FlexibilityTableOptions options;
    if (target_elements != 0) options.patch.target_elements = target_elements;
    options.patch.material = railcontact::Material{youngs_modulus_Pa, poisson_ratio};
    railcontact::validate(options.patch.material);
    railcontact::WheelRailPair pair = pair_of(setup_path);
    railcontact::FlexibilityTableProgressCallback callback;
    if (progress != nullptr)
      callback = [&](const railcontact::FlexibilityTableProgress& p) {
        if (progress(p.nodes_done, p.nodes_total, user_data) != 0) throw Cancelled{};
      };
    try {
      railcontact::FlexibilityTable built = railcontact::build_flexibility_table(pair, y, loads, options, callback);
      table->table.reset();
      table->table.emplace(std::move(built), std::move(pair));
    } catch (const Cancelled&) {
      throw StatusError{RC_CANCELLED, "rc_flextable_build: cancelled by the progress callback"};
    }
  });
}

rc_status rc_flextable_load(rc_flextable* table, const char* path, const char* setup_path) {
  if (table == nullptr) return RC_INVALID_INPUT;
  return guarded(&table->error, [&] {
    require_pointer(path, "rc_flextable_load: path");
    railcontact::FlexibilityTable loaded_table = railcontact::load_flexibility_table(path);
    table->table.reset();
    table->table.emplace(std::move(loaded_table), pair_of(setup_path));
  });
}

rc_status rc_flextable_save(const rc_flextable* table, const char* path) {
  if (table == nullptr) return RC_INVALID_INPUT;
  return guarded(&table->error, [&] {
    require_pointer(path, "rc_flextable_save: path");
    railcontact::save_flexibility_table(loaded(table).table(), path);
  });
}

rc_status rc_flextable_info_get(const rc_flextable* table, rc_flextable_info* info) {
  if (table == nullptr) return RC_INVALID_INPUT;
  return guarded(&table->error, [&] {
    require_pointer(info, "rc_flextable_info_get: info");
    const railcontact::FlexibilityTable& t = loaded(table).table();
    *info = rc_flextable_info{};
    info->y_min_m = t.y_m().front();
    info->y_max_m = t.y_m().back();
    info->load_min_N = t.vertical_loads_N().front();
    info->load_max_N = t.vertical_loads_N().back();
    info->youngs_modulus_Pa = t.metadata().material.youngs_modulus_Pa;
    info->poisson_ratio = t.metadata().material.poisson_ratio;
    info->y_count = static_cast<int>(t.y_m().size());
    info->load_count = static_cast<int>(t.vertical_loads_N().size());
    info->target_elements = t.metadata().target_elements;
  });
}

rc_status rc_flextable_lookup(const rc_flextable* table, double y_m, double vertical_load_N,
                              rc_flextable_values* values) {
  if (table == nullptr) return RC_INVALID_INPUT;
  return guarded(&table->error, [&] {
    require_pointer(values, "rc_flextable_lookup: values");
    if (!std::isfinite(y_m) || !std::isfinite(vertical_load_N))
      throw Error(fmt::format("rc_flextable_lookup: y = {} m and Fz = {} N must be finite", y_m, vertical_load_N));
    const railcontact::FlexibilityTableValues v = loaded(table).table().lookup(y_m, vertical_load_N);
    values->L1_m_per_Pa = v.flexibility.L1;
    values->L2_m_per_Pa = v.flexibility.L2;
    values->L3_m_per_Pa = v.flexibility.L3;
    values->f11_N = v.f11_N;
    values->f22_N = v.f22_N;
    values->f23_Nm = v.f23_Nm;
    values->normal_force_N = v.normal_force_N;
    values->contact_angle_rad = v.contact_angle_rad;
    values->spin_per_m = v.spin_per_m;
    values->area_m2 = v.area_m2;
  });
}

rc_status rc_solver_set_patch_flextable(rc_solver* solver, const rc_flextable* table, double y_m,
                                        double vertical_load_N) {
  if (solver == nullptr) return RC_INVALID_INPUT;
  return guarded(&solver->error, [&] {
    require_pointer(table, "rc_solver_set_patch_flextable: table");
    solver->solver.set_prepared(nullptr, std::nullopt);
    solver->solver.set_prepared(
        SinglePatchSolver::prepare_wheel_rail(solver->solver.settings(), loaded(table), y_m, vertical_load_N),
        std::nullopt);
  });
}

}  // extern "C"
