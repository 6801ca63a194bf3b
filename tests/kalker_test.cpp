// Tests of Kalker's creepage coefficients (src/kalker/kalker_coefficients.cpp) and of the FastSim
// flexibilities (paper Eq 9). References: Kalker's Table E.3 itself (compiled-in rows), Kalker's
// slender-ellipse asymptotes evaluated by an independent script, hand-evaluated Eq 9.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <iostream>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "kalker/kalker_asymptotics.hpp"
#include "kalker/pchip_interpolation.hpp"
#include "railcontact/error.hpp"
#include "railcontact/kalker.hpp"
#include "railcontact/contact_patch.hpp"

namespace railcontact {
namespace {

constexpr double pi = std::numbers::pi;

double rel_diff(double value, double reference) { return std::abs(value / reference - 1.0); }

std::array<double, 3> as_array(const KalkerCoefficients& c) { return {c.C11, c.C22, c.C23}; }
std::array<double, 3> as_array(const KalkerTableRow& row) { return {row.c11, row.c22, row.c23}; }

// 2001 points log-spaced over the whole admissible range a/b = 0.01 ... 100.
std::vector<double> a_over_b_grid() {
  std::vector<double> grid;
  for (int i = 0; i <= 2000; ++i) grid.push_back(std::pow(10.0, -2.0 + 4.0 * i / 2000.0));
  grid.front() = 0.01;
  grid.back() = 100.0;
  return grid;
}

// Every row, the nu = 0.5 (incompressible) rows included.
TEST(KalkerCoefficients, ExactAtEveryTableRow) {
  const auto rows = kalker_table_rows();
  ASSERT_EQ(rows.size(), 57u);
  for (const KalkerTableRow& row : rows) {
    const auto value = as_array(kalker_coefficients(row.a_over_b, row.nu));
    const auto table = as_array(row);
    for (std::size_t c = 0; c < 3; ++c) {
      EXPECT_LT(rel_diff(value[c], table[c]), 1e-12) << "a/b = " << row.a_over_b << ", nu = " << row.nu << ", C" << c;
    }
  }
}

// Leave-one-out check of the interpolation scheme in a/b used by kalker_coefficients (PCHIP of
// ln C against ln(a/b)): every interior row of every (nu, coefficient) column is interpolated from
// the other 18 rows. Measured: max 0.62 % (C11, nu = 0.5, a/b = 0.5); the table has 3 digits.
// It also checks the end slopes of detail::pchip_interpolate: with Boost's default (the end secant)
// the rows next to the ends (a/b = 0.2, 5) come out up to 1.13 % off.
TEST(KalkerCoefficients, LeaveOneOutInterpolationError) {
  const auto rows = kalker_table_rows();
  double worst = 0.0;
  int cases = 0;
  for (const double nu : {0.0, 0.25, 0.5}) {
    std::vector<KalkerTableRow> column;
    for (const auto& row : rows) {
      if (row.nu == nu) column.push_back(row);
    }
    ASSERT_EQ(column.size(), 19u);
    for (std::size_t c = 0; c < 3; ++c) {
      for (std::size_t left_out = 1; left_out + 1 < column.size(); ++left_out) {
        std::vector<double> x, y;
        for (std::size_t i = 0; i < column.size(); ++i) {
          if (i == left_out) continue;
          x.push_back(std::log(column[i].a_over_b));
          y.push_back(std::log(as_array(column[i])[c]));
        }
        const double value = std::exp(detail::pchip_interpolate(x, y, std::log(column[left_out].a_over_b)));
        worst = std::max(worst, rel_diff(value, as_array(column[left_out])[c]));
        ++cases;
      }
    }
  }
  EXPECT_EQ(cases, 153);
  std::cout << "[ leave-one-out ] max relative interpolation error " << 100.0 * worst << " %\n";
  RecordProperty("leave_one_out_max_relative_error", std::to_string(worst));
  EXPECT_LT(worst, 0.0065);
}

TEST(KalkerCoefficients, QuadraticInNuAtCircle) {
  // a/b = 1 is a table row; nu = 0.3: Lagrange weights (-0.08, 0.96, 0.12) on nu = 0, 0.25, 0.5.
  const KalkerCoefficients c = kalker_coefficients(1.0, 0.3);
  EXPECT_NEAR(c.C11, -0.08 * 3.40 + 0.96 * 4.12 + 0.12 * 5.20, 1e-12);
  EXPECT_NEAR(c.C22, -0.08 * 3.40 + 0.96 * 3.67 + 0.12 * 3.98, 1e-12);
  EXPECT_NEAR(c.C23, -0.08 * 1.33 + 0.96 * 1.47 + 0.12 * 1.63, 1e-12);
}

// For nu = 0 the longitudinal and lateral problems coincide: C11 = C22 in the table and in both
// asymptotes, hence everywhere.
TEST(KalkerCoefficients, C11EqualsC22ForNuZero) {
  for (const double g : a_over_b_grid()) {
    const KalkerCoefficients c = kalker_coefficients(g, 0.0);
    EXPECT_LT(rel_diff(c.C11, c.C22), 1e-12) << "a/b = " << g;
  }
}

// C22 and C23 grow with a/b for every nu, and so does C11 for a/b >= 0.4. For small a/b, C11 may
// have one shallow minimum: Kalker's table itself has one for nu = 0.5 (4.85, 4.81, 4.80, 4.82 at
// a/b = 0.1 ... 0.4, below the asymptote π²/(4(1 - nu)) = 4.93), and for nu ≈ 0.1 the table at
// a/b = 0.1 lies 0.015 % below the asymptote. So: C11 decreasing-then-increasing, no oscillation.
TEST(KalkerCoefficients, MonotoneInAOverB) {
  const std::vector<double> grid = a_over_b_grid();
  for (const double nu : {0.0, 0.1, 0.2, 0.25, 0.3, 0.4, 0.45, 0.49, 0.4999}) {
    KalkerCoefficients previous = kalker_coefficients(grid.front(), nu);
    int c11_turns = 0;
    bool c11_rising = false;
    for (std::size_t i = 1; i < grid.size(); ++i) {
      const KalkerCoefficients c = kalker_coefficients(grid[i], nu);
      EXPECT_GT(c.C22, previous.C22) << "a/b = " << grid[i] << ", nu = " << nu;
      EXPECT_GT(c.C23, previous.C23) << "a/b = " << grid[i] << ", nu = " << nu;
      if (grid[i - 1] >= 0.4) {
        EXPECT_GT(c.C11, previous.C11) << "a/b = " << grid[i] << ", nu = " << nu;
      }
      const bool rising = c.C11 > previous.C11;
      if (i > 1 && rising != c11_rising) ++c11_turns;
      EXPECT_TRUE(rising || !c11_rising) << "C11 falls again after rising, a/b = " << grid[i] << ", nu = " << nu;
      c11_rising = rising;
      previous = c;
    }
    EXPECT_LE(c11_turns, 1) << "nu = " << nu;
    if (nu == 0.0 || (nu >= 0.2 && nu <= 0.4)) {
      EXPECT_EQ(c11_turns, 0) << "nu = " << nu;
    }
  }
}

// Before blending, Kalker's asymptotes differ from the table at the joints by up to 6 % (C23 at
// a/b = 0.1, nu = 0.5) and 4.3 % (C11 at a/b = 10, nu = 0.5): the numbers quoted in
// kalker_coefficients.cpp.
TEST(KalkerCoefficients, JointMismatchOfTheAsymptotes) {
  double worst_narrow = 0.0, worst_long = 0.0;
  for (const auto& row : kalker_table_rows()) {
    if (row.a_over_b == 0.1) {
      const auto asym = as_array(detail::kalker_asymptotic_narrow(0.1, row.nu));
      for (std::size_t c = 0; c < 3; ++c) worst_narrow = std::max(worst_narrow, rel_diff(asym[c], as_array(row)[c]));
    }
    if (row.a_over_b == 10.0) {
      const auto asym = as_array(detail::kalker_asymptotic_long(10.0, row.nu));
      for (std::size_t c = 0; c < 3; ++c) worst_long = std::max(worst_long, rel_diff(asym[c], as_array(row)[c]));
    }
  }
  std::cout << "[ joint mismatch ] a/b = 0.1: " << 100.0 * worst_narrow << " %, a/b = 10: " << 100.0 * worst_long << " %\n";
  EXPECT_NEAR(worst_narrow, 0.0599, 0.0005);
  EXPECT_NEAR(worst_long, 0.0431, 0.0005);
}

// After blending the coefficients are continuous at the joints.
TEST(KalkerCoefficients, ContinuousAtTableEdges) {
  for (const double nu : {0.0, 0.1, 0.25, 0.3, 0.4, 0.49}) {
    for (const double edge : {0.1, 10.0}) {
      const auto at = as_array(kalker_coefficients(edge, nu));
      const auto below = as_array(kalker_coefficients(edge * (1.0 - 1e-9), nu));
      const auto above = as_array(kalker_coefficients(edge * (1.0 + 1e-9), nu));
      for (std::size_t c = 0; c < 3; ++c) {
        EXPECT_LT(rel_diff(below[c], at[c]), 1e-8) << "a/b = " << edge << ", nu = " << nu << ", C" << c;
        EXPECT_LT(rel_diff(above[c], at[c]), 1e-8) << "a/b = " << edge << ", nu = " << nu << ", C" << c;
      }
    }
  }
}

// Kalker's asymptotes (Kalker 1990, Table E.3) transcribed correctly: values from an independent
// script, nu = 0.3; g = a/b = 0.01 resp. g = b/a = 0.01, Λ = ln(16/g²) = 11.98.
TEST(KalkerCoefficients, AsymptoteFormulas) {
  const KalkerCoefficients narrow = detail::kalker_asymptotic_narrow(0.01, 0.3);
  EXPECT_NEAR(narrow.C11, pi * pi / (4.0 * 0.7), 1e-13);
  EXPECT_NEAR(narrow.C22, pi * pi / 4.0, 1e-13);
  EXPECT_LT(rel_diff(narrow.C23, 0.2563132204294622), 1e-13);
  const KalkerCoefficients wide = detail::kalker_asymptotic_long(100.0, 0.3);
  EXPECT_LT(rel_diff(wide.C11, 63.023529400012514), 1e-13);
  EXPECT_LT(rel_diff(wide.C22, 78.69158288440846), 1e-13);
  EXPECT_LT(rel_diff(wide.C23, 276.01228265314234), 1e-13);
}

// At a/b = 0.01 and 100 the blended coefficients are close to Kalker's published asymptotes
// (the blend weight is 0.1 resp. (Λ(10)/Λ(100))² = 0.38 there).
TEST(KalkerCoefficients, SlenderLimitsApproachAsymptotes) {
  const KalkerCoefficients narrow = kalker_coefficients(0.01, 0.3);
  EXPECT_LT(rel_diff(narrow.C11, 3.524858714674771), 0.01);
  EXPECT_LT(rel_diff(narrow.C22, 2.4674011002723395), 0.01);
  EXPECT_LT(rel_diff(narrow.C23, 0.2563132204294622), 0.01);
  const KalkerCoefficients wide = kalker_coefficients(100.0, 0.3);
  EXPECT_LT(rel_diff(wide.C11, 63.023529400012514), 0.02);
  EXPECT_LT(rel_diff(wide.C22, 78.69158288440846), 0.02);
  EXPECT_LT(rel_diff(wide.C23, 276.01228265314234), 0.02);
  // nu = 0: C11 = C22 -> π²/4 for a/b -> 0, C23 -> π sqrt(g)/3.
  const KalkerCoefficients narrow0 = kalker_coefficients(0.01, 0.0);
  EXPECT_LT(rel_diff(narrow0.C11, pi * pi / 4.0), 0.01);
  EXPECT_LT(rel_diff(narrow0.C23, pi * 0.1 / 3.0), 0.01);
}

// Eq 9 by hand for a circle (a = b = 5 mm, a/b = 1 is a table row) and for a/b = 2 (a row too),
// nu = 0.25, G = E / (2 (1 + nu)) = 2.1e11 / 2.5 = 8.4e10 Pa.
TEST(FastsimFlexibility, Eq9ByHand) {
  const Material material{2.1e11, 0.25};
  const double G = 8.4e10;
  const Flexibility circle = fastsim_flexibility(0.005, 0.005, material);
  EXPECT_LT(rel_diff(circle.L1, 8.0 * 0.005 / (3.0 * 4.12 * G)), 1e-12);
  EXPECT_LT(rel_diff(circle.L2, 8.0 * 0.005 / (3.0 * 3.67 * G)), 1e-12);
  EXPECT_LT(rel_diff(circle.L3, pi * 0.005 / (4.0 * 1.47 * G)), 1e-12);  // a^{3/2}/sqrt(b) = a
  const Flexibility longer = fastsim_flexibility(0.010, 0.005, material);
  EXPECT_LT(rel_diff(longer.L1, 8.0 * 0.010 / (3.0 * 5.10 * G)), 1e-12);
  EXPECT_LT(rel_diff(longer.L2, 8.0 * 0.010 / (3.0 * 4.90 * G)), 1e-12);
  EXPECT_LT(rel_diff(longer.L3, pi * std::pow(0.010, 1.5) / (4.0 * std::sqrt(0.005) * 2.62 * G)), 1e-12);
}

TEST(KalkerCoefficients, RejectsBadInput) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  constexpr double inf = std::numeric_limits<double>::infinity();
  for (const double bad_nu : {-0.01, 0.51, 0.7, nan, inf}) EXPECT_THROW(kalker_coefficients(1.0, bad_nu), Error);
  for (const double bad_ratio : {0.0, -1.0, 0.0099, 100.01, 1e6, nan, inf}) {
    EXPECT_THROW(kalker_coefficients(bad_ratio, 0.3), Error);
  }
  EXPECT_NO_THROW(kalker_coefficients(0.01, 0.0));
  EXPECT_NO_THROW(kalker_coefficients(100.0, 0.4999));
  try {
    kalker_coefficients(250.0, 0.3);
    FAIL() << "expected railcontact::Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("a/b = 250"), std::string::npos) << error.what();
  }
  const Material steel{2.1e11, 0.3};
  for (const double bad : {0.0, -1e-3, nan, inf}) {
    EXPECT_THROW(fastsim_flexibility(bad, 5e-3, steel), Error);
    EXPECT_THROW(fastsim_flexibility(5e-3, bad, steel), Error);
  }
  EXPECT_THROW(fastsim_flexibility(5e-3, 5e-6, steel), Error);  // a/b = 1000: out of range
  EXPECT_THROW(fastsim_flexibility(5e-3, 5e-3, Material{2.1e11, 0.51}), Error);
}

}  // namespace
}  // namespace railcontact
