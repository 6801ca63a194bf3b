// Closed-form influence coefficients of a uniformly loaded rectangle (METHOD.md §4).
#include "elastic/influence_coefficients.hpp"

#include "elastic/rectangle_antiderivatives.hpp"

#include <cmath>

namespace railcontact {
namespace {

// Sum over the corners of the element [-h1, h1] x [-h2, h2] seen from (x1, x2):
// ∫_{-h1}^{h1} ∫_{-h2}^{h2} k(x1 - s1, x2 - s2) ds2 ds1 = F(x1+h1, x2+h2) - F(x1-h1, x2+h2)
//                                                       - F(x1+h1, x2-h2) + F(x1-h1, x2-h2).
RectangleAntiderivatives rectangle_integrals(double x1, double x2, ElementSize element) {
  const double h1 = 0.5 * element.dx1_m;
  const double h2 = 0.5 * element.dx2_m;
  const RectangleAntiderivatives pp = rectangle_antiderivatives(x1 + h1, x2 + h2);
  const RectangleAntiderivatives mp = rectangle_antiderivatives(x1 - h1, x2 + h2);
  const RectangleAntiderivatives pm = rectangle_antiderivatives(x1 + h1, x2 - h2);
  const RectangleAntiderivatives mm = rectangle_antiderivatives(x1 - h1, x2 - h2);
  auto combine = [](double a, double b, double c, double d) { return a - b - c + d; };
  return {combine(pp.one_over_r, mp.one_over_r, pm.one_over_r, mm.one_over_r),
          combine(pp.x2_over_r3, mp.x2_over_r3, pm.x2_over_r3, mm.x2_over_r3),
          combine(pp.y2_over_r3, mp.y2_over_r3, pm.y2_over_r3, mm.y2_over_r3),
          combine(pp.xy_over_r3, mp.xy_over_r3, pm.xy_over_r3, mm.xy_over_r3)};
}

}  // namespace

double normal_influence(double x1_m, double x2_m, ElementSize element, const Material& material) {
  const double nu = material.poisson_ratio;
  const double G = material.shear_modulus_Pa();
  return (1.0 - nu) / (M_PI * G) * rectangle_integrals(x1_m, x2_m, element).one_over_r;
}

TangentialInfluence tangential_influence(double x1_m, double x2_m, ElementSize element, const Material& material) {
  const double nu = material.poisson_ratio;
  const double scale = 1.0 / (M_PI * material.shear_modulus_Pa());
  const RectangleAntiderivatives I = rectangle_integrals(x1_m, x2_m, element);
  return {scale * ((1.0 - nu) * I.one_over_r + nu * I.x2_over_r3), scale * nu * I.xy_over_r3,
          scale * ((1.0 - nu) * I.one_over_r + nu * I.y2_over_r3)};
}

}  // namespace railcontact
