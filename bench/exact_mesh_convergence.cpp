// The exact solver's convergence with the mesh on the S1002/UIC60 patch at y = 0
// (docs/VALIDATION.md §6; not a Google Benchmark program): pure spin (phi = 0.5 and 2 1/m) and
// xi = 1e-3 from about 700 to 45 000 elements in contact, forces / (mu F3); then Richardson's
// correction 2 F(h) - F(2h) with the second solve on the patch coarsened by 2.
//   build/bench/exact_mesh_convergence
#include <cstdio>

#include "railcontact/contact_patch.hpp"
#include "railcontact/tangential.hpp"
#include "railcontact/wheel_rail.hpp"

namespace {

using namespace railcontact;
constexpr double kMu = 0.3;

// The force along the creepage's main direction, / (mu F3).
double force(const ContactPatch& patch, const Creepage& creepage) {
  const TangentialForces f = solve_rolling_exact(patch, creepage, kMu).forces;
  return (creepage.xi != 0.0 ? f.F1_N : f.F2_N) / (kMu * patch.normal_force_N());
}

}  // namespace

int main() {
  const WheelRailPair pair = default_wheel_rail_pair();
  const Creepage creepages[] = {{0, 0, 0.5}, {0, 0, 2.0}, {1e-3, 0, 0}};
  std::printf("elements  dx1_mm  dx2_mm  F2(phi=0.5)  F2(phi=2)  F1(xi=1e-3)   [Richardson with the patch coarsened by 2]\n");
  for (const int target : {700, 1400, 2800, 5600, 11000, 22000, 45000}) {
    WheelRailPatchOptions options;
    options.target_elements = target;
    const WheelRailPatch wr = solve_wheel_rail_patch(pair, 0.0, options);
    const Mesh& mesh = wr.patch.elements().mesh();
    std::printf("%8zu  %.3f   %.3f ", wr.patch.elements().count(), 1e3 * mesh.dx1_m, 1e3 * mesh.dx2_m);
    const bool extrapolate = target >= 1400 && target <= 11000;
    const ContactPatch coarse = extrapolate ? coarsened(wr.patch, 2) : ContactPatch{};
    for (const Creepage& c : creepages) {
      const double fine = force(wr.patch, c);
      if (extrapolate)
        std::printf("  %.6f [%.6f]", fine, 2.0 * fine - force(coarse, c));
      else
        std::printf("  %.6f           ", fine);
    }
    std::printf("\n");
    std::fflush(stdout);
  }
  return 0;
}
