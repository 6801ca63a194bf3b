// Hertz's solution for an elliptical contact between two quasi-identical elastic bodies,
// Johnson, Contact Mechanics (1985) §4.2, eq. (4.39)-(4.42), rewritten with the associate
// elliptic integrals B, D (see hertz/elliptic_integrals.hpp) so that nothing cancels near the
// circle. Notation: A' <= B' the principal relative curvatures (h = A' x² + B' y²), a >= b the
// semi-axes, a along the axis of the smaller curvature A', g = b/a, e² = 1 - g² = m, mc = g².
//
//   B'/A' = [(a/b)² E - K] / (K - E)          (4.39)  =  B(m) / (g² D(m))   since K - E = m D,
//                                                                           E/g² - K = m B / g²
//   a³ = 3 F (K - E) / (2π E* e² A')          (4.40)  =  3 F D(m) / (2π E* A')
//   p0 = 3 F / (2π a b)                       (4.41)
//   δ  = (p0 / E*) b K(e)                     (4.42)
#include "railcontact/hertz.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>

#include "hertz/elliptic_integrals.hpp"
#include "hertz/hertz_estimate.hpp"
#include "mesh/hertz_pressure.hpp"
#include "railcontact/error.hpp"

namespace railcontact {
namespace {

void require_positive_finite(double value, const char* what) {
  require(std::isfinite(value) && value > 0.0,
          [&] { return fmt::format("hertz: {} must be positive and finite (got {})", what, value); });
}

// Ratio of the larger to the smaller curvature, B'/A', for axis ratio g = b/a in (0, 1]: eq. (4.39).
// Decreases monotonically from +inf (g -> 0) to 1 (g = 1, circle).
double curvature_ratio(double g) {
  const detail::CompleteEllipticIntegrals ell = detail::complete_elliptic_integrals(g * g);
  return ell.B / (g * g * ell.D);
}

// Solves curvature_ratio(g) = ratio >= 1 for g in (0, 1]. The function is monotone: a bracket is
// found by halving g, then Boost.Math's TOMS 748 solver (Alefeld, Potra & Shi 1995) narrows it on
// ln(curvature_ratio(g) / ratio), a smooth function of g, to a width of 2 eps g (a few ulp of g).
double axis_ratio_for_curvature_ratio(double ratio) {
  if (ratio == 1.0) return 1.0;
  // Upper bound: D >= B for m >= 0, so curvature_ratio(g) <= 1/g², hence the root g* <= 1/sqrt(ratio).
  double g_high = std::min(1.0, 1.0 / std::sqrt(ratio));
  // Lower bound: curvature_ratio(g) ~ 1/(g² (ln(4/g) - 1)) for g -> 0, so a few halvings suffice.
  double g_low = 0.5 * g_high;
  constexpr double kSmallestAxisRatio = 1e-150;
  while (curvature_ratio(g_low) < ratio) {
    g_high = g_low;
    g_low *= 0.5;
    require(g_low > kSmallestAxisRatio, [&] { return fmt::format("hertz: curvature ratio {} is too extreme", ratio); });
  }
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  const auto converged = [](double low, double high) { return high - low <= 2.0 * kEps * high; };
  constexpr std::uintmax_t kMaxEvaluations = 200;
  std::uintmax_t evaluations = kMaxEvaluations;
  const auto [low, high] = boost::math::tools::toms748_solve(
      [ratio](double g) { return std::log(curvature_ratio(g) / ratio); }, g_low, g_high, converged, evaluations);
  if (!converged(low, high)) {
    throw Error(ErrorKind::not_converged,
                fmt::format("hertz: the axis ratio b/a for curvature ratio {} did not converge in {} evaluations "
                            "(bracket [{}, {}])",
                            ratio, kMaxEvaluations, low, high));
  }
  return 0.5 * (low + high);
}

// Hertz's solution is closed-form: with the inputs in their ranges every quantity is finite and
// positive. A result that is not is a bug (kind internal), never returned.
template <class Describe>
void require_finite_result(double v1, double v2, double v3, double v4, Describe&& describe) {
  for (const double v : {v1, v2, v3, v4})
    if (!(std::isfinite(v) && v > 0.0))
      throw Error(ErrorKind::internal,
                  fmt::format("hertz: the solution for {} is not positive and finite ({:g}, {:g}, {:g}, {:g})",
                              describe(), v1, v2, v3, v4));
}

}  // namespace

namespace {

std::string range_text(double low, double high, const char* unit) { return fmt::format("[{:g}, {:g}]{}", low, high, unit); }

}  // namespace

void validate_relative_curvature(double value_per_m, std::string_view name) {
  require(std::isfinite(value_per_m) && value_per_m >= kMinimumRelativeCurvature_per_m &&
              value_per_m <= kMaximumRelativeCurvature_per_m,
          [&] {
            return fmt::format("{} = {:g} 1/m must lie in {} (half the sum of the bodies' curvatures: radii from 500 m, "
                               "nearly flat, to 50 um, a sharp edge)",
                               name, value_per_m,
                               range_text(kMinimumRelativeCurvature_per_m, kMaximumRelativeCurvature_per_m, " 1/m"));
          });
}

namespace detail {

HertzContact hertz_estimate(double A_per_m, double B_per_m, double normal_force_N, const Material& material) {
  validate(material);
  require_positive_finite(A_per_m, "curvature A");
  require_positive_finite(B_per_m, "curvature B");
  require_positive_finite(normal_force_N, "the normal force F3");
  const double e_star_Pa = material.contact_modulus_Pa();

  // The major semi-axis lies along the axis of the smaller curvature.
  const double small_curvature = std::min(A_per_m, B_per_m);
  const double ratio = std::max(A_per_m, B_per_m) / small_curvature;
  require(std::isfinite(ratio),
          [&] { return fmt::format("hertz: curvature ratio B/A = {} / {} is too extreme", B_per_m, A_per_m); });
  const double g = axis_ratio_for_curvature_ratio(ratio);  // b/a <= 1
  const detail::CompleteEllipticIntegrals ell = detail::complete_elliptic_integrals(g * g);

  const double major_m =
      std::cbrt(3.0 * normal_force_N * ell.D / (2.0 * std::numbers::pi * e_star_Pa * small_curvature));  // (4.40)
  const double minor_m = g * major_m;

  HertzContact contact;
  contact.normal_force_N = normal_force_N;
  contact.a_m = A_per_m <= B_per_m ? major_m : minor_m;  // a is always the semi-axis along X1
  contact.b_m = A_per_m <= B_per_m ? minor_m : major_m;
  contact.max_pressure_Pa = 3.0 * normal_force_N / (2.0 * std::numbers::pi * major_m * minor_m);  // (4.41)
  contact.approach_m = contact.max_pressure_Pa / e_star_Pa * minor_m * ell.K;                     // (4.42)
  require_finite_result(contact.a_m, contact.b_m, contact.max_pressure_Pa, contact.approach_m,
                        [&] { return fmt::format("A = {:g} 1/m, B = {:g} 1/m", A_per_m, B_per_m); });
  return contact;
}

}  // namespace detail

HertzContact hertz_from_curvatures(double A_per_m, double B_per_m, double normal_force_N, const Material& material) {
  validate(material);
  validate_relative_curvature(A_per_m, "hertz: the relative curvature A");
  validate_relative_curvature(B_per_m, "hertz: the relative curvature B");
  validate_normal_force(normal_force_N, "hertz: the normal force F3");
  const HertzContact contact = detail::hertz_estimate(A_per_m, B_per_m, normal_force_N, material);
  const std::string inputs = fmt::format("hertz: the curvatures A = {:g} 1/m, B = {:g} 1/m (with E = {:g} Pa)",
                                         A_per_m, B_per_m, material.youngs_modulus_Pa);
  for (const double axis : {contact.a_m, contact.b_m})
    require(axis >= kMinimumSemiAxis_m && axis <= kMaximumSemiAxis_m, [&] {
      return fmt::format("{} under F3 = {:g} N give an ellipse of semi-axes a = {:.3g} mm, b = {:.3g} mm, outside "
                         "[{:g}, {:g}] mm (a contact patch from a laboratory micro-contact to beyond a rail head)",
                         inputs, normal_force_N, contact.a_m * 1e3, contact.b_m * 1e3, kMinimumSemiAxis_m * 1e3,
                         kMaximumSemiAxis_m * 1e3);
    });
  detail::validate_hertz_pressure(contact.a_m, contact.b_m, normal_force_N, inputs);
  return contact;
}

namespace {

// The curvatures and the elliptic integrals of the ellipse a x b under F3: inputs checked.
struct SemiAxesSolution {
  HertzCurvatures curvatures;
  double e_star_Pa = 0.0, g = 0.0, minor_m = 0.0;
  detail::CompleteEllipticIntegrals ell;
};

SemiAxesSolution solve_semi_axes(double a_m, double b_m, double normal_force_N, const Material& material) {
  validate(material);
  validate_semi_axis(a_m, "hertz: the semi-axis a");
  validate_semi_axis(b_m, "hertz: the semi-axis b");
  validate_normal_force(normal_force_N, "hertz: the normal force F3");
  detail::validate_hertz_pressure(a_m, b_m, normal_force_N,
                          fmt::format("hertz: the semi-axes a = {:g} m, b = {:g} m", a_m, b_m));
  SemiAxesSolution s;
  s.e_star_Pa = material.contact_modulus_Pa();

  const double major_m = std::max(a_m, b_m);
  s.minor_m = std::min(a_m, b_m);
  s.g = s.minor_m / major_m;
  s.ell = detail::complete_elliptic_integrals(s.g * s.g);

  // (4.40) solved for the smaller curvature (along the major axis), then (4.39) for the larger.
  const double small_curvature =
      3.0 * normal_force_N * s.ell.D / (2.0 * std::numbers::pi * s.e_star_Pa * major_m * major_m * major_m);
  const double large_curvature = small_curvature * s.ell.B / (s.g * s.g * s.ell.D);

  s.curvatures.A_per_m = a_m >= b_m ? small_curvature : large_curvature;
  s.curvatures.B_per_m = a_m >= b_m ? large_curvature : small_curvature;
  require_finite_result(s.curvatures.A_per_m, s.curvatures.B_per_m, s.curvatures.A_per_m, s.curvatures.B_per_m,
                        [&] { return fmt::format("a = {:g} m, b = {:g} m", a_m, b_m); });
  return s;
}

}  // namespace

HertzCurvatures hertz_curvatures_for_semi_axes(double a_m, double b_m, double normal_force_N, const Material& material) {
  return solve_semi_axes(a_m, b_m, normal_force_N, material).curvatures;
}

HertzContact hertz_from_semi_axes(double a_m, double b_m, double normal_force_N, const Material& material) {
  const SemiAxesSolution s = solve_semi_axes(a_m, b_m, normal_force_N, material);
  HertzContact contact;
  contact.normal_force_N = normal_force_N;
  contact.a_m = a_m;
  contact.b_m = b_m;
  contact.max_pressure_Pa = 3.0 * normal_force_N / (2.0 * std::numbers::pi * a_m * b_m);  // (4.41)
  contact.approach_m = contact.max_pressure_Pa / s.e_star_Pa * s.minor_m * s.ell.K;     // (4.42)
  require_finite_result(contact.a_m, contact.b_m, contact.max_pressure_Pa, contact.approach_m,
                        [&] { return fmt::format("a = {:g} m, b = {:g} m", a_m, b_m); });
  return contact;
}

}  // namespace railcontact
