// A C++ program against the installed railcontact (ctest install.package): the C++ API and the
// C API in one program give the same creep forces.
#include <cmath>
#include <cstdio>

#include <railcontact/railcontact.h>
#include <railcontact/railcontact.hpp>

int main() {
  using namespace railcontact;
  const Material steel{2.1e11, 0.3};
  const ContactPatch patch =
      hertzian_patch(elliptical_contact_with_count(6e-3, 4e-3, 1000, EllipseMeshLayout::rolling_resolved), 6e-3, 4e-3,
                     80e3, steel);
  const TangentialForces cpp = NhFastSim(patch).forces(Creepage{1e-3, 0, 0}, 0.3);

  rc_solver* solver = nullptr;
  rc_solver_create(&solver);
  rc_settings settings;
  rc_settings_default(&settings);
  settings.mesh_value = 1000;
  rc_forces c{};
  const rc_creepage creepage{1e-3, 0, 0};
  const bool ok = rc_solver_set_settings(solver, &settings) == RC_OK &&
                  rc_solver_set_ellipse(solver, 6e-3, 4e-3, 80e3) == RC_OK &&
                  rc_solver_solve(solver, &creepage, &c) == RC_OK;
  rc_solver_destroy(solver);
  std::printf("C++ API F1 = %.6f N, C API F1 = %.6f N\n", cpp.F1_N, c.F1_N);
  try {
    (void)hertz_from_curvatures(-1.0, 1.0, 1e4, steel);
    return 1;
  } catch (const Error& e) {
    std::printf("caught railcontact::Error (%s): %s\n", std::string(error_kind_name(e.kind())).c_str(), e.what());
  }
  return ok && cpp.F1_N == c.F1_N ? 0 : 1;
}
