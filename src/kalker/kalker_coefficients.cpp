// Kalker's creepage coefficients C11, C22, C23 of the linear theory for an elliptical contact
// patch, and the flexibilities of original FastSim (paper Eq 9).
//
// Inside the table (0.1 <= a/b <= 10, Kalker 1990 Table E.3, compiled in from
// data/kalker_creepage_coefficients.csv):
//  * in nu: quadratic Lagrange interpolation through nu = 0, 0.25, 0.5, exact at the table's nu
//    (C22 is nearly linear in nu, C11 and C23 are not);
//  * in a/b: shape-preserving cubic Hermite (PCHIP, kalker/pchip_interpolation.hpp) of ln C against
//    ln(a/b), one interpolant over all 19 rows (both halves of Kalker's table, a/b = 0.1 ... 1 and
//    b/a = 0.9 ... 0.1). In log-log form the coefficients are nearly straight lines at both ends
//    (C23 ~ (a/b)^{1/2} for small a/b, C ~ (a/b)^{1 or 3/2} / ln(a/b) for large a/b), so the cubic
//    is accurate even across the wide gap a/b = 5 ... 10, and the interpolant is C1 at a/b = 1.
//    Leave-one-out check (each interior row interpolated from the others, all 3 nu, 3 coefficients,
//    153 cases; test KalkerCoefficients.LeaveOneOutInterpolationError): max relative error 0.62 %
//    (C11, nu = 0.5, a/b = 0.5, near C11's shallow minimum); elsewhere below ~0.5 %, the level of
//    the table's three-digit rounding. For comparison (same leave-one-out, prototype script):
//    linear in a/b resp. b/a 46 %; PCHIP in a/b resp. b/a 21 %; PCHIP of (b/a) C11, (b/a) C22,
//    (b/a)^{3/2} C23 resp. C23/sqrt(a/b) 3.2 %; natural cubic spline in log-log 0.64 %; Akima 0.65 %.
//    Removing a row doubles the local spacing, so the true interpolation error is much smaller.
//
// Outside the table (0.01 <= a/b < 0.1 and 10 < a/b <= 100): Kalker's slender-ellipse asymptotes
// (kalker/kalker_asymptotics.hpp). At the joints they differ from the table by (asymptote/table - 1):
//   a/b = 0.1:  nu = 0:    C11 -1.70 %, C22 -1.70 %, C23 -0.85 %
//               nu = 0.25: C11 -0.61 %, C22 -2.09 %, C23 -4.90 %
//               nu = 0.5:  C11 +1.75 %, C22 -2.47 %, C23 -5.99 %
//   a/b = 10:   nu = 0:    C11 -3.00 %, C22 -3.00 %, C23 +0.95 %
//               nu = 0.25: C11 -3.60 %, C22 -2.32 %, C23 +0.07 %
//               nu = 0.5:  C11 -4.31 %, C22 -1.84 %, C23 -0.25 %
// which is too much for a jump, so the asymptote is blended onto the table:
//   C(a/b) = C_asymptote(a/b) · [1 + (r - 1) w],   r = C_table / C_asymptote at the joint,
// with w = 1 at the joint and w -> 0 for the slender limit at the rate of the terms the asymptote
// neglects: w = (a/b) / 0.1 on the narrow side (corrections O(g) in g = a/b), w = (Λ_joint / Λ)²
// on the long side (the expansion in 1/Λ, Λ = ln(16 (a/b)²), neglects O(1/Λ²)). C is then
// continuous at the joints and tends to Kalker's asymptote for a/b -> 0 and a/b -> ∞.
// Shape (test KalkerCoefficients.MonotoneInAOverB): C22 and C23 increase with a/b for every nu;
// C11 increases for a/b >= 0.4 and may have one shallow minimum below that (nu > ~0.4, where the
// table has one, and nu ≈ 0.1, where table and asymptote differ by 0.015 % at a/b = 0.1).
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <span>

#include "kalker/kalker_asymptotics.hpp"
#include "kalker/pchip_interpolation.hpp"
#include "railcontact/error.hpp"
#include "railcontact/kalker.hpp"

