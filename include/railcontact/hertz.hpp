#pragma once
// Hertz's solution for two quasi-identical elastic bodies whose undeformed distance is
// h(x1, x2) = A x1^2 + B x2^2 (A, B > 0: the relative curvatures halved), Johnson,
// Contact Mechanics (1985) §4.2. Semi-axis a lies along X1 (rolling), b along X2.
#include "railcontact/contact_patch.hpp"

namespace railcontact {

struct HertzContact {
  double a_m = 0.0;                 // semi-axis along X1
  double b_m = 0.0;                 // semi-axis along X2
  double max_pressure_Pa = 0.0;     // p0 = 3 F3 / (2 pi a b)
  double approach_m = 0.0;          // mutual approach of distant points
  double normal_force_N = 0.0;
  [[nodiscard]] double a_over_b() const { return a_m / b_m; }
};

// Contact ellipse, pressure and approach for curvatures A, B (1/m) and normal force F3 (N).
// The longer semi-axis lies along the axis of the smaller curvature (a > b if A < B). Exact for
// A = B (circle) and robust for very slender ellipses. Throws railcontact::Error unless A, B are
// positive and finite, F3 lies in [kMinimumNormalForce_N, kMaximumNormalForce_N] (1 N ... 1e7 N,
// contact_patch.hpp) and the material is valid.
HertzContact hertz_from_curvatures(double A_per_m, double B_per_m, double normal_force_N, const Material& material);

// The curvatures (A, B) that give semi-axes a, b under normal force F3: inverse of the above
// (closed form, no iteration). Throws railcontact::Error unless a, b are positive and finite and
// F3 lies in [kMinimumNormalForce_N, kMaximumNormalForce_N].
struct HertzCurvatures {
  double A_per_m = 0.0;
  double B_per_m = 0.0;
};
HertzCurvatures hertz_curvatures_for_semi_axes(double a_m, double b_m, double normal_force_N, const Material& material);

}  // namespace railcontact
