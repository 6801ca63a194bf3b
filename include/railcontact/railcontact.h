/* railcontact.h: the C API of railcontact (docs/C_API.md), plain C11, usable from C, C++ and
 * Fortran (iso_c_binding): opaque handles, plain structs of doubles and ints, int-sized
 * enumerations, a status code from every call.
 *
 * Units are SI throughout: m, N, Pa, N m, rad; creepages xi, eta dimensionless, spin phi in 1/m.
 * Frame and signs as in the C++ API (docs/CONVENTIONS.md): X1 rolling direction, X2 lateral,
 * X3 normal into the wheel; forces are those on the wheel, Kalker's convention
 * (F1 = -G c^2 C11 xi in the linear regime).
 *
 * Rules of every call:
 *  - it returns an rc_status (RC_OK = 0); the three queries rc_status_string, rc_version_string
 *    and rc_abi_version cannot fail and return their value;
 *  - on failure the handle keeps a one-line message (rc_solver_last_error,
 *    rc_flextable_last_error) and the outputs are unspecified;
 *  - no C++ exception crosses it; out of memory is RC_OUT_OF_MEMORY;
 *  - NaN and infinite inputs are refused (RC_INVALID_INPUT), as are null pointers where a value
 *    is required;
 *  - the caller owns every buffer and passes its size; sizes are queried first;
 *  - a handle may be used by one thread at a time; different handles may be used on different
 *    threads at the same time. A flexibility table may be read by several solvers at once.
 *
 * Handles: rc_solver (a contact patch with its prepared solver, the settings, the last results)
 * and rc_flextable (a flexibility table with its profile pair). Later versions add other
 * handles (e.g. rc_wheelset) in the same style: rc_<handle>_create / _destroy / _last_error and
 * rc_<handle>_<verb>.
 */
#ifndef RAILCONTACT_H
#define RAILCONTACT_H

#include <stddef.h>

#include "railcontact/version.h"

#if defined(RC_BUILDING_LIBRARY) && (defined(__GNUC__) || defined(__clang__))
#define RC_API __attribute__((visibility("default")))
#else
#define RC_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Status ------------------------------------------------------------------------------ */

/* The result of every call; RC_INVALID_INPUT ... RC_INTERNAL mirror railcontact::ErrorKind. */
typedef enum rc_status {
  RC_OK = 0,
  RC_INVALID_INPUT = 1,    /* a value or option outside what is allowed (also NaN, inf, null) */
  RC_NO_CONTACT = 2,       /* the bodies do not touch */
  RC_SEVERAL_PATCHES = 3,  /* several contact patches where the computation needs one */
  RC_NOT_CONVERGED = 4,    /* an iterative solver did not reach its tolerance */
  RC_IO = 5,               /* a file cannot be read or written */
  RC_INTERNAL = 6,         /* an invariant of railcontact does not hold (a bug) */
  RC_OUT_OF_MEMORY = 7,    /* an allocation failed (reduce the number of elements) */
  RC_BUFFER_TOO_SMALL = 8, /* a caller's buffer is smaller than the size queried */
  RC_CANCELLED = 9         /* a progress callback asked to stop */
} rc_status;

/* "ok", "invalid input", "no contact", "several contact patches", "not converged",
   "input/output", "internal error", "out of memory", "buffer too small", "cancelled";
   "unknown status" for other values. Static storage: do not free. */
RC_API const char* rc_status_string(int status);

/* ---- Version ----------------------------------------------------------------------------- */

/* "MAJOR.MINOR.PATCH" of the library linked (static storage). */
RC_API const char* rc_version_string(void);
/* The version numbers of the library linked; each pointer may be null. */
RC_API rc_status rc_version(int* major, int* minor, int* patch);
/* The ABI version of the library linked; equals RC_ABI_VERSION of the header compiled against
   when the two fit. */
RC_API int rc_abi_version(void);

/* ---- Settings of a solver ---------------------------------------------------------------- */

