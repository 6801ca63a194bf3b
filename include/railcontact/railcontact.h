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
 *    rc_flextable_last_error, rc_wheelset_last_error) and the outputs are unspecified;
 *  - no C++ exception crosses it; out of memory is RC_OUT_OF_MEMORY;
 *  - NaN and infinite inputs are refused (RC_INVALID_INPUT), as are null pointers where a value
 *    is required;
 *  - the caller owns every buffer and passes its size; sizes are queried first;
 *  - a handle may be used by one thread at a time; different handles may be used on different
 *    threads at the same time. A flexibility table may be read by several solvers at once.
 *
 * Handles: rc_solver (a contact patch with its prepared solver, the settings, the last results),
 * rc_flextable (a flexibility table with its profile pair) and rc_wheelset (both wheels of a
 * wheelset on their rails, docs/WHEELSET.md). Each in the same style: rc_<handle>_create /
 * _destroy / _last_error and rc_<handle>_<verb>. Handles are not validated, like the pointers of
 * malloc and free: a handle used after its _destroy, destroyed twice, or not made by _create is
 * undefined behaviour (a crash at best). rc_<handle>_destroy(NULL) does nothing and returns RC_OK:
 * set a handle's variable to NULL after destroying it.
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

/* ---- Counts ------------------------------------------------------------------------------ */

/* The largest count each call accepts, checked before anything is allocated (RC_INVALID_INPUT
   naming the argument): a count like (size_t)-1 is a caller's error, not a batch.
   RC_MAX_BATCH_STATES: rc_batch_creep_forces' count (10 million states: ~36 bytes of bookkeeping
   each, and about 10 s at 1 us a state). RC_MAX_WHEELSET_BATCH_STATES: rc_wheelset_batch_evaluate's
   count (1 million states, as a sweep's cases: 0.1-0.5 s each). RC_MAX_PATCHES_PER_WHEEL: its
   patches_per_wheel (a wheel has 1 to 3 patches). rc_flextable_build: y_count at most 10000 and
   load_count at most 100 (kMaximumFlexibilityTableYValues, kMaximumFlexibilityTableLoads of
   flexibility_table.hpp); rc_wheelset_table_build: at most 20000 values per axis and nodes. */
#define RC_MAX_BATCH_STATES ((size_t)10000000)
#define RC_MAX_WHEELSET_BATCH_STATES ((size_t)1000000)
#define RC_MAX_PATCHES_PER_WHEEL ((size_t)64)

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

