#pragma once
// Starting pressure for the normal solver (METHOD.md §5): a Hertz-like distribution on an
// interpenetration region of the undeformed distance, sized to be consistent with the load.
//
// With z = h - min(h), the trial pressure on the region z < d is
//   p = c sqrt(1 - z / d),   c such that sum p = P (= F3 / S),
// which for a quadratic h is Hertz's ellipsoidal pressure on the ellipse z < d (Johnson,
// Contact Mechanics §4.2). In the solution, A p = delta - h on the contact area, i.e. the
// displacement falls with slope 1 against z. For the trial pressure, the least-squares slope k
// of A p against z over the region scales as F3 / (L d) ~ d^(-3/2) (region size L ~ sqrt(d)),
// so d <- d k^(2/3) makes it consistent (exactly so for a circular Hertz contact). One update
// (one FFT product) from d = the lower quartile of z: on the 80 x 60 Hertz benchmark the
// solver then needs 16 iterations instead of 19 (27 vs 22 at 160 x 120); a second update
// changes nothing measurable.
#include <span>
#include <vector>

#include "elastic/influence_operator.hpp"

namespace railcontact::detail {

// Writes the starting pressure into p (one value per mesh element, sum p = pressure_sum).
// work: scratch of mesh size (the trial displacement).
void hertz_like_initial_pressure(InfluenceOperator& A, std::span<const double> h, double pressure_sum,
                                 std::span<double> p, std::vector<double>& work);

}  // namespace railcontact::detail
