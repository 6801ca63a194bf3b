#pragma once
// Carter's two-dimensional steady rolling contact (Carter 1926; Johnson, Contact Mechanics §8.2),
// an independent closed-form reference for the frictional solvers.
//
// Two equal elastic cylinders (plane strain) with the 2-D Hertz pressure p3 = p0 sqrt(1 - x^2/a^2)
// roll with creepage xi. With friction mu the traction is mu p3 minus Carter's correction over the
// adhesion zone, which lies at the leading edge with half-length a' = a (1 - xi/xi_c), and
//   F / (mu P) = 1 - (1 - xi/xi_c)^2   (xi <= xi_c, else 1),   P = pi a p0 / 2 per unit width,
//   xi_c = 2 (1 - nu) mu p0 / G.
// (From the surface strain of a tangential traction q on the combined half-planes,
// du1/dx = -(2 (1 - nu) / (pi G)) PV int q(s) / (x - s) ds; for q = mu p0 sqrt(1 - s^2/a^2) it is
// 2 (1 - nu) mu p0 x / (G a). With equal materials xi_c equals Carter's mu a / R.)
//
// A patch much wider than long along X2 with this pressure on every strip behaves as the 2-D
// contact away from its lateral ends.
#include <cmath>
#include <vector>

#include "railcontact/contact_patch.hpp"

namespace railcontact::testing {

struct CarterContact {
  ContactPatch patch;
  double a_m = 0.0;          // half-length along X1
  double p0_Pa = 0.0;        // peak pressure
  double xi_c = 0.0;         // creepage of full slip, 2 (1 - nu) mu p0 / G
  int centre_strip = 0;      // mesh row at x2 = 0
};

// n1 x n2 elements covering [-a, a] x [-width/2, width/2]; n2 odd puts a strip at x2 = 0.
inline CarterContact carter_contact(double a_m, double width_m, int n1, int n2, const Material& material, double mu,
                                    double p0_Pa = 800e6) {
  const Mesh mesh = Mesh::covering(-a_m, a_m, -0.5 * width_m, 0.5 * width_m, n1, n2);
  std::vector<double> pressure(mesh.size());
  for (int i2 = 0; i2 < n2; ++i2)
    for (int i1 = 0; i1 < n1; ++i1) {
      const double x = mesh.x1(i1);
      pressure[mesh.index(i1, i2)] = p0_Pa * std::sqrt(std::max(0.0, 1.0 - x * x / (a_m * a_m)));
    }
  const double nu = material.poisson_ratio, G = material.shear_modulus_Pa();
  return {ContactPatch(mesh, pressure, material), a_m, p0_Pa, 2.0 * (1.0 - nu) * mu * p0_Pa / G, n2 / 2};
}

// Carter's F / (mu P) at xi / xi_c = r >= 0.
inline double carter_force_ratio(double r) { return r >= 1.0 ? 1.0 : 1.0 - (1.0 - r) * (1.0 - r); }

}  // namespace railcontact::testing