/* Where nH-FastSim puts the traction of a slipping element (docs/FASTSIM.md "The slip direction"). */
typedef enum rc_slip_direction {
  RC_SLIP_RADIAL = 0,               /* scaled onto the bound (Eq 8, Kalker's and the paper's) */
  RC_SLIP_FLEXIBILITY_WEIGHTED = 1, /* towards the slip of FastSim's elastic law: within 3 % of the
                                       exact solver on flange patches, where Eq 8 misses F1 by up
                                       to 4 % of mu F3 */
  RC_SLIP_RIGID = 2,                /* flexibility-weighted, turning to the rigid slip's own spin as
                                       an element slides: flange patches in full slip under spin
                                       within 3 % too */
  RC_SLIP_ELASTIC = 3               /* rigid, and where the patch slips everywhere Coulomb's law
                                       along the elastic slip (the wheelset's default): flange
                                       patches in full slip within 0.5 % */
} rc_slip_direction;

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
  double krylov_tolerance;      /* exact solvers: inner GMRES, relative, (0, 0.5]; default 1e-6 (the exact
                                   solver's last Newton steps; earlier ones stop at min(residual, 0.1)) */
  double regularisation;        /* exact-regularised: epsilon (slip per unit rolling speed, -),
                                   [1e-14, 1e-2]; default 1e-8 */
  double normal_tolerance;      /* grid geometry: normal solver's relative residual,
                                   (0, 1e-2]; default 1e-10 */
  double jacobian_step_creepage; /* rc_solver_jacobian: central-difference step of xi and eta
                                   (-), [1e-10, 1e-2]; default 1e-6 */
  double jacobian_step_spin_per_m; /* ... and of phi (1/m), [1e-8, 1]; default 1e-4 */
  int method;                   /* rc_method; default RC_METHOD_NH_FASTSIM */
  int mesh_mode;                /* rc_mesh_mode; default RC_MESH_ELEMENTS_IN_CONTACT */
  int flexibility_coarsening;   /* nh-fastsim: K2 on the patch coarsened in square blocks of this
                                   factor, 1..8; 0 automatic (default: f along the rolling
                                   direction, f + 1 across from f = 3) */
  int slip_direction;           /* nh-fastsim: rc_slip_direction; default RC_SLIP_RADIAL (Eq 8, as
                                   the paper; RC_SLIP_RIGID for flange patches) */
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
  double a_m, b_m;        /* ELLIPSE: semi-axes along X1 and X2 (m), [1e-5, 0.1], a/b [0.01, 100] */
  double A_per_m, B_per_m;/* HERTZ: curvatures of h = A x1^2 + B x2^2 (1/m), [1e-3, 1e4] */
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
  double xi;         /* longitudinal creepage (-), [-0.5, 0.5] */
  double eta;        /* lateral creepage (-), [-0.5, 0.5] */
  double phi_per_m;  /* spin creepage (1/m), [-100, 100] */
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
/* The contact patch with the normal problem solved for a given approach (penetration) delta =
   approach_m (m) instead of a given normal force: patch->normal_force_N is ignored and F3
   follows (rc_solver_normal_result). HERTZ: Hertz's ellipse and F3 for the curvatures at delta
   (delta > 0). ELLIPSE: the semi-axes a, b are kept and F3 is the ellipse's Hertzian load at
   delta (delta > 0). GRID: the normal solver with the approach prescribed: h - delta + u >= 0
   (h measured at the bodies' position, negative where they overlap; delta = 0 is the
   position-driven problem); RC_NO_CONTACT when no element comes into contact. The F3 found must
   lie in [1, 1e7] N. Then as rc_solver_set_patch (the method's preparation). */
RC_API rc_status rc_solver_set_patch_at_approach(rc_solver* solver, const rc_patch* patch, double approach_m);
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
   the element slips, 0 in adhesion or outside contact. RC_BUFFER_TOO_SMALL when size < n1 * n2.
   For nh-fastsim and fastsim the fields are computed by the first call after a solve, from its
   creepages (about the cost of one more solve; rc_solver_solve itself computes the forces only);
   the exact solvers keep them from the solve. */
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


/* ---- Wheelset (docs/WHEELSET.md) ------------------------------------------------------------ */

/* Both wheels of a wheelset on their rails in 3-D: a multibody state in (position and velocity),
   every contact patch of both wheels and the forces on each wheel out.
   - Track frame: x along the track in the direction of travel, y lateral to the LEFT, z UP; the
     origin on the track centreline at the height of the rail profiles' origins.
   - Contact frame of a patch: X1 = x (the rail's direction), X3 the rail's normal into the wheel
     at the reference point, leaning towards the track centre by the contact angle gamma,
     X2 = X3 x X1 (pointing to the left on both wheels). Forces and moments are those on the
     wheel; creepages as in rc_creepage (kinematic, at the patch's reference point).
   - Wheels are indexed by rc_wheel_side: 0 right, 1 left.
   - Profile files: any format of the library (SIMPACK .prw/.prr, MiniProf .ban/.whl, two-column
     text in mm), each in its own side's profile frame (docs/GEOMETRY.md); one file serves both
     sides. */

typedef struct rc_wheelset rc_wheelset;

typedef enum rc_wheel_side {
  RC_WHEEL_RIGHT = 0,
  RC_WHEEL_LEFT = 1
} rc_wheel_side;

/* Where the wheel's radius is the nominal radius r0 (docs/WHEEL_RAIL.md; the set-up key
   track.nominal_radius_at). On a new S1002 drawn from its taping line the two agree. */
typedef enum rc_nominal_radius_datum {
  RC_RADIUS_AT_PROFILE_ORIGIN = 0, /* the wheel profile's origin (z = 0), as Kalker's CONTACT */
  RC_RADIUS_AT_TAPING_LINE = 1     /* the taping line (the flange back + taping_line_from_flange_back_m) */
} rc_nominal_radius_datum;