/* The tangential method. */
typedef enum rc_method {
  RC_METHOD_NH_FASTSIM = 0,        /* nH-FastSim: FastSim with flexibilities from K2 of the patch */
  RC_METHOD_FASTSIM = 1,           /* classical FastSim: Kalker's flexibilities (Eq 9) of the
                                      (equivalent) ellipse, the parabolic traction bound (Eq 1) */
  RC_METHOD_EXACT = 2,             /* exact steady rolling with Coulomb friction */
  RC_METHOD_EXACT_REGULARISED = 3  /* exact steady rolling with the regularised law (Eq A1) */
} rc_method;

/* How the ellipse and Hertz geometries are meshed (a grid brings its own mesh). */
typedef enum rc_mesh_mode {
  RC_MESH_ELEMENTS_IN_CONTACT = 0, /* mesh_value: about this many elements in contact, square
                                      elements when a >= b (the CLI's ellipse cases) */
  RC_MESH_ELEMENTS_ACROSS = 1,     /* mesh_value: n x n elements over the bounding box 2a x 2b
                                      (the paper's meshes) */
  RC_MESH_ELEMENT_SIZE = 2         /* mesh_value: element edge (m); n1 = ceil(2a / value),
                                      n2 = ceil(2b / value) elements over the bounding box */
} rc_mesh_mode;

/* All settings of a solver handle. Fill with rc_settings_default, change fields, pass to
   rc_solver_set_settings (which checks every field). Ranges as the C++ API's. */
typedef struct rc_settings {
  double youngs_modulus_Pa;     /* E of both bodies (Pa), [1e6, 1e13]; default 2.1e11 */
  double poisson_ratio;         /* nu (-), [0, 0.5]; default 0.3 */
  double friction_coefficient;  /* mu (-), (0, 10]; default 0.3 */
  double mesh_value;            /* see mesh_mode; default 2800 (elements in contact) */
  double bound_skew;            /* nh-fastsim's traction bound skew, [0, 1]; default 0.45 (0: the
                                   paper's parabola, Eq 1) */
  double collocation_offset;    /* alpha (-) of K2 (nh-fastsim) and of the exact solvers,
                                   [-0.95, 1]; default 0 */
  double tolerance;             /* exact solvers: Newton residual relative to mu max p3,
                                   (0, 1e-3]; default 1e-9 */
  double krylov_tolerance;      /* exact solvers: inner GMRES, relative, (0, 0.5]; default 1e-6 */
  double regularisation;        /* exact-regularised: epsilon (slip per unit rolling speed, -),
                                   [1e-14, 1e-2]; default 1e-8 */
  double normal_tolerance;      /* grid geometry: normal solver's relative residual,
                                   (0, 1e-2]; default 1e-10 */
  double jacobian_step_creepage; /* rc_solver_jacobian: central-difference step of xi and eta
                                   (-), [1e-10, 1e-2]; default 1e-6 */
  double jacobian_step_spin_per_m; /* ... and of phi (1/m), [1e-8, 1]; default 1e-4 */
  int method;                   /* rc_method; default RC_METHOD_NH_FASTSIM */
  int mesh_mode;                /* rc_mesh_mode; default RC_MESH_ELEMENTS_IN_CONTACT */
  int flexibility_coarsening;   /* nh-fastsim: K2 on the patch coarsened by this factor, 1..8;
                                   0 automatic (default) */
  int max_newton_iterations;    /* exact solvers, >= 1; default 100 */
  int max_krylov_iterations;    /* exact solvers, >= 1; default 300 */
  int normal_max_iterations;    /* grid geometry, >= 1; default 1000 */
} rc_settings;

RC_API rc_status rc_settings_default(rc_settings* settings);

/* ---- Contact patch, creepages, results ---------------------------------------------------- */

