#pragma once
// Kalker's asymptotic expressions for the creepage coefficients of slender contact ellipses,
// Kalker, Three-dimensional elastic bodies in rolling contact (1990), Appendix E, footnotes of
// Table E.3 (first derived in Kalker's thesis, Delft 1967). a is the semi-axis along X1 (rolling).
#include "railcontact/kalker.hpp"

namespace railcontact::detail {

// g = a/b -> 0 (ellipse narrow in the rolling direction):
//   C11 = π² / (4 (1 - ν)),   C22 = π² / 4,
//   C23 = π √g / (3 (1 - ν)) · [1 + ν (Λ/2 + ln 4 - 5)],   Λ = ln(16/g²), i.e. Λ/2 + ln 4 - 5 = ln(16/g) - 5.
KalkerCoefficients kalker_asymptotic_narrow(double a_over_b, double nu);

// g = b/a -> 0 (ellipse long in the rolling direction), Λ = ln(16/g²):
//   C11 = 2π / ((Λ - 2ν) g) · [1 + (3 - ln 4) / (Λ - 2ν)],
//   C22 = 2π / (((1 - ν) Λ + 2ν) g) · [1 + (1 - ν)(3 - ln 4) / ((1 - ν) Λ + 2ν)],
//   C23 = 2π / (3 g^{3/2} ((1 - ν) Λ - 2 + 4ν)).
KalkerCoefficients kalker_asymptotic_long(double a_over_b, double nu);

}  // namespace railcontact::detail
