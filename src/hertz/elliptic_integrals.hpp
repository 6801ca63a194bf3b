#pragma once
// Complete elliptic integrals for the Hertz solution, computed without cancellation near the
// circle (e -> 0) and accurate for very slender ellipses (e -> 1).
//
// The associate complete integrals of Jahnke-Emde (also used by Fukushima), with parameter
// m = k^2 (k the modulus) and complementary parameter mc = 1 - m:
//   B(m) = ∫_0^{π/2} cos²θ / sqrt(1 - m sin²θ) dθ,   D(m) = ∫_0^{π/2} sin²θ / sqrt(1 - m sin²θ) dθ,
//   K = B + D,   E = B + mc D,   K - E = m D.
// B and D stay finite and O(1) at m = 0 (both π/4), so (K - E)/e² = D needs no series.
//
// They are taken from Carlson's symmetric integrals (B.C. Carlson, "Numerical computation of real
// or complex elliptic integrals", Numerical Algorithms 10 (1995) 13-26; DLMF §19.16, §19.36)
//   R_F(x,y,z) = 1/2 ∫_0^∞ dt / sqrt((t+x)(t+y)(t+z))
//   R_D(x,y,z) = 3/2 ∫_0^∞ dt / ((t+z) sqrt((t+x)(t+y)(t+z))),
// which depend on mc itself rather than on the modulus (DLMF 19.25.1):
//   K = R_F(0, mc, 1),   D = R_D(0, mc, 1) / 3,
// evaluated by Boost.Math (boost::math::ellint_rf, ellint_rd). std::comp_ellint_1/2 take the
// modulus k = sqrt(1 - mc) and give D only as (K - E)/m, which cancels near the circle and
// loses mc to rounding for slender ellipses (docs/DEPENDENCIES.md, "Numerical routines").

namespace railcontact::detail {

// The complete integrals K, E and the associates B, D for complementary parameter
// mc = 1 - k^2 = (b/a)^2 in (0, 1] (mc = 1: circle, B = D = π/4, K = E = π/2). Throws
// railcontact::Error outside (0, 1].
struct CompleteEllipticIntegrals {
  double K = 0.0;  // first kind
  double E = 0.0;  // second kind
  double B = 0.0;  // B = (E - mc K) / m
  double D = 0.0;  // D = (K - E) / m
};
CompleteEllipticIntegrals complete_elliptic_integrals(double complementary_parameter);

}  // namespace railcontact::detail