typedef enum rc_geometry {
  RC_GEOMETRY_ELLIPSE = 0, /* semi-axes a (along X1), b; Hertzian pressure; a/b in [0.01, 100] */
  RC_GEOMETRY_HERTZ = 1,   /* h = A x1^2 + B x2^2: Hertz's ellipse and pressure for A, B, F3 */
  RC_GEOMETRY_GRID = 2     /* undeformed distance h on a regular grid: the normal problem is
                              solved (non-Hertzian); the patch must be one connected region */
} rc_geometry;

/* One single-patch state's geometry and load. Fields not used by the kind are ignored. */
typedef struct rc_patch {
  double normal_force_N;  /* F3 (N), [1, 1e7] */
  double a_m, b_m;        /* ELLIPSE: semi-axes along X1 and X2 (m) */
  double A_per_m, B_per_m;/* HERTZ: curvatures of h = A x1^2 + B x2^2 (1/m), > 0 */
  double grid_dx1_m;      /* GRID: element length along X1 (m) */
  double grid_dx2_m;      /* GRID: element width along X2 (m) */
  const double* grid_h_m; /* GRID: n1 * n2 values of h (m), element (i1, i2) at i2 * n1 + i1
                             (X1 fastest); h > 0 separated. Read during the call only. */
  int kind;               /* rc_geometry */
  int grid_n1, grid_n2;   /* GRID: elements along X1 and X2, >= 2 each */
  int reserved;           /* set to 0 */
} rc_patch;

/* Creepages of steady rolling. */
typedef struct rc_creepage {
  double xi;         /* longitudinal creepage (-) */
  double eta;        /* lateral creepage (-) */
  double phi_per_m;  /* spin creepage (1/m) */
} rc_creepage;

/* Tangential results on the wheel, in the contact frame. */
typedef struct rc_forces {
  double F1_N;               /* longitudinal force (N) */
  double F2_N;               /* lateral force (N) */
  double M3_Nm;              /* spin moment Mz about X3 through the pressure centre (N m) */
  double adhesion_fraction;  /* elements in adhesion / elements in contact (-) */
} rc_forces;

/* The normal problem of the patch. */
typedef struct rc_normal_result {
  double normal_force_N;   /* F3 carried by the discrete patch (N) */
  double area_m2;          /* elements in contact x element area (m^2) */
  double max_pressure_Pa;  /* largest p3 on the mesh (Pa) */
  double approach_m;       /* mutual approach delta (m): Hertz's for ELLIPSE / HERTZ, the normal
                              solver's for GRID and wheel-rail patches */
  double a_m, b_m;         /* semi-axes (ELLIPSE, HERTZ) or the equivalent ellipse (same area,
                              axis ratio of the patch's extents) (m) */
  double dx1_m, dx2_m;     /* element size of the patch's mesh (m) */
  double x1_first_m;       /* x1 of the centre of mesh column 0, origin at the pressure centre */
  double x2_first_m;       /* x2 of the centre of mesh row 0 (m) */
  double contact_angle_rad;/* wheel-rail patches (rc_solver_set_patch_flextable): gamma; else 0 */
  double spin_per_m;       /* wheel-rail patches: spin from conicity (Eq 24, signed); else 0 */
  int n1, n2;              /* the patch's mesh: elements along X1 and X2 (traction fields) */
  int elements_in_contact;
  int reserved;
} rc_normal_result;

/* ---- Solver handle ------------------------------------------------------------------------ */

typedef struct rc_solver rc_solver;

/* A new solver with rc_settings_default and no patch. *solver is null on failure. */
RC_API rc_status rc_solver_create(rc_solver** solver);
/* Destroys the solver (null is allowed and does nothing). */
RC_API rc_status rc_solver_destroy(rc_solver* solver);
/* The message of the last failed call on this solver ("" when none), NUL-terminated and cut to
   size - 1 bytes; *length (may be null) receives its full length without the NUL. buffer may be
   null when size is 0 (query the length first). RC_BUFFER_TOO_SMALL when the message was cut. */