/* The track and wheelset dimensions (m), as in the wheel-rail set-up files. */
typedef struct rc_track_parameters {
  double track_gauge_m;                  /* between the gauge faces; default 1.435 */
  double gauge_measuring_depth_m;        /* ... measured this far below the top of the rails; 0.014 */
  double flange_back_distance_m;         /* between the wheels' flange backs; 1.360 */
  double flange_back_y_m;                /* the flange back in the wheel profile frame; -0.070 */
  double taping_line_from_flange_back_m; /* lateral distance flange back -> taping line; 0.070 */
  double nominal_rolling_radius_m;       /* wheel radius r0 at nominal_radius_at; 0.46 (ranges: geometry.hpp) */
  int nominal_radius_at;                 /* rc_nominal_radius_datum: where the wheel's radius is r0;
                                            default RC_RADIUS_AT_PROFILE_ORIGIN */
  double rail_cant_rad;                  /* rail inclination towards the track centre, applied to the rail
                                            profile (rad, |x| <= 0.1); default 0: the profile as given
                                            (the shipped UIC60 is inclined 1:40); 1:40 is 0.0249948 */
} rc_track_parameters;

RC_API rc_status rc_track_parameters_default(rc_track_parameters* track);

/* How each wheel's normal problem is set. */
typedef enum rc_wheelset_normal {
  RC_WHEELSET_BY_LOAD = 0,    /* each wheel's height is solved so that its vertical force meets
                                 its load (the state's z is ignored) */
  RC_WHEELSET_BY_POSITION = 1 /* the state's z and roll give the overlap; the forces follow */
} rc_wheelset_normal;

/* How a patch's reference point and contact angle average its contact locus (docs/WHEELSET.md §4). */
typedef enum rc_reference_weighting {
  RC_WEIGHTING_SQUARED_GAP = 0, /* each lateral strip by the integral of its squared rigid overlap
                                   along the track, as Kalker's CONTACT (default) */
  RC_WEIGHTING_DEPTH = 1        /* by the overlap depth (smoother where the contact runs onto the
                                   flange) */
} rc_reference_weighting;

/* The contact surface of each wheelset patch (docs/WHEELSET.md §4 "Conformal contact"). */
typedef enum rc_contact_surface {
  RC_SURFACE_PLANAR = 0,    /* the tangent plane at the patch's reference point (default) */
  RC_SURFACE_CONFORMAL = 1, /* curved with the profiles across the rolling direction */
  RC_SURFACE_AUTO = 2       /* planar where the contact angle hardly varies over the patch,
                               conformal where it does, both blended between (smooth in y) */
} rc_contact_surface;

/* The options of a wheelset (defaults from rc_wheelset_options_default). */
typedef struct rc_wheelset_options {
  double youngs_modulus_Pa;    /* E of wheels and rails (Pa); default 2.1e11 */
  double poisson_ratio;        /* nu (-); default 0.3 */
  double friction_coefficient; /* mu (-), (0, 2]; default 0.3 */
  double element_size_m;       /* square elements of the potential contact areas (m),
                                  [0.02e-3, 5e-3]; default 0.2e-3 */
  double right_load_N;         /* BY_LOAD: the right wheel's vertical load (N), [1, 1e7]; 98100 */
  double left_load_N;          /* BY_LOAD: the left wheel's (N); 98100 */
  int normal_mode;             /* rc_wheelset_normal; default RC_WHEELSET_BY_LOAD */
  int balance_roll;            /* BY_LOAD: 1 solves the axle's height and roll together (one rigid
                                  axle carries both loads); 0 (default) each wheel's height on its
                                  own at the state's roll */
  int tangential_in_balance;   /* BY_LOAD: 1 (default) the vertical balance includes the tangential
                                  forces' vertical components; 0 the normal forces only */
  int allow_wheel_lift;        /* 1: a wheel without contact has no patches and zero forces;
                                  0 (default): RC_NO_CONTACT */
  int warm_start;              /* 1 (default): an evaluation starts from the previous one's
                                  pressures, heights and balance and reuses its plans
                                  (docs/WHEELSET.md §8; faster for a time step, the numbers depend
                                  on the previous state to the solvers' tolerances: 2e-6 of F3,
                                  2e-4 of mu F3 where an element at a contact's edge is in
                                  contact in one and not the other, by load with the tangential
                                  forces in the balance 1e-5 of the load); 0: every evaluation
                                  from a cold start (its numbers depend
                                  on the state only, as in the batch) */
  int slip_direction;          /* nh-fastsim: rc_slip_direction; default RC_SLIP_ELASTIC (the
                                  wheelset's, for its flange) */
  int solver_count;            /* 1 .. 4: the tangential solvers run on every patch */
  int solvers[4];              /* rc_method values, distinct; the first one's forces make the
                                  wheels' totals */
  int balance_solver;          /* the rc_method whose forces the load balance (BY_LOAD: their
                                  vertical components) and RC_ROTATION_FREE use, one of solvers;
                                  -1 (default): the first of solvers */
  int reference_weighting;     /* rc_reference_weighting of each patch's reference point and
                                  contact angle; default RC_WEIGHTING_SQUARED_GAP */
  int contact_surface;         /* rc_contact_surface; default RC_SURFACE_PLANAR (a wheelset
                                  table is built on this surface and used with it) */
} rc_wheelset_options;

