#pragma once
// Kalker's creepage coefficients computed numerically: K2 (Eq 18) on an elliptical patch on a
// regular mesh, converted with c = sqrt(a b) (paper §3). Compares directly with Kalker's table.
#include <cstddef>

#include "railcontact/adhesion.hpp"
#include "railcontact/ellipse.hpp"

namespace railcontact {

struct EllipseCoefficientOptions {
  int target_elements = 2800;  // about this many elements in contact
  EllipseMeshLayout layout = EllipseMeshLayout::rolling_resolved;
  AdhesionOptions adhesion = default_adhesion_for_coefficients();
  // false: c = sqrt(a b) of the ellipse (the paper). true: c from the discrete patch's area,
  // c^2 = N S / pi, which removes the staircase-area error of the mesh from the comparison.
  bool c_from_discrete_area = false;

  // alpha = 0 for the xi and eta columns, alpha = 0.5 for the spin column (paper Fig 3).
  static AdhesionOptions default_adhesion_for_coefficients() {
    AdhesionOptions options;
    options.spin_collocation_offset = 0.5;
    return options;
  }
};

struct EllipseCoefficientResult {
  CreepageCoefficients coefficients;
  Eigen::Matrix3d creepage_matrix;
  std::size_t elements_in_contact = 0;
  int n1 = 0, n2 = 0;               // mesh over the bounding box
  double area_error = 0.0;          // (N S - pi a b) / (pi a b)
  int iterations = 0;
  double solve_time_s = 0.0;        // K2 (operator set-up and the three solves)
};

// For semi-axis ratio a/b (a along X1) and Poisson's ratio nu in [0, 0.5); E = 2.1e11 Pa and
// c = sqrt(a b) = 6 mm (the coefficients do not depend on either).
EllipseCoefficientResult ellipse_creepage_coefficients(double a_over_b, double nu,
                                                       const EllipseCoefficientOptions& options = {});

}  // namespace railcontact
