/* ABI check of railcontact/railcontact.h (ctest c_api.abi_c, c_api.abi_cxx): compiled with
   gcc -std=c11 -Wall -Wextra -pedantic -Werror and as C++ with g++. The layouts below are the ABI
   of RC_ABI_VERSION 4: a change that breaks one of them must raise RAILCONTACT_ABI_VERSION in
   CMakeLists.txt (and these numbers). x86-64 / AArch64 (LP64) layouts. */
#include <stddef.h>

#include "railcontact/railcontact.h"

#ifdef __cplusplus
#define RC_STATIC_ASSERT static_assert
#else
#define RC_STATIC_ASSERT _Static_assert
#endif

RC_STATIC_ASSERT(RC_ABI_VERSION == 4, "the layouts below are those of ABI version 4");
RC_STATIC_ASSERT(sizeof(rc_status) == sizeof(int), "enumerations are int-sized");
RC_STATIC_ASSERT(sizeof(rc_method) == sizeof(int), "enumerations are int-sized");
RC_STATIC_ASSERT(RC_OK == 0 && RC_INVALID_INPUT == 1 && RC_INTERNAL == 6 && RC_CANCELLED == 9, "status values");
RC_STATIC_ASSERT(RC_METHOD_EXACT_REGULARISED == 3 && RC_MESH_ELEMENT_SIZE == 2 && RC_GEOMETRY_GRID == 2,
                 "enumeration values");
RC_STATIC_ASSERT(sizeof(rc_settings) == 12 * 8 + 7 * 4 + 4, "rc_settings: 12 doubles, 7 ints, 4 bytes padding");
RC_STATIC_ASSERT(offsetof(rc_settings, method) == 96, "rc_settings.method");
RC_STATIC_ASSERT(offsetof(rc_settings, slip_direction) == 108, "rc_settings.slip_direction");
RC_STATIC_ASSERT(offsetof(rc_settings, normal_max_iterations) == 120, "rc_settings.normal_max_iterations");
RC_STATIC_ASSERT(sizeof(rc_patch) == 7 * 8 + sizeof(void*) + 4 * 4, "rc_patch");
RC_STATIC_ASSERT(offsetof(rc_patch, grid_h_m) == 56 && offsetof(rc_patch, kind) == 64, "rc_patch fields");
RC_STATIC_ASSERT(sizeof(rc_creepage) == 3 * 8, "rc_creepage");
RC_STATIC_ASSERT(sizeof(rc_forces) == 4 * 8, "rc_forces");
RC_STATIC_ASSERT(sizeof(rc_normal_result) == 12 * 8 + 4 * 4, "rc_normal_result");
RC_STATIC_ASSERT(offsetof(rc_normal_result, n1) == 96, "rc_normal_result.n1");
RC_STATIC_ASSERT(sizeof(rc_flextable_values) == 10 * 8, "rc_flextable_values");
RC_STATIC_ASSERT(sizeof(rc_flextable_info) == 6 * 8 + 4 * 4, "rc_flextable_info");
RC_STATIC_ASSERT(RC_SLIP_RADIAL == 0 && RC_SLIP_FLEXIBILITY_WEIGHTED == 1 && RC_SLIP_RIGID == 2, "slip direction values");
RC_STATIC_ASSERT(RC_WHEEL_LEFT == 1 && RC_WHEELSET_BY_POSITION == 1 && RC_ROTATION_GIVEN == 1,
                 "wheelset enumeration values");
RC_STATIC_ASSERT(sizeof(rc_track_parameters) == 6 * 8 + 4 + 4 + 8,
                 "rc_track_parameters: 6 doubles, 1 int, 4 bytes padding, 1 double");
RC_STATIC_ASSERT(offsetof(rc_track_parameters, nominal_radius_at) == 48 &&
                     offsetof(rc_track_parameters, rail_cant_rad) == 56,
                 "rc_track_parameters.nominal_radius_at, rail_cant_rad");