RC_API rc_status rc_wheelset_options_default(rc_wheelset_options* options);

/* How the wheels turn about their axle. */
typedef enum rc_wheel_rotation {
  RC_ROTATION_ROLLING = 0, /* pure rolling at the nominal radius r0 with the extra longitudinal
                              creepage xi0 at r0: V - Omega r0 = xi0 (V + Omega r0) / 2 */
  RC_ROTATION_GIVEN = 1,   /* wheel_angular_velocity_rad_per_s */
  RC_ROTATION_FREE = 2     /* free rolling: the angular velocity at which the wheels' tangential forces
                              have no moment about the axle, solved (rc_wheelset_wheel_angular_velocity);
                              rc_wheelset_evaluate only, not from a table */
} rc_wheel_rotation;

/* A wheelset's state: its position and velocity on the track (SI units, rad, rad/s). */
typedef struct rc_wheelset_state {
  double y_m;                  /* lateral displacement of the centre (m), + to the left; |y| <= 0.1 */
  double z_m;                  /* BY_POSITION: vertical displacement of the centre above its
                                  nominal height (m), + up; |z| <= 0.1; ignored BY_LOAD */
  double roll_rad;             /* about x, + the left wheel rises; |roll| <= 0.1 (balance_roll:
                                  the first guess) */
  double yaw_rad;              /* about z, + the axle's left end moves backwards; |yaw| <= 0.1 */
  double forward_speed_m_per_s;    /* V in (0, 200], the rolling speed of the creepages; default 20 */
  double lateral_velocity_m_per_s; /* dy/dt (m/s), |.| <= 10; rates |.| <= 10 rad/s (wheelset.hpp) */
  double vertical_velocity_m_per_s;/* dz/dt (m/s) */
  double roll_rate_rad_per_s;
  double yaw_rate_rad_per_s;
  double wheel_angular_velocity_rad_per_s; /* RC_ROTATION_GIVEN: about the axle, + rolling forward, |.| <= 1000 */
  double extra_longitudinal_creepage;      /* RC_ROTATION_ROLLING: xi0 (-), < 0 traction, > 0 braking, |.| <= 0.5 */
  int rotation;                /* rc_wheel_rotation; default RC_ROTATION_ROLLING */
  int reserved;                /* set to 0 */
} rc_wheelset_state;

/* Zero position and velocities, V = 20 m/s, pure rolling. */
RC_API rc_status rc_wheelset_state_default(rc_wheelset_state* state);

