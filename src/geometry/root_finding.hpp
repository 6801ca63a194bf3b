#pragma once
// One-dimensional root finding used by the geometry: Newton's method safeguarded by bisection
// on a sign-changing bracket (the classical "rtsafe").
#include <cmath>
#include <algorithm>
#include <optional>
#include <tuple>
#include <utility>

namespace railcontact::geometry {

// Root of f in [lo, hi], where f(x) returns {f, df/dx} and f(lo), f(hi) have opposite signs (or
// one is zero). Starts from `guess` if it lies in the bracket. Returns nothing if [lo, hi] does
// not bracket a root. Converges to |dx| < tolerance.
template <class Function>
std::optional<double> solve_bracketed(Function&& f, double lo, double hi, double guess, double tolerance,
                                      int max_iterations = 100) {
  auto [f_lo, df_lo] = f(lo);
  auto [f_hi, df_hi] = f(hi);
  (void)df_lo;
  (void)df_hi;
  if (f_lo == 0.0) return lo;
  if (f_hi == 0.0) return hi;
  if ((f_lo > 0.0) == (f_hi > 0.0)) return std::nullopt;
  if (f_lo > 0.0) {  // orient so that f(lo) < 0 < f(hi)
    std::swap(lo, hi);
  }
  double x = (guess > std::min(lo, hi) && guess < std::max(lo, hi)) ? guess : 0.5 * (lo + hi);
  double dx_old = std::abs(hi - lo);
  double dx = dx_old;
  auto [fx, dfx] = f(x);
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    const bool newton_leaves_bracket = ((x - hi) * dfx - fx) * ((x - lo) * dfx - fx) > 0.0;
    const bool newton_too_slow = std::abs(2.0 * fx) > std::abs(dx_old * dfx);
    dx_old = dx;
    if (newton_leaves_bracket || newton_too_slow || dfx == 0.0) {
      dx = 0.5 * (hi - lo);
      x = lo + dx;
    } else {
      dx = fx / dfx;
      x -= dx;
    }
    if (std::abs(dx) < tolerance) return x;
    std::tie(fx, dfx) = f(x);
    if (fx == 0.0) return x;
    if (fx < 0.0) {
      lo = x;
    } else {
      hi = x;
    }
  }
  return x;
}

}  // namespace railcontact::geometry
