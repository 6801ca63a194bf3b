#pragma once
// The per-patch geometry of FastSim's strip marching (paper Eq 1-3, METHOD.md §7): the march
// (fastsim.cpp) and S D B of Eq 19 (FastSim::adhesion_force_matrix, the flexibility matching's
// input) use exactly these discrete increments.
//
// Each strip run is marched from its leading edge (largest x1) towards its trailing edge. The
// march visits the element centres; the "upstream point" of an element is the previous centre
// of its run, or the leading edge x_l for the run's leading element. With
//   step_e = x1_e - x1_upstream   (< 0: -dx1/2 for the leading element, -dx1 after it)
// the increments of the adhesion traction of Eq 2-3 between the upstream point and the centre
// of element e are exactly
//   dp1 = (xi/L1 - phi x2_e / L3) step_e                                    (from Eq 2)
//   dp2 = (eta/L2) step_e + (phi/L3) (x1_e^2 - x1_upstream^2) / 2           (from Eq 3)
// with (x1_e^2 - x1_upstream^2)/2 = step_e (x1_e - step_e/2). Summed from
// the leading edge (where Eq 2-3 vanish) they telescope to Eq 2-3 at the element centre.
#include <vector>

#include "railcontact/contact_patch.hpp"

namespace railcontact::fastsim_detail {

// step_e (m) per contact element, in the order of patch.elements().indices().
std::vector<double> march_steps_m(const ContactPatch& patch);

// Traction bound p3e (Pa) per contact element (TractionBound in tangential.hpp): for each run
//   p3e = h t (1 - t) (1 + skew t),   t = (x_l - x1) / (x_l - x_t)
// at the element centres, with the run's own leading and trailing edges x_l, x_t and h such that
// sum(p3e) = sum(p3) over the run's elements (same discrete strip force). skew = 0 is the
// paper's parabola p3e = h' (1 - 4 ((x1 - x_c) / (x_l - x_t))^2) of Eq 1 (4 t (1 - t) = 1 - 4 u^2
// with u = (x1 - x_c) / (x_l - x_t) = 1/2 - t).
std::vector<double> traction_bound_Pa(const ContactPatch& patch, double skew);

}  // namespace railcontact::fastsim_detail