namespace railcontact {
namespace {

constexpr double kTableMinAOverB = 0.1;
constexpr double kTableMaxAOverB = 10.0;
constexpr double kMinAOverB = 0.01;
constexpr double kMaxAOverB = 100.0;
constexpr std::size_t kRowsPerNu = 19;                   // a/b = 0.1 ... 1 ... 10
constexpr std::array<double, 3> kTableNu = {0.0, 0.25, 0.5};
constexpr std::size_t kNumCoefficients = 3;              // C11, C22, C23

// Kalker's table reorganised per coefficient and per nu, rows sorted by a/b.
struct KalkerTable {
  std::array<double, kRowsPerNu> log_a_over_b{};
  // value[coefficient][nu index][row]
  std::array<std::array<std::array<double, kRowsPerNu>, kTableNu.size()>, kNumCoefficients> value{};
};

KalkerTable build_table() {
  KalkerTable table;
  std::array<std::size_t, kTableNu.size()> count{};
  std::array<double, kRowsPerNu> a_over_b{};
  for (const KalkerTableRow& row : kalker_table_rows()) {
    std::size_t k = 0;
    while (k < kTableNu.size() && row.nu != kTableNu[k]) ++k;
    require(k < kTableNu.size(), [&] { return fmt::format("kalker: table row with unexpected nu = {}", row.nu); });
    const std::size_t i = count[k]++;
    require(i < kRowsPerNu, "kalker: too many table rows for one nu");
    if (k == 0) {
      require(i == 0 || row.a_over_b > a_over_b[i - 1], "kalker: table rows must be sorted by a/b");
      a_over_b[i] = row.a_over_b;
    } else {
      require(row.a_over_b == a_over_b[i], "kalker: the table must list the same a/b for every nu");
    }
    table.value[0][k][i] = row.c11;
    table.value[1][k][i] = row.c22;
    table.value[2][k][i] = row.c23;
  }
  for (const std::size_t c : count) require(c == kRowsPerNu, "kalker: every nu needs 19 table rows");
  require(a_over_b.front() == kTableMinAOverB && a_over_b.back() == kTableMaxAOverB,
          "kalker: the table must span a/b = 0.1 ... 10");
  for (std::size_t i = 0; i < kRowsPerNu; ++i) table.log_a_over_b[i] = std::log(a_over_b[i]);
  return table;
}

const KalkerTable& kalker_table() {
  static const KalkerTable table = build_table();  // immutable after first use
  return table;
}

// Quadratic Lagrange weights through nu = 0, 0.25, 0.5 (each exactly 0 or 1 at those nodes).
std::array<double, 3> lagrange_weights_in_nu(double nu) {
  return {(nu - 0.25) * (nu - 0.5) / 0.125, nu * (nu - 0.5) / -0.0625, nu * (nu - 0.25) / 0.125};
}

// Table interpolation for 0.1 <= a/b <= 10 (see the file comment).
KalkerCoefficients table_coefficients(double a_over_b, double nu) {
  const KalkerTable& table = kalker_table();
  const std::array<double, 3> w = lagrange_weights_in_nu(nu);
  std::array<double, kNumCoefficients> result{};
  for (std::size_t c = 0; c < kNumCoefficients; ++c) {
    std::array<double, kRowsPerNu> log_value{};
    for (std::size_t i = 0; i < kRowsPerNu; ++i) {
      const double value = w[0] * table.value[c][0][i] + w[1] * table.value[c][1][i] + w[2] * table.value[c][2][i];
      log_value[i] = std::log(value);
    }
    result[c] = std::exp(detail::pchip_interpolate(table.log_a_over_b, log_value, std::log(a_over_b)));
  }
  return {result[0], result[1], result[2]};
}

// Asymptote scaled onto the table at the joint: C = C_asym · [1 + (C_table/C_asym at joint - 1) w].
KalkerCoefficients blend(const KalkerCoefficients& asymptote, const KalkerCoefficients& asymptote_at_joint,
                         const KalkerCoefficients& table_at_joint, double weight) {
  const auto one = [weight](double value, double at_joint, double table) {
    return value * (1.0 + (table / at_joint - 1.0) * weight);
  };
  return {one(asymptote.C11, asymptote_at_joint.C11, table_at_joint.C11),
          one(asymptote.C22, asymptote_at_joint.C22, table_at_joint.C22),
          one(asymptote.C23, asymptote_at_joint.C23, table_at_joint.C23)};
}

}  // namespace

KalkerCoefficients kalker_coefficients(double a_over_b, double nu) {
  require(std::isfinite(nu) && nu >= 0.0 && nu <= 0.5,
          [&] { return fmt::format("kalker: Poisson's ratio nu = {:g} must lie in [0, 0.5]", nu); });
  require(std::isfinite(a_over_b) && a_over_b >= kMinAOverB && a_over_b <= kMaxAOverB, [&] {
    return fmt::format("kalker: semi-axis ratio a/b = {} must lie in [{}, {}]", a_over_b, kMinAOverB, kMaxAOverB);
  });

  if (a_over_b < kTableMinAOverB) {
    const double weight = a_over_b / kTableMinAOverB;
    return blend(detail::kalker_asymptotic_narrow(a_over_b, nu), detail::kalker_asymptotic_narrow(kTableMinAOverB, nu),
                 table_coefficients(kTableMinAOverB, nu), weight);
  }
  if (a_over_b > kTableMaxAOverB) {
    const double lambda = std::log(16.0 * a_over_b * a_over_b);  // Λ = ln(16/g²), g = b/a
    const double lambda_joint = std::log(16.0 * kTableMaxAOverB * kTableMaxAOverB);
    const double weight = (lambda_joint / lambda) * (lambda_joint / lambda);
    return blend(detail::kalker_asymptotic_long(a_over_b, nu), detail::kalker_asymptotic_long(kTableMaxAOverB, nu),
                 table_coefficients(kTableMaxAOverB, nu), weight);
  }
  return table_coefficients(a_over_b, nu);
}

// Paper Eq 9 (Kalker's simplified theory): L1 = 8a/(3 C11 G), L2 = 8a/(3 C22 G),
// L3 = π a^{3/2} / (4 sqrt(b) C23 G).
Flexibility fastsim_flexibility(double a_m, double b_m, const Material& material) {
  validate(material);
  require(std::isfinite(a_m) && a_m > 0.0,
          [&] { return fmt::format("fastsim flexibility: semi-axis a = {} m must be positive and finite", a_m); });
  require(std::isfinite(b_m) && b_m > 0.0,
          [&] { return fmt::format("fastsim flexibility: semi-axis b = {} m must be positive and finite", b_m); });
  const double g_Pa = material.shear_modulus_Pa();
  const KalkerCoefficients c = kalker_coefficients(a_m / b_m, material.poisson_ratio);
  Flexibility flexibility;
  flexibility.L1 = 8.0 * a_m / (3.0 * c.C11 * g_Pa);
  flexibility.L2 = 8.0 * a_m / (3.0 * c.C22 * g_Pa);
  flexibility.L3 = std::numbers::pi * a_m * std::sqrt(a_m / b_m) / (4.0 * c.C23 * g_Pa);
  return flexibility;
}

}  // namespace railcontact
