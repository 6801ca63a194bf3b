#pragma once
// One-dimensional root finding used by the geometry, done by Boost.Math:
//  * bracketed_root: TOMS 748 (Alefeld, Potra & Shi, ACM TOMS 21 (1995) 327-344;
//    boost/math/tools/toms748_solve.hpp), for a sign-changing bracket without a useful guess;
//  * newton_root: Newton-Raphson with its bracket kept (boost/math/tools/roots.hpp), for the
//    undeformed distance, which is called once per mesh element with the previous element's root
//    as a close starting guess.
// The adapters only fit Boost's solvers to the geometry: a bracket without a sign change is
// reported as "no root" (the callers fall back or throw their own error), the unknowns are lengths
// in metres that may be zero (so the stopping tests are absolute, not relative to the unknown),
// and a solver that does not converge throws railcontact::Error (kind not_converged).
#include <fmt/core.h>

#include <algorithm>
#include <boost/math/tools/roots.hpp>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>

#include "railcontact/error.hpp"

namespace railcontact::geometry {

// Root of f in the interval between a and b, where f(a), f(b) have opposite signs (or one is zero):
// the middle of a bracket narrowed to 4 eps max(|a|, |b|), i.e. to a few ulp of the unknown.
// Nothing if f(a), f(b) have the same sign. `what` names the equation in error messages.
template <class Function>
std::optional<double> bracketed_root(Function&& f, double a, double b, const char* what,
                                     std::uintmax_t max_evaluations = 100) {
  const double lo = std::min(a, b), hi = std::max(a, b);
  const double f_lo = f(lo), f_hi = f(hi);
  if (f_lo == 0.0) return lo;
  if (f_hi == 0.0) return hi;
  if ((f_lo > 0.0) == (f_hi > 0.0)) return std::nullopt;
  const double width = 4.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(lo), std::abs(hi));
  const auto narrow_enough = [width](double left, double right) { return right - left <= width; };
  std::uintmax_t evaluations = max_evaluations;
  const auto [left, right] = boost::math::tools::toms748_solve(f, lo, hi, f_lo, f_hi, narrow_enough, evaluations);
  if (!narrow_enough(left, right)) {
    throw Error(ErrorKind::not_converged,
                fmt::format("geometry: {} did not converge in {} evaluations (bracket [{}, {}] m)", what,
                            max_evaluations, left, right));
  }
  return 0.5 * (left + right);
}

// Root of f in the interval between a and b by Newton's method from `guess` (moved into the
// interval if outside), where f(s) returns {f, df/ds} and f(a), f(b) have opposite signs (or one is
// zero); it stops after a Newton step shorter than `tolerance`. Nothing if f(a), f(b) have the
// same sign.
template <class Function>
std::optional<double> newton_root(Function&& f, double a, double b, double guess, double tolerance, const char* what,
                                  std::uintmax_t max_iterations = 100) {
  const double lo = std::min(a, b), hi = std::max(a, b);
  const double f_lo = f(lo).first, f_hi = f(hi).first;
  if (f_lo == 0.0) return lo;
  if (f_hi == 0.0) return hi;
  if ((f_lo > 0.0) == (f_hi > 0.0)) return std::nullopt;
  // Boost stops once a step is below 2^(1 - digits) |x|, relative to the unknown x. Newton runs on
  // x = s - (lo - W), W = hi - lo, which lies in [W, 2W], so that test becomes an absolute step of
  // at most 2^(1 - digits) 2W <= tolerance (digits capped at double's 53: a tolerance finer than
  // the resolution of x is not asked for).
  const double width = hi - lo;
  const double origin = lo - width;
  const int digits = std::min(std::numeric_limits<double>::digits,
                              1 + static_cast<int>(std::ceil(std::log2(2.0 * width / tolerance))));
  const auto shifted = [&](double x) { return f(x + origin); };
  std::uintmax_t iterations = max_iterations;
  double x = 0.0;
  try {
    x = boost::math::tools::newton_raphson_iterate(shifted, std::clamp(guess, lo, hi) - origin, width, 2.0 * width,
                                                   digits, iterations);
  } catch (const boost::math::evaluation_error& e) {
    throw Error(ErrorKind::not_converged, fmt::format("geometry: {} failed: {}", what, e.what()));
  }
  if (iterations >= max_iterations) {
    throw Error(ErrorKind::not_converged,
                fmt::format("geometry: {} did not converge to {:g} m in {} Newton iterations (last s = {} m)", what,
                            tolerance, max_iterations, x + origin));
  }
  return x + origin;
}

}  // namespace railcontact::geometry
