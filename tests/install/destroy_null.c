/* Destroying a null handle does nothing and returns RC_OK, for each handle (ctest install.package,
 * built through pkg-config and run without LD_LIBRARY_PATH; docs/C_API.md "Handles"). Exit 0 when
 * each call gave RC_OK. */
#include <stdio.h>

#include <railcontact/railcontact.h>

int main(void) {
  const rc_status statuses[3] = {rc_solver_destroy(NULL), rc_flextable_destroy(NULL), rc_wheelset_destroy(NULL)};
  const char* names[3] = {"rc_solver_destroy", "rc_flextable_destroy", "rc_wheelset_destroy"};
  int failures = 0;
  for (int k = 0; k < 3; ++k)
    if (statuses[k] != RC_OK) {
      fprintf(stderr, "%s(NULL): %s\n", names[k], rc_status_string(statuses[k]));
      ++failures;
    }
  printf("destroy(NULL): %s\n", failures == 0 ? "no-op for every handle" : "FAILED");
  return failures == 0 ? 0 : 1;
}
