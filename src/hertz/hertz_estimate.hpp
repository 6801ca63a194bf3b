#pragma once
// Internal: Hertz's closed form without the physical ranges of railcontact/hertz.hpp, for the
// wheel-rail patch's first estimate from the profiles' local curvatures (a conformal contact has B
// below kMinimumRelativeCurvature_per_m; the estimate only seeds the mesh of the true patch).
#include "railcontact/hertz.hpp"

namespace railcontact::detail {

// hertz_from_curvatures for any A, B > 0 and finite, F3 > 0 and a valid material; a result that
// is not positive and finite throws Error (internal).
HertzContact hertz_estimate(double A_per_m, double B_per_m, double normal_force_N, const Material& material);

}  // namespace railcontact::detail
