#include "kalker/monotone_cubic.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "railcontact/error.hpp"

namespace railcontact::detail {
namespace {

// Three-point end slope (Moler 2004, pchip.m end condition): the slope of the quadratic through
// the first three points, set to zero if its sign differs from the first secant and limited to 3x
// that secant if the first two secants differ in sign (Fritsch-Carlson monotonicity region).
double end_slope(double h0, double h1, double secant0, double secant1) {
  const double slope = ((2.0 * h0 + h1) * secant0 - h0 * secant1) / (h0 + h1);
  if (slope * secant0 <= 0.0) return 0.0;
  if (secant0 * secant1 <= 0.0 && std::abs(slope) > std::abs(3.0 * secant0)) return 3.0 * secant0;
  return slope;
}

}  // namespace

void pchip_slopes(std::span<const double> x, std::span<const double> y, std::span<double> slopes) {
  const std::size_t n = x.size();
  require(n >= 2 && y.size() == n && slopes.size() == n, "pchip: need at least two nodes and matching sizes");
  for (std::size_t i = 0; i + 1 < n; ++i) {
    require(x[i + 1] > x[i], "pchip: abscissae must be strictly increasing");
  }
  if (n == 2) {
    slopes[0] = slopes[1] = (y[1] - y[0]) / (x[1] - x[0]);
    return;
  }
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double h_left = x[i] - x[i - 1];
    const double h_right = x[i + 1] - x[i];
    const double secant_left = (y[i] - y[i - 1]) / h_left;
    const double secant_right = (y[i + 1] - y[i]) / h_right;
    if (secant_left * secant_right <= 0.0) {
      slopes[i] = 0.0;  // local extremum or flat: keeps the interpolant monotone on both sides
    } else {
      // Fritsch-Butland weighted harmonic mean (Brodlie's weights for unequal spacing).
      const double w_left = 2.0 * h_right + h_left;
      const double w_right = h_right + 2.0 * h_left;
      slopes[i] = (w_left + w_right) / (w_left / secant_left + w_right / secant_right);
    }
  }
  slopes[0] = end_slope(x[1] - x[0], x[2] - x[1], (y[1] - y[0]) / (x[1] - x[0]), (y[2] - y[1]) / (x[2] - x[1]));
  slopes[n - 1] = end_slope(x[n - 1] - x[n - 2], x[n - 2] - x[n - 3], (y[n - 1] - y[n - 2]) / (x[n - 1] - x[n - 2]),
                            (y[n - 2] - y[n - 3]) / (x[n - 2] - x[n - 3]));
}

double hermite_interpolate(std::span<const double> x, std::span<const double> y, std::span<const double> slopes,
                           double x_query) {
  const std::size_t n = x.size();
  require(n >= 2 && y.size() == n && slopes.size() == n, "pchip: need at least two nodes and matching sizes");
  require(x_query >= x.front() && x_query <= x.back(), "pchip: query point outside the interpolation range");
  // Interval [x_i, x_{i+1}] with x_i <= x_query; a query at a node lands at its left end (t = 0),
  // except the last node (t = 1); both return the node value exactly.
  const auto upper = std::upper_bound(x.begin(), x.end(), x_query);
  const std::size_t i = std::min(static_cast<std::size_t>(upper - x.begin()), n - 1) - 1;
  const double h = x[i + 1] - x[i];
  const double t = (x_query - x[i]) / h;
  const double t2 = t * t;
  const double t3 = t2 * t;
  return (2.0 * t3 - 3.0 * t2 + 1.0) * y[i] + (t3 - 2.0 * t2 + t) * h * slopes[i] + (3.0 * t2 - 2.0 * t3) * y[i + 1] +
         (t3 - t2) * h * slopes[i + 1];
}

}  // namespace railcontact::detail
