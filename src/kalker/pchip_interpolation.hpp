#pragma once
// Shape-preserving piecewise cubic Hermite interpolation (PCHIP) of Kalker's table: Boost.Math's
// pchip (boost/math/interpolators/pchip.hpp) with the end slopes chosen here.
//  * Interior slopes (Boost's): Fritsch & Butland, SIAM J. Sci. Stat. Comput. 5 (1984) 300-304,
//    the weighted harmonic mean of the neighbouring secants with Brodlie's weights for unequal
//    spacing, zero at a local extremum (Fritsch & Carlson, SIAM J. Numer. Anal. 17 (1980) 238-246).
//  * End slopes (ours, passed to Boost): the three-point shape-preserving rule of Moler, Numerical
//    Computing with MATLAB (2004) §3.6. Boost's default end slope is the first secant, which is
//    only first-order accurate; on the table's wide last interval (a/b = 5 ... 10) it moves C11 by
//    up to 0.62 % (docs/DEPENDENCIES.md, "Numerical routines").
// The interpolant is C1, passes through the data exactly and is monotone on every interval where
// the data are monotone (no overshoot), which a natural cubic spline does not guarantee.
#include <span>

namespace railcontact::detail {

// Value at x_query of the PCHIP through (x, y): x strictly increasing, x.size() == y.size() >= 4
// (Boost's minimum), x_query in [x.front(), x.back()]; throws railcontact::Error otherwise. At a
// node the node value is returned exactly.
double pchip_interpolate(std::span<const double> x, std::span<const double> y, double x_query);

}  // namespace railcontact::detail