/* One contact patch of a wheel. */
typedef struct rc_wheelset_patch {
  double reference_point_track_m[3]; /* the patch's reference point on the rail surface, track
                                        frame (m): the overlap-weighted average (docs/WHEELSET.md §4) */
  double x2_axis[3];                 /* the contact frame's X2 and X3 in the track frame (unit);
                                        X1 = (1, 0, 0) */
  double x3_axis[3];
  double contact_angle_rad;          /* gamma, + leaning towards the track centre */
  double rolling_radius_m;           /* the wheel's radius at the patch (m) */
  double max_interpenetration_m;     /* largest overlap of the undeformed bodies (m) */
  rc_creepage creepage;              /* kinematic creepages at the reference point, contact frame */
  double normal_force_N;             /* F3 (N) */
  double area_m2;                    /* elements in contact x element area (m^2) */
  double max_pressure_Pa;            /* largest p3 (Pa) */
  double pressure_centre_x1_m;       /* the centre of pressure from the reference point, */
  double pressure_centre_x2_m;       /* along X1 and X2 (m) */
  rc_forces forces[4];               /* per solver of the options, in their order (unused: 0):
                                        F1, F2 (N), M3 about the centre of pressure (N m), contact
                                        frame, and the adhesion fraction */
  double force_track_N[4][3];        /* F1 X1 + F2 X2 + F3 X3 per solver, track frame (N) */
  double pressure_force_track_N[3];  /* the pressure's resultant on the wheel, track frame (N):
                                        F3 X3 on a planar patch, the strips' pressures along their
                                        own normals on a conformal one */
  double contact_angle_spread_rad;   /* the rail normal angle's weighted standard deviation over
                                        the overlap (rad; RC_SURFACE_AUTO's measure with gamma) */
  double conformal_weight;           /* 0 planar, 1 conformal, between: both blended */
  int side;                          /* rc_wheel_side */
  int elements_in_contact;
  int normal_iterations;             /* of the final normal solve */
  int solver_count;                  /* entries of forces and force_track_N in use */
} rc_wheelset_patch;

/* The totals of one evaluation (forces of the options' first solver). */
typedef struct rc_wheelset_result {
  double force_track_N[3];              /* on the wheelset: both wheels, track frame (N) */
  double wheel_force_track_N[2][3];     /* on each wheel [rc_wheel_side], track frame (N) */
  double wheel_vertical_displacement_m[2]; /* the height at which each wheel was solved (m) */
  double vertical_displacement_m;       /* the state as solved: z of the centre (m); BY_LOAD the
                                           mean of the wheels' heights found */
  double roll_rad;                      /* the state as solved: roll (balance_roll: found) */
  int patch_count[2];                   /* patches of each wheel [rc_wheel_side] */
  int load_iterations[2];               /* BY_LOAD: normal solves of each wheel's height iteration, all balance passes */
} rc_wheelset_result;

/* A new wheelset with rc_wheelset_options_default and no track (set one before evaluating).
   *wheelset is null on failure. */
RC_API rc_status rc_wheelset_create(rc_wheelset** wheelset);
RC_API rc_status rc_wheelset_destroy(rc_wheelset* wheelset);
RC_API rc_status rc_wheelset_last_error(const rc_wheelset* wheelset, char* buffer, size_t size, size_t* length);

/* The track: the shipped S1002 / UIC60 1:40 set-up (profiles and dimensions). */
RC_API rc_status rc_wheelset_set_default_track(rc_wheelset* wheelset);
/* The track: one wheel and one rail profile file for both sides, and the dimensions (null: the
   defaults of rc_track_parameters_default). RC_IO for a file that cannot be read. */
RC_API rc_status rc_wheelset_set_track(rc_wheelset* wheelset, const char* wheel_profile_path,
                                       const char* rail_profile_path, const rc_track_parameters* track);
/* The track with a profile file per wheel and rail. */
RC_API rc_status rc_wheelset_set_track_profiles(rc_wheelset* wheelset, const char* right_wheel_path,
                                                const char* left_wheel_path, const char* right_rail_path,
                                                const char* left_rail_path, const rc_track_parameters* track);
/* The track's dimensions and the nominal axle height H0 (m; may be null): the height of the
   wheelset centre at which, with y, roll and yaw zero, the first wheel touches its rail. */
RC_API rc_status rc_wheelset_get_track(const rc_wheelset* wheelset, rc_track_parameters* track,
                                       double* nominal_axle_height_m);

/* Checks and takes all options (a failed call keeps the previous ones). Discards the warm start. */
RC_API rc_status rc_wheelset_set_options(rc_wheelset* wheelset, const rc_wheelset_options* options);
RC_API rc_status rc_wheelset_get_options(const rc_wheelset* wheelset, rc_wheelset_options* options);

/* Evaluates a state: the contact search, each patch's normal problem (by load or by position),
   the creepages and the tangential solvers. result (may be null) receives the totals; the
   patches are queried with rc_wheelset_patch_count and rc_wheelset_patches. */