RC_API rc_status rc_solver_last_error(const rc_solver* solver, char* buffer, size_t size, size_t* length);

/* Checks and takes all settings. A changed material, mesh or method discards the patch's
   prepared solver (the next call prepares it again); friction alone does not. */
RC_API rc_status rc_solver_set_settings(rc_solver* solver, const rc_settings* settings);
RC_API rc_status rc_solver_get_settings(const rc_solver* solver, rc_settings* settings);

/* Sets the contact patch: the normal problem (Hertz, or the normal solver for a grid), then the
   tangential method's preparation (nh-fastsim: K2 and the flexibilities, the costly part).
   Later rc_solver_solve calls evaluate creepages on it. */
RC_API rc_status rc_solver_set_patch(rc_solver* solver, const rc_patch* patch);
/* Shorthands of rc_solver_set_patch. */
RC_API rc_status rc_solver_set_ellipse(rc_solver* solver, double a_m, double b_m, double normal_force_N);
RC_API rc_status rc_solver_set_hertz(rc_solver* solver, double A_per_m, double B_per_m, double normal_force_N);
RC_API rc_status rc_solver_set_grid(rc_solver* solver, int n1, int n2, double dx1_m, double dx2_m, const double* h_m,
                                    double normal_force_N);
/* The normal results of the patch. */
RC_API rc_status rc_solver_normal_result(const rc_solver* solver, rc_normal_result* result);

/* Creep forces and spin moment for the creepages on the patch set. */
RC_API rc_status rc_solver_solve(rc_solver* solver, const rc_creepage* creepage, rc_forces* forces);
/* The classic creep-force routine of a multibody code: rc_solver_set_patch (skipped when the
   patch equals the one set: the prepared solver is reused), then rc_solver_solve. normal may be
   null. */
RC_API rc_status rc_creep_forces(rc_solver* solver, const rc_patch* patch, const rc_creepage* creepage,
                                 rc_forces* forces, rc_normal_result* normal);
/* forces (may be null) and the Jacobian d(F1, F2, M3)/d(xi, eta, phi) at the creepages, row-major
   (jacobian[3 * i + j] = dF_i / dc_j; units N, N/(1/m); N m, N m/(1/m)), by central differences
   with the settings' steps (6 more solves). The traction fields are those of the creepages. */
RC_API rc_status rc_solver_jacobian(rc_solver* solver, const rc_creepage* creepage, rc_forces* forces,
                                    double jacobian[9]);

/* The traction fields of the last rc_solver_solve / rc_creep_forces / rc_solver_jacobian, on the
   patch's mesh: n1 x n2 values each, element (i1, i2) at i2 * n1 + i1 (X1 fastest), 0 outside
   contact. *count receives n1 * n2. */
RC_API rc_status rc_solver_traction_size(const rc_solver* solver, int* n1, int* n2, size_t* count);
/* Copies the fields into the caller's buffers of `size` values each (each may be null: not
   wanted): p1, p2 tangential traction on the wheel (Pa), p3 normal pressure (Pa), slip 1 where
   the element slips, 0 in adhesion or outside contact. RC_BUFFER_TOO_SMALL when size < n1 * n2. */
RC_API rc_status rc_solver_tractions(const rc_solver* solver, size_t size, double* p1_Pa, double* p2_Pa,
                                     double* p3_Pa, int* slip);

/* Many single-patch states at once on `threads` threads (1 = the calling thread only; 0 = the
   machine's hardware threads), one internal solver per thread with this solver's settings; the
   results equal those of the serial loop of rc_creep_forces. State k has patch
   patches[patch_count == 1 ? 0 : k] and creepages[k]; patch_count is 1 (one patch for all: it is
   prepared once and shared) or count. Outputs (count entries each): forces (required), normal
   and jacobians (9 values per state; may be null: not computed), statuses (may be null). Returns
   RC_OK when every state succeeded, else the status of the first failed state, whose message
   ("state K: ...") is the solver's last error. This solver's own patch and fields are unchanged. */
