#include "hertz/elliptic_integrals.hpp"

#include <boost/math/special_functions/ellint_rd.hpp>
#include <boost/math/special_functions/ellint_rf.hpp>
#include <cmath>
#include <numbers>

#include "railcontact/error.hpp"

namespace railcontact::detail {

// K = R_F(0, mc, 1) (DLMF 19.25.1), D = (K - E)/m = R_D(0, mc, 1)/3, B = K - D, E = B + mc D.
// Boost's default policy evaluates them in long double (measured against 40-digit mpmath over
// mc = 1e-200 ... 1: within 0.7 ulp).
CompleteEllipticIntegrals complete_elliptic_integrals(double complementary_parameter) {
  const double mc = complementary_parameter;
  require(std::isfinite(mc) && mc > 0.0 && mc <= 1.0,
          "elliptic integrals: the complementary parameter 1 - k^2 must lie in (0, 1]");
  CompleteEllipticIntegrals out;
  if (mc == 1.0) {  // circle: exact values
    out.K = out.E = 0.5 * std::numbers::pi;
    out.B = out.D = 0.25 * std::numbers::pi;
    return out;
  }
  out.K = boost::math::ellint_rf(0.0, mc, 1.0);
  out.D = boost::math::ellint_rd(0.0, mc, 1.0) / 3.0;
  out.B = out.K - out.D;
  out.E = out.B + mc * out.D;
  return out;
}

}  // namespace railcontact::detail
