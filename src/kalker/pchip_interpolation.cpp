#include "kalker/pchip_interpolation.hpp"

// Boost 1.74's pchip.hpp calls isnan unqualified, so boost::math::isnan must be declared before it
// is included (boostorg/math#397, fixed after 1.74).
#include <boost/math/special_functions/fpclassify.hpp>

#include <boost/math/interpolators/pchip.hpp>
#include <cmath>
#include <cstddef>
#include <vector>

#include "railcontact/error.hpp"

namespace railcontact::detail {
namespace {

// Three-point end slope (Moler 2004, pchip.m end condition): the slope of the quadratic through
// the end point and its two neighbours, set to zero if its sign differs from the end secant and
// limited to 3x that secant if the first two secants differ in sign (Fritsch-Carlson monotonicity
// region). h0, secant0: the end interval; h1, secant1: the next one inwards.
double end_slope(double h0, double h1, double secant0, double secant1) {
  const double slope = ((2.0 * h0 + h1) * secant0 - h0 * secant1) / (h0 + h1);
  if (slope * secant0 <= 0.0) return 0.0;
  if (secant0 * secant1 <= 0.0 && std::abs(slope) > std::abs(3.0 * secant0)) return 3.0 * secant0;
  return slope;
}

}  // namespace

double pchip_interpolate(std::span<const double> x, std::span<const double> y, double x_query) {
  const std::size_t n = x.size();
  require(n >= 4 && y.size() == n, "pchip: need at least four nodes and as many values as abscissae");
  for (std::size_t i = 0; i + 1 < n; ++i) {
    require(x[i + 1] > x[i], "pchip: abscissae must be strictly increasing");
  }
  require(x_query >= x.front() && x_query <= x.back(), "pchip: query point outside the interpolation range");
  const auto secant = [&](std::size_t i) { return (y[i + 1] - y[i]) / (x[i + 1] - x[i]); };
  const double left = end_slope(x[1] - x[0], x[2] - x[1], secant(0), secant(1));
  const double right = end_slope(x[n - 1] - x[n - 2], x[n - 2] - x[n - 3], secant(n - 2), secant(n - 3));
  const boost::math::interpolators::pchip<std::vector<double>> interpolant(
      std::vector<double>(x.begin(), x.end()), std::vector<double>(y.begin(), y.end()), left, right);
  return interpolant(x_query);
}

}  // namespace railcontact::detail
