#pragma once
// Full-adhesion steady-state rolling on an arbitrary set of contact elements (paper §2.2,
// Eq 10-18; METHOD.md §6): the non-Hertzian analogue of Kalker's linear theory.
//
// Steady rolling in +X1 (leading edge at the largest x1): the slip velocity at the collocation
// points is s = V (w - R p), R the upwind X1-difference of the tangential influence (the
// paper's (A - A0)/dx1 of Eq 10) and w = (xi - phi x2, eta + phi x1) the rigid slip (Eq 11-12).
// Full adhesion, s = 0: R p = D^T (xi, eta, phi)  (Eq 14), and the creepage-coefficient matrix
//   K2 = S D R^-1 D^T  (Eq 18),  (F1, F2, M3) = K2 (xi, eta, phi)  (Eq 13, 15).
// With this sign convention K2 has the pattern of Kalker's K1 (Eq 16): negative diagonal.
// Coordinates are the mesh's: put the origin at the pressure centre (METHOD.md §2).
#include <Eigen/Core>
#include <optional>

#include "railcontact/creepage.hpp"
#include "railcontact/material.hpp"
#include "railcontact/mesh.hpp"

namespace railcontact {

enum class LinearSolver {
  krylov,  // GMRES on the FFT operator, preconditioned by strip marching (fast path)
  dense,   // dense LU (reference path; O(N^3))
};

// Where the rigid slip w is evaluated along X1 for each element.
enum class RigidSlipPoint {
  collocation,         // at the collocation point x1 + alpha dx1/2 (the paper)
  difference_centre,   // at the centre of the upwind difference, x1 + (alpha + 1) dx1/2
};

// Preconditioner of the Krylov path (see src/tangential/steady_rolling_preconditioner.hpp).
enum class AdhesionPreconditioner {
  marching_half_laplacian,  // FastSim marching followed by c0 - Laplacian (default)
  marching,                 // FastSim marching alone
};

// What to compute of K2.
enum class CreepageMatrixPart {
  full,        // all of K2 and the tractions: one direct solve R p = D^T e_j per creepage (3 solves)
  // Rows 1 and 2 (F1 and F2 per unit xi, eta, phi) by adjoint solves R^T y = (S D)^T e_i, one per
  // force (2 solves): all term-by-term nH-FastSim needs (K2_11, K2_22, K2_23) and the
  // normalisation of Eq 22-23 (f11, f22). Row 3 (M3) is NaN and no tractions are returned.
  force_rows,
};

struct AdhesionOptions {
  double collocation_offset = 0.0;  // alpha in (-1, 1]: collocation point at x1 + alpha dx1/2 (METHOD.md §3)
  // Collocation offset for the spin column of K2 only (unit phi); unset = collocation_offset.
  // The paper (Fig 3) finds alpha = 0 best for C11, C22 and alpha = 0.5 best for C23; each
  // column of K2 is a separate solve, so each may use its own offset.
  std::optional<double> spin_collocation_offset;
  RigidSlipPoint rigid_slip_point = RigidSlipPoint::collocation;
  LinearSolver solver = LinearSolver::krylov;
  double tolerance = 1e-10;         // Krylov: relative residual
  int max_iterations = 400;         // Krylov
  AdhesionPreconditioner preconditioner = AdhesionPreconditioner::marching_half_laplacian;
  // marching_half_laplacian's shift c0 = gamma pi^2 / (patch size sqrt(dx1 dx2)); 3 is best for
  // tight solves on ellipses (steady_rolling_preconditioner.hpp).
  double half_laplacian_gamma = 3.0;
  CreepageMatrixPart part = CreepageMatrixPart::full;
};

struct AdhesionSolution {
  // (F1, F2, M3) = K2 (xi, eta, phi): units N, N, N m per unit xi, eta and per 1/m of phi.
  Eigen::Matrix3d creepage_matrix;
  // Tractions (Pa) per unit creepage: column j for creepage j (xi, eta, phi); rows
  // [p1 on elements 0..N-1, p2 on elements 0..N-1] in the order of ContactElements::indices().
  Eigen::MatrixXd unit_tractions;
  int iterations = 0;               // Krylov iterations, all three right-hand sides
  double relative_residual = 0.0;   // largest over the right-hand sides
};

// Throws railcontact::Error on bad input (no elements, bad material, alpha outside (-1, 1];
// alpha = -1 centres the difference on the element and decouples odd and even elements)
// or when the Krylov solver does not converge.
AdhesionSolution solve_full_adhesion(const ContactElements& elements, const Material& material,
                                     const AdhesionOptions& options = {});

// Kalker's creepage coefficients from K2 with c = sqrt(a b) (paper §3, METHOD.md §2):
// C11 = -K2_11/(G c^2), C22 = -K2_22/(G c^2), C23 = -K2_23/(G c^3), C33 = -K2_33/(G c^4).
struct CreepageCoefficients {
  double C11 = 0.0, C22 = 0.0, C23 = 0.0, C33 = 0.0;
};
CreepageCoefficients creepage_coefficients(const Eigen::Matrix3d& creepage_matrix, double shear_modulus_Pa, double c_m);

}  // namespace railcontact
