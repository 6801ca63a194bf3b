#pragma once
// A patch solved lobe by lobe (NhFastSimPerLobe, the table-driven model, a wheelset table's
// conformal patches): each lobe takes the rigid slip at its own centre of pressure, its forces add
// up with the spin moment moved to the patch's origin, and where a neck widens the lobes' sum is
// blended with the whole patch's solution (docs/WHEELSET.md §8).
#include "railcontact/contact_patch.hpp"

namespace railcontact::detail {

// The creepages at (x1, x2) from those at the patch's origin: the rigid slip (ξ − φ x2, η + φ x1).
inline Creepage creepage_at(const Creepage& c, double x1_m, double x2_m) {
  return {c.xi - c.phi * x2_m, c.eta + c.phi * x1_m, c.phi};
}

// The spin moment about the patch's origin of a lobe's forces, its own moment taken about its
// centre (x1, x2).
inline double moment_about_origin_Nm(const TangentialForces& lobe, double x1_m, double x2_m) {
  return lobe.M3_Nm + x1_m * lobe.F2_N - x2_m * lobe.F1_N;
}

// A lobe's forces added to the patch's sum (M3 about the patch's origin).
inline void add_lobe(TangentialForces& sum, const TangentialForces& lobe, double x1_m, double x2_m) {
  sum.F1_N += lobe.F1_N;
  sum.F2_N += lobe.F2_N;
  sum.M3_Nm += moment_about_origin_Nm(lobe, x1_m, x2_m);
}

// The lobes' sum blended with the whole patch's, weight w of the whole patch's.
inline double blend(double per_lobe, double whole, double w) { return (1.0 - w) * per_lobe + w * whole; }
inline TangentialForces blend(const TangentialForces& per_lobe, const TangentialForces& whole, double w) {
  return {blend(per_lobe.F1_N, whole.F1_N, w), blend(per_lobe.F2_N, whole.F2_N, w), blend(per_lobe.M3_Nm, whole.M3_Nm, w)};
}

}  // namespace railcontact::detail
