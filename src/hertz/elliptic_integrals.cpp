#include "hertz/elliptic_integrals.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "railcontact/error.hpp"

namespace railcontact::detail {
namespace {

// Stop the duplication when all arguments lie within this relative distance of their mean:
// the truncation error of the 5th-order series below is then ~ kTolerance^6 ~ 1e-18
// (Carlson 1995, eq. 2.2 and 2.6).
constexpr double kTolerance = 1e-3;
constexpr int kMaxDuplications = 100;  // each one reduces the spread by 4; 30 suffice in practice

}  // namespace

// Duplication theorem R_F(x,y,z) = R_F((x+λ)/4, (y+λ)/4, (z+λ)/4), λ = √x√y + √y√z + √z√x,
// then the series (Carlson 1995, eq. 2.2) in X = 1 - x/μ etc. (X + Y + Z = 0):
// R_F = μ^{-1/2} (1 - E2/10 + E3/14 + E2²/24 - 3 E2 E3/44), E2 = XY - Z², E3 = XYZ.
double carlson_rf(double x, double y, double z) {
  require(x >= 0 && y >= 0 && z >= 0 && (x + y > 0) && (y + z > 0) && (z + x > 0),
          "elliptic integrals: R_F needs non-negative arguments, at most one zero");
  double mean = (x + y + z) / 3.0;
  double dx = 1.0 - x / mean, dy = 1.0 - y / mean, dz = 1.0 - z / mean;
  for (int n = 0; n < kMaxDuplications && std::max({std::abs(dx), std::abs(dy), std::abs(dz)}) > kTolerance; ++n) {
    const double sx = std::sqrt(x), sy = std::sqrt(y), sz = std::sqrt(z);
    const double lambda = sx * (sy + sz) + sy * sz;
    x = 0.25 * (x + lambda);
    y = 0.25 * (y + lambda);
    z = 0.25 * (z + lambda);
    mean = (x + y + z) / 3.0;
    dx = 1.0 - x / mean;
    dy = 1.0 - y / mean;
    dz = 1.0 - z / mean;
  }
  const double e2 = dx * dy - dz * dz;
  const double e3 = dx * dy * dz;
  return (1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0 - 3.0 * e2 * e3 / 44.0) / std::sqrt(mean);
}

// Duplication as for R_F plus the accumulated sum 3 Σ 4^{-n} / (√z_n (z_n + λ_n)), then the series
// (Carlson 1995, eq. 2.6) with μ = (x + y + 3z)/5, X = 1 - x/μ, ..., X + Y + 3Z = 0:
// R_D = 3 Σ + 4^{-N} μ^{-3/2} (1 - 3E2/14 + E3/6 + 9E2²/88 - 3E4/22 - 9E2E3/52 + 3E5/26),
// E2 = XY - 6Z², E3 = (3XY - 8Z²) Z, E4 = 3 (XY - Z²) Z², E5 = XY Z³.
double carlson_rd(double x, double y, double z) {
  require(x >= 0 && y >= 0 && (x + y > 0) && z > 0,
          "elliptic integrals: R_D needs x, y >= 0 (not both zero) and z > 0");
  double sum = 0.0;
  double scale = 1.0;  // 4^{-n}
  double mean = (x + y + 3.0 * z) / 5.0;
  double dx = 1.0 - x / mean, dy = 1.0 - y / mean, dz = 1.0 - z / mean;
  for (int n = 0; n < kMaxDuplications && std::max({std::abs(dx), std::abs(dy), std::abs(dz)}) > kTolerance; ++n) {
    const double sx = std::sqrt(x), sy = std::sqrt(y), sz = std::sqrt(z);
    const double lambda = sx * (sy + sz) + sy * sz;
    sum += scale / (sz * (z + lambda));
    scale *= 0.25;
    x = 0.25 * (x + lambda);
    y = 0.25 * (y + lambda);
    z = 0.25 * (z + lambda);
    mean = (x + y + 3.0 * z) / 5.0;
    dx = 1.0 - x / mean;
    dy = 1.0 - y / mean;
    dz = 1.0 - z / mean;
  }
  const double xy = dx * dy;
  const double z2 = dz * dz;
  const double e2 = xy - 6.0 * z2;
  const double e3 = (3.0 * xy - 8.0 * z2) * dz;
  const double e4 = 3.0 * (xy - z2) * z2;
  const double e5 = xy * z2 * dz;
  const double series = 1.0 - 3.0 * e2 / 14.0 + e3 / 6.0 + 9.0 * e2 * e2 / 88.0 - 3.0 * e4 / 22.0 -
                        9.0 * e2 * e3 / 52.0 + 3.0 * e5 / 26.0;
  return 3.0 * sum + scale * series / (mean * std::sqrt(mean));
}

// K = R_F(0, mc, 1) (DLMF 19.25.1), D = (K - E)/m = R_D(0, mc, 1)/3, B = K - D, E = B + mc D.
CompleteEllipticIntegrals complete_elliptic_integrals(double complementary_parameter) {
  const double mc = complementary_parameter;
  require(std::isfinite(mc) && mc > 0.0 && mc <= 1.0,
          "elliptic integrals: the complementary parameter 1 - k^2 must lie in (0, 1]");
  CompleteEllipticIntegrals out;
  if (mc == 1.0) {  // circle: the series are exact, avoid the iteration
    out.K = out.E = 0.5 * std::numbers::pi;
    out.B = out.D = 0.25 * std::numbers::pi;
    return out;
  }
  out.K = carlson_rf(0.0, mc, 1.0);
  out.D = carlson_rd(0.0, mc, 1.0) / 3.0;
  out.B = out.K - out.D;
  out.E = out.B + mc * out.D;
  return out;
}

}  // namespace railcontact::detail
