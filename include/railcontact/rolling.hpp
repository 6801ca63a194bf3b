#pragma once
// Exact steady-state rolling with Coulomb friction on a contact patch (paper §2.2 and Appendix;
// METHOD.md §8): the reference the simplified methods are measured against.
//
// Slip per unit rolling speed at the collocation points: s = w - R p (Eq 10, sign derived in
// docs/CONVENTIONS.md), w = (xi - phi x2, eta + phi x1). Two friction laws:
//  - exact Coulomb: adhesion where |p| < mu p3 and s = 0; slip where |p| = mu p3 and p = -mu p3 s/|s|;
//  - regularised Coulomb (Eq A1): p = -(2 mu p3 / pi) atan(|s|/epsilon) s/|s|.
// Both are solved by Newton's method with GMRES on the FFT operator (docs/ROLLING.md).
#include <cstdint>
#include <vector>

#include "railcontact/creepage.hpp"
#include "railcontact/patch.hpp"

namespace railcontact {

struct RollingOptions {
  double collocation_offset = 0.0;  // alpha (METHOD.md §3), the same as the adhesion solver's
  double tolerance = 1e-9;          // Newton: max residual relative to mu max(p3)
  int max_newton_iterations = 100;
  double krylov_tolerance = 1e-6;   // inner GMRES, relative
  int max_krylov_iterations = 300;
  // Regularised law only: epsilon as a slip velocity per unit rolling speed (dimensionless;
  // equals the paper's epsilon in m/s at V = 1 m/s). The paper uses 1e-8.
  double regularisation = 1e-8;
};

struct RollingSolution {
  TangentialForces forces;
  // Per contact element, in the order of patch.elements().indices():
  std::vector<double> p1_Pa, p2_Pa;     // tangential traction on the wheel
  std::vector<double> s1, s2;           // slip velocity per unit rolling speed (-)
  std::vector<std::uint8_t> slip;       // 1 where the element slips (|p| at the traction bound)
  double adhesion_fraction = 0.0;       // share of the contact area in adhesion
  int newton_iterations = 0;
  int krylov_iterations = 0;            // all inner GMRES iterations
  double residual = 0.0;                // final Newton residual, relative to mu max(p3)
  bool converged = false;
};

// Throws railcontact::Error on bad input (mu <= 0 or not finite, non-finite creepage) and when
// Newton does not converge within max_newton_iterations.
RollingSolution solve_rolling_exact(const ContactPatch& patch, const Creepage& creepage, double mu,
                                    const RollingOptions& options = {});
RollingSolution solve_rolling_regularised(const ContactPatch& patch, const Creepage& creepage, double mu,
                                          const RollingOptions& options = {});

}  // namespace railcontact