RC_STATIC_ASSERT(RC_RADIUS_AT_TAPING_LINE == 1 && RC_WEIGHTING_DEPTH == 1, "datum and weighting values");
RC_STATIC_ASSERT(RC_SURFACE_PLANAR == 0 && RC_SURFACE_CONFORMAL == 1 && RC_SURFACE_AUTO == 2, "contact surface values");
RC_STATIC_ASSERT(sizeof(rc_wheelset_options) == 6 * 8 + 14 * 4, "rc_wheelset_options: 6 doubles, 14 ints");
RC_STATIC_ASSERT(offsetof(rc_wheelset_options, contact_surface) == 100, "rc_wheelset_options.contact_surface");
RC_STATIC_ASSERT(offsetof(rc_wheelset_options, balance_solver) == 92 &&
                     offsetof(rc_wheelset_options, reference_weighting) == 96,
                 "rc_wheelset_options.balance_solver, reference_weighting");
RC_STATIC_ASSERT(offsetof(rc_wheelset_options, normal_mode) == 48 &&
                     offsetof(rc_wheelset_options, slip_direction) == 68 && offsetof(rc_wheelset_options, solvers) == 76,
                 "rc_wheelset_options fields");
RC_STATIC_ASSERT(sizeof(rc_wheelset_state) == 11 * 8 + 2 * 4, "rc_wheelset_state: 11 doubles, 2 ints");
RC_STATIC_ASSERT(offsetof(rc_wheelset_state, rotation) == 88, "rc_wheelset_state.rotation");
RC_STATIC_ASSERT(sizeof(rc_wheelset_patch) == 53 * 8 + 4 * 4, "rc_wheelset_patch: 53 doubles, 4 ints");
RC_STATIC_ASSERT(offsetof(rc_wheelset_patch, forces) == 20 * 8 && offsetof(rc_wheelset_patch, pressure_force_track_N) == 384 &&
                     offsetof(rc_wheelset_patch, conformal_weight) == 416 && offsetof(rc_wheelset_patch, side) == 424,
                 "rc_wheelset_patch fields");
RC_STATIC_ASSERT(sizeof(rc_wheelset_result) == 13 * 8 + 4 * 4, "rc_wheelset_result: 13 doubles, 4 ints");
RC_STATIC_ASSERT(offsetof(rc_wheelset_result, patch_count) == 104, "rc_wheelset_result.patch_count");

/* Every function with its exact type. */
static void check_signatures(void) {
  const char* (*status_string)(int) = rc_status_string;
  rc_status (*solve)(rc_solver*, const rc_creepage*, rc_forces*) = rc_solver_solve;
  rc_status (*batch)(rc_solver*, size_t, const rc_patch*, size_t, const rc_creepage*, int, rc_forces*,
                     rc_normal_result*, double*, int*) = rc_batch_creep_forces;
  rc_status (*build)(rc_flextable*, const char*, const double*, size_t, const double*, size_t, int, double, double,
                     rc_progress_callback, void*) = rc_flextable_build;
  rc_status (*approach)(rc_solver*, const rc_patch*, double) = rc_solver_set_patch_at_approach;
  rc_status (*evaluate)(rc_wheelset*, const rc_wheelset_state*, rc_wheelset_result*) = rc_wheelset_evaluate;
  rc_status (*patches)(const rc_wheelset*, int, size_t, rc_wheelset_patch*) = rc_wheelset_patches;
  rc_status (*wheelset_batch)(rc_wheelset*, size_t, const rc_wheelset_state*, int, rc_wheelset_result*, size_t,
                              rc_wheelset_patch*, int*) = rc_wheelset_batch_evaluate;
  (void)approach;
  (void)evaluate;
  (void)patches;
  (void)wheelset_batch;
  (void)status_string;
  (void)solve;
  (void)batch;
  (void)build;
}

int rc_abi_check_main(void);
int rc_abi_check_main(void) {
  check_signatures();
  return 0;
}
