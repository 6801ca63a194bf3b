// Kalker's slender-ellipse asymptotes of the linear-theory creepage coefficients.
// Source: J.J. Kalker, Three-dimensional elastic bodies in rolling contact, Kluwer 1990, Table E.3
// (asymptotic rows for g -> 0); the same expressions are used by Vollebregt's CONTACT (m_hertz,
// routine linrol), which we read to confirm the transcription. Checked against the table: at
// g = 0.1 they agree within 0.07 % ... 6 % (see kalker_coefficients.cpp for the joint).
#include "kalker/kalker_asymptotics.hpp"

#include <cmath>
#include <numbers>

namespace railcontact::detail {

KalkerCoefficients kalker_asymptotic_narrow(double a_over_b, double nu) {
  constexpr double pi = std::numbers::pi;
  const double g = a_over_b;
  KalkerCoefficients c;
  c.C11 = pi * pi / (4.0 * (1.0 - nu));
  c.C22 = pi * pi / 4.0;
  c.C23 = pi * std::sqrt(g) / (3.0 * (1.0 - nu)) * (1.0 + nu * (std::log(16.0 / g) - 5.0));
  return c;
}

KalkerCoefficients kalker_asymptotic_long(double a_over_b, double nu) {
  constexpr double pi = std::numbers::pi;
  const double g = 1.0 / a_over_b;                    // b/a
  const double lambda = std::log(16.0 / (g * g));     // Λ
  const double c0 = 3.0 - std::log(4.0);
  const double d11 = lambda - 2.0 * nu;
  const double d22 = (1.0 - nu) * lambda + 2.0 * nu;
  KalkerCoefficients c;
  c.C11 = 2.0 * pi / (d11 * g) * (1.0 + c0 / d11);
  c.C22 = 2.0 * pi / (d22 * g) * (1.0 + (1.0 - nu) * c0 / d22);
  c.C23 = 2.0 * pi / (3.0 * g * std::sqrt(g) * ((1.0 - nu) * lambda - 2.0 + 4.0 * nu));
  return c;
}

}  // namespace railcontact::detail
