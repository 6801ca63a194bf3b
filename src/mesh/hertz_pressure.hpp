#pragma once
// Internal: the pressure part of validate_ellipse (railcontact/contact_patch.hpp) alone, for Hertz's
// closed form (src/hertz), which has no mesh and takes any axis ratio.
#include <string_view>

namespace railcontact::detail {

// Throws Error (invalid_input) unless p0 = 3 F3 / (2 pi a b) <= kMaximumHertzPressure_Pa; the
// message starts with `inputs`.
void validate_hertz_pressure(double a_m, double b_m, double normal_force_N, std::string_view inputs);

}  // namespace railcontact::detail
