/* The C API's handles created, used and destroyed in every order (ctest c_api.valgrind, run under
 * valgrind by tests/install/valgrind_test.sh; docs/C_API.md "Memory"):
 *   - round 0: a flexibility table is built and sets a solver's patch; the table is destroyed
 *     first and the solver solves again (a table must outlive rc_solver_set_patch_flextable only);
 *   - rounds 1-6: a solver, a table and a wheelset, each used (a solve, a batch on two threads, a
 *     failed load with its message, a wheelset evaluation) and left with a pending error message,
 *     destroyed in each of the 3! orders;
 *   - destroying null handles.
 * Small meshes keep it quick under valgrind. Exit 0 when every call gave the status expected. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <railcontact/railcontact.h>

static int failures = 0;

static void expect(int ok, const char* what) {
  if (!ok) {
    fprintf(stderr, "handles: %s failed\n", what);
    ++failures;
  }
}

static rc_solver* new_solver(void) {
  rc_solver* solver = NULL;
  expect(rc_solver_create(&solver) == RC_OK && solver != NULL, "rc_solver_create");
  rc_settings settings;
  rc_settings_default(&settings);
  settings.mesh_value = 300;
  expect(rc_solver_set_settings(solver, &settings) == RC_OK, "rc_solver_set_settings");
  return solver;
}

static void use_solver(rc_solver* solver) {
  expect(rc_solver_set_ellipse(solver, 6e-3, 4e-3, 80e3) == RC_OK, "rc_solver_set_ellipse");
  const rc_creepage c = {1e-3, 5e-4, 0.3};
  rc_forces f;
  expect(rc_solver_solve(solver, &c, &f) == RC_OK && f.F1_N < 0, "rc_solver_solve");
  rc_creepage batch[8];
  rc_forces forces[8];
  int statuses[8];
  rc_patch patch;
  memset(&patch, 0, sizeof patch);
  patch.kind = RC_GEOMETRY_ELLIPSE;
  patch.a_m = 6e-3;
  patch.b_m = 4e-3;
  patch.normal_force_N = 80e3;
  for (int k = 0; k < 8; ++k) batch[k] = (rc_creepage){1e-4 * k, 0.0, 0.0};
  batch[5].xi = NAN; /* one failed state: its message */
  expect(rc_batch_creep_forces(solver, 8, &patch, 1, batch, 2, forces, NULL, NULL, statuses) == RC_INVALID_INPUT &&
             statuses[5] == RC_INVALID_INPUT && statuses[4] == RC_OK,
         "rc_batch_creep_forces on two threads");
  size_t length = 0; /* the length query: the message does not fit a buffer of size 0 */
  expect(rc_solver_last_error(solver, NULL, 0, &length) == RC_BUFFER_TOO_SMALL && length > 0, "rc_solver_last_error");
}

static void use_table(rc_flextable* table) {
  expect(rc_flextable_load(table, "/nonexistent/railcontact-table.json", NULL) == RC_IO, "rc_flextable_load");
  char message[256];
  expect(rc_flextable_last_error(table, message, sizeof message, NULL) == RC_OK && strlen(message) > 0,
         "rc_flextable_last_error");
}

static rc_wheelset* new_wheelset(void) {
  rc_wheelset* wheelset = NULL;
  expect(rc_wheelset_create(&wheelset) == RC_OK && wheelset != NULL, "rc_wheelset_create");
  expect(rc_wheelset_set_default_track(wheelset) == RC_OK, "rc_wheelset_set_default_track");
  rc_wheelset_options options;
  rc_wheelset_options_default(&options);
  options.element_size_m = 1e-3;
  options.normal_mode = RC_WHEELSET_BY_POSITION;
  options.allow_wheel_lift = 1;
  expect(rc_wheelset_set_options(wheelset, &options) == RC_OK, "rc_wheelset_set_options");
  return wheelset;
}

static void use_wheelset(rc_wheelset* wheelset) {
  rc_wheelset_state state;
  rc_wheelset_state_default(&state);
  state.z_m = -0.05e-3; /* 0.05 mm below the nominal height: both wheels touch */
  rc_wheelset_result result;
  expect(rc_wheelset_evaluate(wheelset, &state, &result) == RC_OK && result.patch_count[0] > 0, "rc_wheelset_evaluate");
  rc_wheelset_patch patch;
  expect(rc_wheelset_patches(wheelset, RC_WHEEL_RIGHT, 1, &patch) == RC_OK, "rc_wheelset_patches");
  state.yaw_rad = 1.0; /* out of range: a pending message */
  expect(rc_wheelset_evaluate(wheelset, &state, &result) == RC_INVALID_INPUT, "rc_wheelset_evaluate, bad yaw");
}

/* Round 0: the table built, used by a solver, destroyed before the solver. */
static void table_before_solver(void) {
  rc_flextable* table = NULL;
  expect(rc_flextable_create(&table) == RC_OK, "rc_flextable_create");
  const double y[] = {0.0, 0.5e-3};
  const double load[] = {98100.0};
  expect(rc_flextable_build(table, NULL, y, 2, load, 1, 300, 2.1e11, 0.3, NULL, NULL) == RC_OK, "rc_flextable_build");
  rc_flextable_values values;
  expect(rc_flextable_lookup(table, 0.25e-3, 98100.0, &values) == RC_OK && values.L1_m_per_Pa > 0,
         "rc_flextable_lookup");
  rc_solver* solver = new_solver();
  expect(rc_solver_set_patch_flextable(solver, table, 0.25e-3, 98100.0) == RC_OK, "rc_solver_set_patch_flextable");
  expect(rc_flextable_destroy(table) == RC_OK, "rc_flextable_destroy");
  const rc_creepage c = {1e-3, 0.0, 0.0};
  rc_forces f;
  expect(rc_solver_solve(solver, &c, &f) == RC_OK && f.F1_N < 0, "rc_solver_solve after the table's destruction");
  expect(rc_solver_destroy(solver) == RC_OK, "rc_solver_destroy");
}

int main(void) {
  table_before_solver();
  static const int orders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int round = 0; round < 6; ++round) {
    rc_solver* solver = new_solver();
    rc_flextable* table = NULL;
    expect(rc_flextable_create(&table) == RC_OK, "rc_flextable_create");
    rc_wheelset* wheelset = new_wheelset();
    use_solver(solver);
    use_table(table);
    if (round == 0 || round == 5) use_wheelset(wheelset); /* the costly one: twice */
    for (int k = 0; k < 3; ++k) {
      switch (orders[round][k]) {
        case 0: expect(rc_solver_destroy(solver) == RC_OK, "rc_solver_destroy"); break;
        case 1: expect(rc_flextable_destroy(table) == RC_OK, "rc_flextable_destroy"); break;
        default: expect(rc_wheelset_destroy(wheelset) == RC_OK, "rc_wheelset_destroy"); break;
      }
    }
  }
  expect(rc_solver_destroy(NULL) == RC_OK && rc_flextable_destroy(NULL) == RC_OK && rc_wheelset_destroy(NULL) == RC_OK,
         "destroying null handles");
  printf("handles: 7 rounds, %d failure%s\n", failures, failures == 1 ? "" : "s");
  return failures == 0 ? 0 : 1;
}