RC_API rc_status rc_wheelset_evaluate(rc_wheelset* wheelset, const rc_wheelset_state* state,
                                      rc_wheelset_result* result);
/* Forgets the warm start (the previous evaluation's pressures and the normal solvers' plans): the
   next rc_wheelset_evaluate starts cold and gives the numbers of a fresh wheelset with the same
   track and options, to the last digit. For a jump in the state (a new run, a restart). The last
   result stays readable. */
RC_API rc_status rc_wheelset_reset_warm_start(rc_wheelset* wheelset);
/* Where the wheelset's evaluations spent their time (rc_wheelset_time_stages; docs/WHEELSET.md §8
   "Where a step's time goes"): wall-clock seconds per stage, summed over the rc_wheelset_evaluate
   calls since timing was switched on (failed ones too). Each interval counts in one stage, the
   innermost running, so the stages add up to the evaluations' time. */
typedef struct rc_wheelset_stage_times {
  double search_s;      /* contact search: each wheel's contact locus, its overlap regions, first touch */
  double area_s;        /* the potential contact areas and their undeformed distance */
  double normal_s;      /* normal problems (contact windows, their checks, whole areas, coupling) */
  double height_s;      /* BY_LOAD: the heights' and balances' own steps (their trials' stages not) */
  double kinematics_s;  /* each patch's creepage point, frame, kinematic creepages */
  double tangential_s;  /* the tangential solvers, with their patches made from the pressure */
  double assembly_s;    /* the rest: checks of the input, the patches' other numbers, the sums */
  long long evaluations; /* rc_wheelset_evaluate calls timed */
} rc_wheelset_stage_times;
/* Times the stages of every rc_wheelset_evaluate from now on (on != 0) or stops (on == 0); either
   way the times start again from zero. Off by default; on costs a clock reading at every change of
   stage (about 1 us a step). Batches and the wheelset table are not timed. */
RC_API rc_status rc_wheelset_time_stages(rc_wheelset* wheelset, int on);
RC_API rc_status rc_wheelset_stage_times_get(const rc_wheelset* wheelset, rc_wheelset_stage_times* times);
/* The last evaluation's totals and solved state. */
RC_API rc_status rc_wheelset_result_get(const rc_wheelset* wheelset, rc_wheelset_result* result);
/* The wheels' angular velocity of the last evaluation (rad/s, + rolling forward): RC_ROTATION_FREE's
   solution, the given one, or pure rolling's V (1 - xi0/2) / ((1 + xi0/2) r0). */
RC_API rc_status rc_wheelset_wheel_angular_velocity(const rc_wheelset* wheelset, double* rad_per_s);
/* The number of patches of a wheel (side: rc_wheel_side) in the last evaluation. */
RC_API rc_status rc_wheelset_patch_count(const rc_wheelset* wheelset, int side, size_t* count);
/* Copies the patches of a wheel, along the rail profile (gauge side first), into the caller's
   buffer of `size` entries; RC_BUFFER_TOO_SMALL when size < rc_wheelset_patch_count. */
RC_API rc_status rc_wheelset_patches(const rc_wheelset* wheelset, int side, size_t size,
                                     rc_wheelset_patch* patches);

/* Many states at once on `threads` threads (1 = the calling thread only; 0 = the machine's
   hardware threads), one wheelset per thread with this wheelset's track and options. Each state
   is evaluated from a cold start: the results equal those of the serial loop of
   rc_wheelset_evaluate with warm_start = 0, bit for bit, whatever the threads. Outputs:
   results (count entries, required); patches (may be null when patches_per_wheel is 0): state k,
   wheel w, patch j at patches[(2 k + w) patches_per_wheel + j]; statuses (count entries, may be
   null). With patches given, a state with more patches on a wheel than patches_per_wheel has
   RC_BUFFER_TOO_SMALL (its results entry is filled: patch_count gives the size needed). Returns RC_OK when every
   state succeeded, else the status of the first failed state, whose message ("state K: ...")
   is the wheelset's last error. This wheelset's warm start and last result are unchanged. */
RC_API rc_status rc_wheelset_batch_evaluate(rc_wheelset* wheelset, size_t count, const rc_wheelset_state* states,
                                            int threads, rc_wheelset_result* results, size_t patches_per_wheel,
                                            rc_wheelset_patch* patches, int* statuses);

