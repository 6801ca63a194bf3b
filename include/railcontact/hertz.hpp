#pragma once
// Hertz's solution for two quasi-identical elastic bodies whose undeformed distance is
// h(x1, x2) = A x1^2 + B x2^2 (A, B > 0: the relative curvatures halved), Johnson,
// Contact Mechanics (1985) §4.2. Semi-axis a lies along X1 (rolling), b along X2.
#include <string_view>

#include "railcontact/contact_patch.hpp"

namespace railcontact {

// The physical range of the relative curvatures A, B of h = A x1^2 + B x2^2 (half the sum of the
// bodies' curvatures; docs/RELIABILITY.md "Values and solvers"; the range of the ellipse they give
// is in contact_patch.hpp, kMinimumSemiAxis_m ...): [1e-3, 1e4] 1/m, radii from 500 m (a nearly
// flat, conformal contact) down to 50 um (a sharp edge; below, the surface is a corner, not a curve
// Hertz's theory can describe). A railway wheel gives A = 1 / (2 r0) = 1.1 1/m, the rail head's
// crown and gauge corner B = 1.7 ... 40 1/m.
inline constexpr double kMinimumRelativeCurvature_per_m = 1e-3;
inline constexpr double kMaximumRelativeCurvature_per_m = 1e4;
// Throws Error (invalid_input) unless value lies in [kMinimumRelativeCurvature_per_m,
// kMaximumRelativeCurvature_per_m].
void validate_relative_curvature(double value_per_m, std::string_view name);

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
// A = B (circle) and robust for very slender ellipses. Throws railcontact::Error unless A, B lie in
// [kMinimumRelativeCurvature_per_m, kMaximumRelativeCurvature_per_m], F3 lies in
// [kMinimumNormalForce_N, kMaximumNormalForce_N] (1 N ... 1e7 N, contact_patch.hpp), the material is
// valid and the ellipse they give has semi-axes in [kMinimumSemiAxis_m, kMaximumSemiAxis_m] and
// p0 <= kMaximumHertzPressure_Pa (the message names A, B, F3 and E); any axis ratio.
HertzContact hertz_from_curvatures(double A_per_m, double B_per_m, double normal_force_N, const Material& material);

// The curvatures (A, B) that give semi-axes a, b under normal force F3: inverse of the above
// (closed form, no iteration). Throws railcontact::Error unless a, b lie in [kMinimumSemiAxis_m,
// kMaximumSemiAxis_m], F3 in [kMinimumNormalForce_N, kMaximumNormalForce_N] and the ellipse passes
// validate_hertz_pressure (any axis ratio).
struct HertzCurvatures {
  double A_per_m = 0.0;
  double B_per_m = 0.0;
};
HertzCurvatures hertz_curvatures_for_semi_axes(double a_m, double b_m, double normal_force_N, const Material& material);

// Hertz's contact of the ellipse with semi-axes a, b under F3 (p0 and the approach; closed form):
// hertz_from_curvatures of hertz_curvatures_for_semi_axes without the curvatures' range (a valid
// ellipse under a small load has curvatures below kMinimumRelativeCurvature_per_m). The same checks
// as hertz_curvatures_for_semi_axes.
HertzContact hertz_from_semi_axes(double a_m, double b_m, double normal_force_N, const Material& material);

}  // namespace railcontact
