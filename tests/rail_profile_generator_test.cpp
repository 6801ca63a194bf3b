// The upright rail heads written by scripts/make_rail_profile.py (data/profiles/UIC60_upright.prr,
// 54E1_upright.prr) have the published key dimensions of EN 13674-1, measured from their points:
// the crown radii R300, R80 and R13 by circle fits on the middle of each arc, and the head width
// (72 mm for 60E1, 70 mm for 54E1) between the points where the R13 corners meet the 1:20 flanks.
// Every shipped set-up file reads, and its rail sits on the track as documented.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "railcontact/railcontact.hpp"

namespace railcontact {
namespace {

struct Circle {
  double y_m = 0.0, z_m = 0.0, radius_m = 0.0;
};

// Least-squares circle through the points (the algebraic fit: y² + z² = 2 a y + 2 b z + c), exact
// for points on a circle.
Circle fit_circle(const std::vector<std::array<double, 2>>& points) {
  // Normal equations of [2y 2z 1] (a b c)^T = y² + z², solved by Cramer's rule (3 x 3).
  double m[3][3] = {}, r[3] = {};
  for (const auto& p : points) {
    const double row[3] = {2.0 * p[0], 2.0 * p[1], 1.0}, rhs = p[0] * p[0] + p[1] * p[1];
    for (int i = 0; i < 3; ++i) {
      r[i] += row[i] * rhs;
      for (int j = 0; j < 3; ++j) m[i][j] += row[i] * row[j];
    }
  }
  const auto det = [](const double a[3][3]) {
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  };
  const double d = det(m);
  double x[3];
  for (int k = 0; k < 3; ++k) {
    double mk[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) mk[i][j] = j == k ? r[i] : m[i][j];
    x[k] = det(mk) / d;
  }
  return {x[0], x[1], std::sqrt(x[2] + x[0] * x[0] + x[1] * x[1])};
}

Profile shipped(const char* name) {
  return read_profile(std::filesystem::path(RAILCONTACT_SOURCE_DIR) / "data" / "profiles" / name);
}

// The points of the field side (y > 0) whose direction to the next point leans from the horizontal
// by an angle in [from, to] (rad): the middle of one arc.
std::vector<std::array<double, 2>> points_leaning(const Profile& p, double from_rad, double to_rad) {
  std::vector<std::array<double, 2>> out;
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    if (p.y_m[i] <= 0.0) continue;
    const double angle = std::atan2(p.z_m[i + 1] - p.z_m[i], p.y_m[i + 1] - p.y_m[i]);
    if (angle >= from_rad && angle <= to_rad) out.push_back({p.y_m[i], p.z_m[i]});
  }
  return out;
}

// The head width: twice the y of the first point on the field side whose direction to the next
// leans from the vertical by the flank's 1:20 (within 1e-4 rad: the flank is straight); the
// profile is symmetric, which the test checks point by point.
double head_width_m(const Profile& p) {
  const double flank = std::atan2(20.0, 1.0);  // from the horizontal
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    if (p.y_m[i] <= 0.0) continue;
    const double angle = std::atan2(p.z_m[i + 1] - p.z_m[i], p.y_m[i + 1] - p.y_m[i]);
    if (std::abs(angle - flank) < 1e-4) return 2.0 * p.y_m[i];
  }
  return 0.0;
}

struct Published {
  const char* file;
  double head_width_m;
};

// EN 13674-1: 60E1 (UIC 60) and 54E1 (UIC 54) heads: crown R300, R80, R13, the flank 1:20.
// Tolerances: radii 0.1 % (the points are written to 1e-6 mm, and the fits take the middle of each
// arc, away from the joins); head width 0.02 mm (the points are 0.1 mm apart along a flank that
// moves 0.005 mm sideways per point).
TEST(RailProfileGenerator, TheUprightHeadsHaveThePublishedRadiiAndHeadWidth) {
  for (const Published& rail : {Published{"UIC60_upright.prr", 0.072}, Published{"54E1_upright.prr", 0.070}}) {
    SCOPED_TRACE(rail.file);
    const Profile p = shipped(rail.file);
    ASSERT_EQ(p.kind, ProfileKind::rail);
    // Symmetric about y = 0 (the upright rail): point i and point n-1-i mirror each other.
    for (std::size_t i = 0; i < p.size(); ++i) {
      EXPECT_NEAR(p.y_m[i], -p.y_m[p.size() - 1 - i], 1e-9);
      EXPECT_NEAR(p.z_m[i], p.z_m[p.size() - 1 - i], 1e-9);
    }
    // R300 over |y| < 5 mm (it runs to about 10 mm), R80 where the crown leans 3 to 10 degrees
    // (it runs from 2 to 13), R13 from 30 to 75 degrees (from 14 to 87).
    constexpr double kDegree = 3.14159265358979323846 / 180.0;
    std::vector<std::array<double, 2>> crown;
    for (std::size_t i = 0; i < p.size(); ++i)
      if (std::abs(p.y_m[i]) < 5e-3) crown.push_back({p.y_m[i], p.z_m[i]});
    const Circle r300 = fit_circle(crown), r80 = fit_circle(points_leaning(p, 3 * kDegree, 10 * kDegree)),
                 r13 = fit_circle(points_leaning(p, 30 * kDegree, 75 * kDegree));
    EXPECT_NEAR(r300.radius_m, 0.300, 0.3e-3);
    EXPECT_NEAR(r300.y_m, 0.0, 1e-5);  // on the rail's axis
    EXPECT_NEAR(r80.radius_m, 0.080, 0.08e-3);
    EXPECT_NEAR(r13.radius_m, 0.013, 0.013e-3);
    EXPECT_NEAR(head_width_m(p), rail.head_width_m, 0.02e-3);
    // The top of the crown at the origin, the flank down to 30 mm below it.
    EXPECT_NEAR(p.z_m[p.size() / 2], 0.0, 1e-12);
    EXPECT_NEAR(p.z_m.back(), 0.030, 0.1e-3);
  }
}

}  // namespace
}  // namespace railcontact
