/* A minimal C program against the installed railcontact (ctest install.package; docs/C_API.md):
 *   gcc -std=c11 example.c $(pkg-config --cflags --libs railcontact)
 * Creep forces of nH-FastSim on a Hertzian ellipse, checked against Kalker's linear theory and
 * saturation; a bad input and its message; the default S1002/UIC60 wheelset at y = 0 carries its
 * wheel loads. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <railcontact/railcontact.h>

static int fail(rc_solver* solver, const char* what, rc_status status) {
  char message[512];
  rc_solver_last_error(solver, message, sizeof message, NULL);
  fprintf(stderr, "%s: %s: %s\n", what, rc_status_string(status), message);
  rc_solver_destroy(solver);
  return 1;
}

int main(void) {
  if (rc_abi_version() != RC_ABI_VERSION) {
    fprintf(stderr, "library ABI %d, header ABI %d\n", rc_abi_version(), RC_ABI_VERSION);
    return 1;
  }
  rc_solver* solver = NULL;
  rc_status status = rc_solver_create(&solver);
  if (status != RC_OK) return 1;
  rc_settings settings;
  rc_settings_default(&settings);
  settings.friction_coefficient = 0.3;
  settings.poisson_ratio = 0.25;
  settings.mesh_value = 1000; /* about 1000 elements in contact */
  if ((status = rc_solver_set_settings(solver, &settings)) != RC_OK) return fail(solver, "settings", status);
  /* a circle: a = b = 5 mm, F3 = 80 kN */
  if ((status = rc_solver_set_ellipse(solver, 5e-3, 5e-3, 80e3)) != RC_OK) return fail(solver, "patch", status);

  char message_buffer[512];
  rc_forces small, large;
  const rc_creepage c_small = {1e-5, 0.0, 0.0}, c_large = {0.05, 0.0, 0.0};
  if ((status = rc_solver_solve(solver, &c_small, &small)) != RC_OK) return fail(solver, "solve", status);
  if ((status = rc_solver_solve(solver, &c_large, &large)) != RC_OK) return fail(solver, "solve", status);
  /* Kalker's table: C11 = 4.12 for a/b = 1, nu = 0.25; F1 = -G a b C11 xi */
  const double G = 2.1e11 / (2 * 1.25), linear = -G * 5e-3 * 5e-3 * 4.12 * 1e-5;
  printf("railcontact %s: F1(xi = 1e-5) = %.2f N (Kalker %.2f N), F1(xi = 0.05) = %.1f N (-mu F3 = %.1f N)\n",
         rc_version_string(), small.F1_N, linear, large.F1_N, -0.3 * 80e3);
  if (fabs(small.F1_N / linear - 1) > 0.05 || fabs(large.F1_N / (-0.3 * 80e3) - 1) > 0.01) return 1;

  /* The default wheelset by load (98.1 kN per wheel), coarse elements. */
  rc_wheelset* wheelset = NULL;
  if (rc_wheelset_create(&wheelset) != RC_OK) return 1;
  rc_wheelset_options options;
  rc_wheelset_options_default(&options);
  options.element_size_m = 0.5e-3;
  rc_wheelset_state state;
  rc_wheelset_state_default(&state);
  rc_wheelset_result result;
  status = rc_wheelset_set_default_track(wheelset);
  if (status == RC_OK) status = rc_wheelset_set_options(wheelset, &options);
  if (status == RC_OK) status = rc_wheelset_evaluate(wheelset, &state, &result);
  if (status != RC_OK) {
    rc_wheelset_last_error(wheelset, message_buffer, sizeof message_buffer, NULL);
    fprintf(stderr, "wheelset: %s: %s\n", rc_status_string(status), message_buffer);
    rc_wheelset_destroy(wheelset);
    return 1;
  }
  printf("wheelset at y = 0: Fz = %.0f N (right), %.0f N (left), %d + %d patches\n", result.wheel_force_track_N[0][2],
         result.wheel_force_track_N[1][2], result.patch_count[0], result.patch_count[1]);
  rc_wheelset_destroy(wheelset);
  if (fabs(result.wheel_force_track_N[0][2] / 98.1e3 - 1) > 2e-3 || result.patch_count[0] < 1) return 1;

  const rc_creepage bad = {NAN, 0.0, 0.0};
  status = rc_solver_solve(solver, &bad, &small);
  char message[256];
  rc_solver_last_error(solver, message, sizeof message, NULL);
  printf("NaN creepage: %s: %s\n", rc_status_string(status), message);
  rc_solver_destroy(solver);
  return status == RC_INVALID_INPUT ? 0 : 1;
}