/* ---- The wheelset table (docs/WHEELSET_TABLE.md) ---------------------------------------------
   A wheelset's patches precomputed over a grid of lateral displacement y, yaw and wheel load, so
   that a state is evaluated in microseconds: the kinematic creepages of the state on each node's
   patches, FastSim with the node's nH-FastSim flexibilities, the forces interpolated between the
   nodes. A wheelset holds at most one table; it serves rc_wheelset_evaluate_table. The table is
   used only with what it was built for: the track (four profile files, dimensions) and the options
   youngs_modulus_Pa, poisson_ratio, element_size_m and slip_direction (and nH-FastSim's recipe of
   this railcontact). rc_wheelset_set_default_track, rc_wheelset_set_track,
   rc_wheelset_set_track_profiles and rc_wheelset_set_options keep the table while these are its;
   a call that changes one of them drops the table, and rc_wheelset_evaluate_table then fails
   naming that call and what differs. Loads, friction, solvers and the other flags do not matter
   to the table. */

/* Builds the table of this wheelset's track with its options (material, element size) over the
   grid: y_m (m), yaw_rad (rad, |yaw| <= 0.1; one value, e.g. 0, serves every yaw by turning the
   contact point) and loads_N (N per wheel), each strictly increasing; about 0.2-0.5 s per node
   (y_count x yaw_count x load_count nodes, at most 20000). progress (may be null) is called after
   each node; a non-zero return cancels (RC_CANCELLED). Nodes that cannot be solved are gaps:
   evaluations next to them fail, naming the node. Replaces a table the wheelset had. */
RC_API rc_status rc_wheelset_table_build(rc_wheelset* wheelset, const double* y_m, size_t y_count, const double* yaw_rad,
                                         size_t yaw_count, const double* loads_N, size_t load_count,
                                         rc_progress_callback progress, void* user_data);
/* The y refinement of the wheelset's next table builds (docs/WHEELSET_TABLE.md §3 "Where the
   contact jumps"): y nodes are added, halving the steps up to three times, around a node whose
   wheel's lateral normal force lies further than lateral_force_fraction of its load from the line
   between its neighbours (a flange snapping in, a second contact appearing). 0.01 (the default, for
   a table that runs into the flange); 0: none; in [0, 1]. The progress callback's total grows as
   nodes are added. */
RC_API rc_status rc_wheelset_table_set_refinement(rc_wheelset* wheelset, double lateral_force_fraction);
/* Loads a table file (`railcontact wheelset-table build`, rc_wheelset_table_save) and checks that it
   was built for this wheelset's track (its four profile files (hashes) and dimensions) and options
   (material, element size, slip direction, nH-FastSim's recipe): RC_INVALID_INPUT naming each
   difference, e.g. "element-size 0.2 mm (rc_wheelset_options: element_size_m) differs from the
   table's 0.5 mm"; the wheelset keeps the table it had. */
RC_API rc_status rc_wheelset_table_load(rc_wheelset* wheelset, const char* path);
/* Writes the wheelset's table (JSON, docs/WHEELSET_TABLE.md §4). */
RC_API rc_status rc_wheelset_table_save(const rc_wheelset* wheelset, const char* path);
/* The grid of the wheelset's table: the number of y, yaw and load values (each may be null). */
RC_API rc_status rc_wheelset_table_size(const rc_wheelset* wheelset, size_t* y_count, size_t* yaw_count,
                                        size_t* load_count);

/* Evaluates a state from the table: each wheel carries its load of the options (right_load_N,
   left_load_N; normal_mode must be RC_WHEELSET_BY_LOAD), the friction coefficient is the options',
   the solver nh-fastsim (one entry in each patch's forces). The state's z is not used; its roll_rad
   must be 0 (the nodes have zero roll).
   RC_INVALID_INPUT when y, yaw (with several yaw values) or a load lies outside the grid or a node
   needed is a gap. The result and patches are queried as after rc_wheelset_evaluate. Thread-safe
   against other wheelsets; the table itself is not modified. */
RC_API rc_status rc_wheelset_evaluate_table(rc_wheelset* wheelset, const rc_wheelset_state* state,
                                            rc_wheelset_result* result);

#ifdef __cplusplus
}
#endif

#endif /* RAILCONTACT_H */
