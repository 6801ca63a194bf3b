#pragma once
// Shape-preserving piecewise cubic Hermite interpolation (PCHIP): Fritsch & Carlson, "Monotone
// piecewise cubic interpolation", SIAM J. Numer. Anal. 17 (1980) 238-246, with the interior
// slopes of Fritsch & Butland, SIAM J. Sci. Stat. Comput. 5 (1984) 300-304 (weighted harmonic
// mean of the neighbouring secants, zero at local extrema) and the three-point shape-preserving
// end slopes of Moler, Numerical Computing with MATLAB (2004) §3.6. The interpolant is C1, passes
// through the data exactly and is monotone on every interval where the data are monotone
// (no overshoot), which a natural cubic spline does not guarantee.
#include <span>

namespace railcontact::detail {

// Slopes dy/dx at the nodes; x strictly increasing, x.size() == y.size() == slopes.size() >= 2.
void pchip_slopes(std::span<const double> x, std::span<const double> y, std::span<double> slopes);

// Evaluates the cubic Hermite interpolant with the given node slopes at x_query in [x.front(), x.back()]
// (throws outside). At a node the node value is returned exactly.
double hermite_interpolate(std::span<const double> x, std::span<const double> y, std::span<const double> slopes,
                           double x_query);

}  // namespace railcontact::detail