RC_API rc_status rc_batch_creep_forces(rc_solver* solver, size_t count, const rc_patch* patches, size_t patch_count,
                                       const rc_creepage* creepages, int threads, rc_forces* forces,
                                       rc_normal_result* normal, double* jacobians, int* statuses);

/* ---- Flexibility table (docs/FLEXTABLE.md) ------------------------------------------------- */

typedef struct rc_flextable rc_flextable;

/* An empty table. *table is null on failure. */
RC_API rc_status rc_flextable_create(rc_flextable** table);
RC_API rc_status rc_flextable_destroy(rc_flextable* table);
RC_API rc_status rc_flextable_last_error(const rc_flextable* table, char* buffer, size_t size, size_t* length);

/* Progress of rc_flextable_build after each node; return 0 to go on, non-zero to stop (the build
   then returns RC_CANCELLED). */
typedef int (*rc_progress_callback)(size_t nodes_done, size_t nodes_total, void* user_data);

/* Builds the table of a wheel-rail set-up file (docs/WHEEL_RAIL.md "Set-up files"; null: the
   shipped S1002/UIC60 set-up) over the lateral displacements y_m[0 .. y_count) (m, increasing)
   and vertical wheel loads loads_N[0 .. load_count) (N, increasing), with about
   target_elements elements in contact per patch ([100, 200000]; 0: 3000) and the material
   E, nu (Pa, -). progress may be null. Replaces the table's content. */
RC_API rc_status rc_flextable_build(rc_flextable* table, const char* setup_path, const double* y_m, size_t y_count,
                                    const double* loads_N, size_t load_count, int target_elements,
                                    double youngs_modulus_Pa, double poisson_ratio, rc_progress_callback progress,
                                    void* user_data);
/* Loads a table file (JSON) for the profiles of a set-up file (null: the shipped S1002/UIC60);
   RC_INVALID_INPUT when the table was built for other profiles. */
RC_API rc_status rc_flextable_load(rc_flextable* table, const char* path, const char* setup_path);
RC_API rc_status rc_flextable_save(const rc_flextable* table, const char* path);

/* Interpolated values of a table at (y, Fz). */
typedef struct rc_flextable_values {
  double L1_m_per_Pa, L2_m_per_Pa, L3_m_per_Pa; /* nH-FastSim flexibilities */
  double f11_N, f22_N, f23_Nm;                  /* creepage coefficients of K2 */
  double normal_force_N;                        /* F3 = Fz / cos(gamma) */
  double contact_angle_rad;                     /* gamma */
  double spin_per_m;                            /* Eq 24, signed (right wheel) */
  double area_m2;                               /* patch area */
} rc_flextable_values;

/* The grid: counts, ranges (m, N), and the material (Pa, -) and target elements of the build. */
typedef struct rc_flextable_info {
  double y_min_m, y_max_m;
  double load_min_N, load_max_N;
  double youngs_modulus_Pa, poisson_ratio;
  int y_count, load_count;
  int target_elements;
  int reserved;
} rc_flextable_info;

RC_API rc_status rc_flextable_info_get(const rc_flextable* table, rc_flextable_info* info);
RC_API rc_status rc_flextable_lookup(const rc_flextable* table, double y_m, double vertical_load_N,
                                     rc_flextable_values* values);

/* Sets the solver's patch to the wheel-rail patch of the table's profile pair at wheelset lateral
   displacement y (m) and vertical wheel load Fz (N): the normal problem is solved, and
   nh-fastsim takes its flexibilities from the table (no K2); the other methods run on the
   same patch. The solver's material must be the table's. The table must outlive the call only. */
RC_API rc_status rc_solver_set_patch_flextable(rc_solver* solver, const rc_flextable* table, double y_m,
                                               double vertical_load_N);

#ifdef __cplusplus
}
#endif

#endif /* RAILCONTACT_H */
