// Tests of the Hertz solution (src/hertz/hertz.cpp) and of the elliptic integrals it uses
// (src/hertz/elliptic_integrals.hpp, Boost.Math's Carlson integrals behind it).
// References: the closed-form circle; Johnson, Contact Mechanics §4.2 eq. (4.39)-(4.42) evaluated
// with the standard library's std::comp_ellint_1/2 (an implementation independent of Boost's);
// numbers from an independent script (arithmetic-geometric mean for K and E, bisection for e).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "hertz/elliptic_integrals.hpp"
#include "hertz/hertz_estimate.hpp"
#include "railcontact/error.hpp"
#include "railcontact/hertz.hpp"
#include "railcontact/contact_patch.hpp"

namespace railcontact {
namespace {

constexpr double pi = std::numbers::pi;

double rel_diff(double value, double reference) { return std::abs(value / reference - 1.0); }

// ---- elliptic integrals ------------------------------------------------------------------------

// Very slender ellipses, b/a = 1e-10 and 1e-50: the integrals depend on mc = (b/a)² itself, which
// the modulus k = sqrt(1 - mc) rounds to 1 (libstdc++'s comp_ellint_1 then returns NaN). References:
// Carlson's R_F(0, mc, 1), R_D(0, mc, 1)/3 in 40-digit mpmath; K ≈ ln(4/sqrt(mc)), E ≈ 1, D ≈ K - 1.
// E = B + mc D with B = K - D is only good to about K eps (cancellation), hence 1e-14 for E.
TEST(EllipticIntegrals, SlenderEllipseFromComplementaryParameter) {
  const detail::CompleteEllipticIntegrals slender = detail::complete_elliptic_integrals(1e-20);
  EXPECT_LT(rel_diff(slender.K, 24.412145291060347459), 2e-15);
  EXPECT_LT(rel_diff(slender.D, 23.412145291060347459), 2e-15);
  EXPECT_LT(rel_diff(slender.E, 1.0), 1e-14);
  const detail::CompleteEllipticIntegrals extreme = detail::complete_elliptic_integrals(1e-100);
  EXPECT_LT(rel_diff(extreme.K, 116.51554901082217482), 2e-15);
  EXPECT_LT(rel_diff(extreme.D, 115.51554901082217482), 2e-15);
  // m = 1/2, all four: K = 1.8540746773013719184, D = 1.0068615925073928318, B = K - D, E = B + D/2.
  const detail::CompleteEllipticIntegrals half = detail::complete_elliptic_integrals(0.5);
  EXPECT_LT(rel_diff(half.K, 1.8540746773013719184), 2e-15);
  EXPECT_LT(rel_diff(half.D, 1.0068615925073928318), 2e-15);
  EXPECT_LT(rel_diff(half.B, 0.84721308479397908661), 2e-15);
  EXPECT_LT(rel_diff(half.E, 1.3506438810476755025), 2e-15);
  EXPECT_THROW((void)detail::complete_elliptic_integrals(0.0), Error);
  EXPECT_THROW((void)detail::complete_elliptic_integrals(1.5), Error);
}

// K and E for k = 0.99 by the arithmetic-geometric mean in 40-digit decimal arithmetic.
TEST(EllipticIntegrals, HighPrecisionReference) {
  const detail::CompleteEllipticIntegrals ell = detail::complete_elliptic_integrals(1.0 - 0.99 * 0.99);
  EXPECT_LT(rel_diff(ell.K, 3.356600523361192376), 2e-15);
  EXPECT_LT(rel_diff(ell.E, 1.028475809028804001), 2e-15);
}

// libstdc++'s std::comp_ellint_2 is itself only good to ~4e-13 at k = 0.99 (see above), hence 1e-12.
TEST(EllipticIntegrals, MatchStandardLibrary) {
  for (const double k : {0.05, 0.3, 0.6, 0.9, 0.99, 0.999999}) {
    const detail::CompleteEllipticIntegrals ell = detail::complete_elliptic_integrals(1.0 - k * k);
    const double K = std::comp_ellint_1(k);  // the standard library takes the modulus k
    const double E = std::comp_ellint_2(k);
    EXPECT_LT(rel_diff(ell.K, K), 1e-12) << "k = " << k;
    EXPECT_LT(rel_diff(ell.E, E), 1e-12) << "k = " << k;
    if (k >= 0.3) {
      EXPECT_LT(rel_diff(ell.D, (K - E) / (k * k)), 1e-12) << "k = " << k;
    }
    EXPECT_NEAR(ell.B + ell.D, ell.K, 1e-14 * ell.K);
  }
}

// Near the circle D = (K - E)/m = (π/4)(1 + 3m/8 + 15m²/64 + ...) without cancellation.
TEST(EllipticIntegrals, AssociateIntegralsNearCircle) {
  const double m = 1e-8;
  const detail::CompleteEllipticIntegrals ell = detail::complete_elliptic_integrals(1.0 - m);
  EXPECT_NEAR(ell.D, pi / 4.0 * (1.0 + 3.0 * m / 8.0), 1e-15);
  EXPECT_NEAR(ell.B, pi / 4.0 * (1.0 + m / 8.0), 1e-15);  // B = K - D, K = (π/2)(1 + m/4 + ...)
  const detail::CompleteEllipticIntegrals circle = detail::complete_elliptic_integrals(1.0);
  EXPECT_DOUBLE_EQ(circle.D, pi / 4.0);
  EXPECT_DOUBLE_EQ(circle.K, pi / 2.0);
}

// ---- Hertz ----------------------------------------------------------------------------------

const Material kSteel{2.1e11, 0.3};

// Sphere-like contact A = B = 1/(2R): a = b = (3 F R / (4 E*))^{1/3}, p0 = 3F/(2π a²), δ = a²/R.
TEST(Hertz, CircleMatchesClosedForm) {
  const double radius_m = 0.5;
  const double force_N = 98.1e3;
  const double e_star_Pa = kSteel.contact_modulus_Pa();
  const double a_ref = std::cbrt(3.0 * force_N * radius_m / (4.0 * e_star_Pa));
  const HertzContact c = hertz_from_curvatures(0.5 / radius_m, 0.5 / radius_m, force_N, kSteel);
  EXPECT_LT(rel_diff(c.a_m, a_ref), 1e-13);
  EXPECT_LT(rel_diff(c.b_m, a_ref), 1e-13);
  EXPECT_LT(rel_diff(c.max_pressure_Pa, 3.0 * force_N / (2.0 * pi * a_ref * a_ref)), 1e-13);
  EXPECT_LT(rel_diff(c.approach_m, a_ref * a_ref / radius_m), 1e-13);
  EXPECT_DOUBLE_EQ(c.normal_force_N, force_N);
  EXPECT_DOUBLE_EQ(c.a_over_b(), 1.0);
}

// e -> 0: a curvature ratio 1 + 1e-9 must give (nearly) the circle, b/a ≈ 1 - (2/3)·1e-9.
TEST(Hertz, NearlyCircularIsContinuous) {
  const HertzContact circle = hertz_from_curvatures(1.0, 1.0, 1e4, kSteel);
  const HertzContact near = hertz_from_curvatures(1.0, 1.0 + 1e-9, 1e4, kSteel);
  EXPECT_GT(near.a_m, near.b_m);
  EXPECT_NEAR(near.b_m / near.a_m, 1.0 - 2.0 / 3.0 * 1e-9, 1e-12);
  EXPECT_LT(rel_diff(near.a_m, circle.a_m), 1e-9);
  EXPECT_LT(rel_diff(near.approach_m, circle.approach_m), 1e-9);
}

// Wheel radius 0.46 m (curvature along X1), rail crown radius 0.3 m (along X2), F = 98.1 kN,
// E = 2.1e11 Pa, nu = 0.3. Reference numbers from an independent script (AGM elliptic integrals,
// bisection on e); identities of Johnson (4.39)-(4.42) checked with std::comp_ellint_1/2.
TEST(Hertz, WheelOnRailMatchesJohnson) {
  const double A = 1.0 / (2.0 * 0.46);
  const double B = 1.0 / (2.0 * 0.3);
  const double force_N = 98.1e3;
  const HertzContact c = hertz_from_curvatures(A, B, force_N, kSteel);
  EXPECT_LT(rel_diff(c.a_m, 7.1160286080e-03), 1e-9);
  EXPECT_LT(rel_diff(c.b_m, 5.3528350557e-03), 1e-9);
  EXPECT_LT(rel_diff(c.max_pressure_Pa, 1.2296707631e+09), 1e-9);
  EXPECT_LT(rel_diff(c.approach_m, 1.0279589415e-04), 1e-9);

  // A < B: the major axis lies along X1. Johnson's closed form with the standard library:
  ASSERT_GT(c.a_m, c.b_m);
  const double e = std::sqrt(1.0 - (c.b_m / c.a_m) * (c.b_m / c.a_m));
  const double K = std::comp_ellint_1(e);
  const double E = std::comp_ellint_2(e);
  const double e_star_Pa = kSteel.contact_modulus_Pa();
  EXPECT_LT(rel_diff(B / A, ((c.a_m / c.b_m) * (c.a_m / c.b_m) * E - K) / (K - E)), 1e-10);       // (4.39)
  EXPECT_LT(rel_diff(std::pow(c.a_m, 3), 3.0 * force_N * (K - E) / (2.0 * pi * e_star_Pa * e * e * A)), 1e-10);  // (4.40)
  EXPECT_LT(rel_diff(c.approach_m, c.max_pressure_Pa / e_star_Pa * c.b_m * K), 1e-10);           // (4.42)
  // Total load of the semi-ellipsoidal pressure: (2/3) π a b p0 = F.
  EXPECT_LT(rel_diff(2.0 / 3.0 * pi * c.a_m * c.b_m * c.max_pressure_Pa, force_N), 1e-13);
}

// b/a = 0.5 (e² = 0.75): B/A = [(a/b)² E - K]/(K - E) = 2.842753308670997 (AGM script).
TEST(Hertz, KnownAxisRatio) {
  const HertzContact c = hertz_from_curvatures(1.0, 2.842753308670997, 5e4, kSteel);
  EXPECT_NEAR(c.b_m / c.a_m, 0.5, 1e-12);
}

TEST(Hertz, SwappingCurvaturesSwapsSemiAxes) {
  const HertzContact c = hertz_from_curvatures(1.3, 4.1, 7e4, kSteel);
  const HertzContact swapped = hertz_from_curvatures(4.1, 1.3, 7e4, kSteel);
  EXPECT_GT(c.a_m, c.b_m);  // smaller curvature along X1 -> longer semi-axis along X1
  EXPECT_DOUBLE_EQ(swapped.a_m, c.b_m);
  EXPECT_DOUBLE_EQ(swapped.b_m, c.a_m);
  EXPECT_DOUBLE_EQ(swapped.max_pressure_Pa, c.max_pressure_Pa);
  EXPECT_DOUBLE_EQ(swapped.approach_m, c.approach_m);
}

TEST(Hertz, RoundTripCurvaturesSemiAxesCurvatures) {
  // B/A within the curvatures' range [1e-3, 1e4] 1/m (hertz.hpp); the closed form itself for 1e8
  // and 1e-6 in HertzEstimate below.
  for (const double ratio : {1.0, 1.0 + 1e-7, 1.5, 3.0, 17.0, 250.0, 1e4, 1.0 / 40.0, 1.0 / 400.0}) {
    const double A = 0.8;
    const double B = A * ratio;
    const double force_N = 2.5e4;
    const HertzContact c = hertz_from_curvatures(A, B, force_N, kSteel);
    EXPECT_LT(rel_diff(2.0 / 3.0 * pi * c.a_m * c.b_m * c.max_pressure_Pa, force_N), 1e-13);
    const HertzCurvatures back = hertz_curvatures_for_semi_axes(c.a_m, c.b_m, force_N, kSteel);
    EXPECT_LT(rel_diff(back.A_per_m, A), 1e-10) << "B/A = " << ratio;
    EXPECT_LT(rel_diff(back.B_per_m, B), 1e-10) << "B/A = " << ratio;
  }
}

TEST(Hertz, RoundTripSemiAxesCurvaturesSemiAxes) {
  for (const double b_m : {1e-3, 2e-3, 5e-3, 6e-3, 2e-2, kMaximumSemiAxis_m}) {
    const double a_m = 6e-3;
    const HertzCurvatures k = hertz_curvatures_for_semi_axes(a_m, b_m, 1e5, kSteel);
    const HertzContact c = hertz_from_curvatures(k.A_per_m, k.B_per_m, 1e5, kSteel);
    EXPECT_LT(rel_diff(c.a_m, a_m), 1e-10) << "b = " << b_m;
    EXPECT_LT(rel_diff(c.b_m, b_m), 1e-10) << "b = " << b_m;
  }
}

// Hertz's closed form without the physical ranges (the wheel-rail patch's estimate): very slender
// ellipses still carry their load, 2/3 pi a b p0 = F3, to 1e-13.
TEST(Hertz, EstimateForVerySlenderEllipses) {
  for (const double ratio : {1e8, 1e-6}) {
    const HertzContact c = detail::hertz_estimate(0.8, 0.8 * ratio, 2.5e4, kSteel);
    EXPECT_LT(rel_diff(2.0 / 3.0 * pi * c.a_m * c.b_m * c.max_pressure_Pa, 2.5e4), 1e-13) << "B/A = " << ratio;
    EXPECT_THROW((void)hertz_from_curvatures(0.8, 0.8 * ratio, 2.5e4, kSteel), Error);
  }
}

TEST(Hertz, RejectsBadInput) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  constexpr double inf = std::numeric_limits<double>::infinity();
  for (const double bad : {0.0, -1.0, nan, inf}) {
    EXPECT_THROW(hertz_from_curvatures(bad, 1.0, 1e4, kSteel), Error);
    EXPECT_THROW(hertz_from_curvatures(1.0, bad, 1e4, kSteel), Error);
    EXPECT_THROW(hertz_from_curvatures(1.0, 1.0, bad, kSteel), Error);
    EXPECT_THROW(hertz_curvatures_for_semi_axes(bad, 1e-3, 1e4, kSteel), Error);
    EXPECT_THROW(hertz_curvatures_for_semi_axes(1e-3, bad, 1e4, kSteel), Error);
    EXPECT_THROW(hertz_curvatures_for_semi_axes(1e-3, 1e-3, bad, kSteel), Error);
  }
  EXPECT_THROW(hertz_from_curvatures(1.0, 1.0, 1e4, Material{-2.1e11, 0.3}), Error);
  EXPECT_THROW(hertz_from_curvatures(1.0, 1.0, 1e4, Material{2.1e11, 0.51}), Error);  // nu = 0.5 is valid
  EXPECT_THROW(hertz_curvatures_for_semi_axes(1e-3, 1e-3, 1e4, Material{2.1e11, -0.1}), Error);
  try {
    hertz_from_curvatures(-1.0, 1.0, 1e4, kSteel);
    FAIL() << "expected railcontact::Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("hertz: the relative curvature A"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace railcontact
