// Tests of the normal contact solver (src/normal/, METHOD.md §5) against independent references:
// Hertz's closed form (src/hertz, Johnson §4.2) for quadratic h; a dense active-set solver
// (Kalker's NORM strategy: dense LU of the bordered system on a trial set, drop negative
// pressures, add penetrating elements) on small meshes; complementarity checked with the dense
// influence matrix, not with the FFT product the solver uses.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <numeric>
#include <vector>

#include "elastic/influence_operator.hpp"
#include "normal/known_product.hpp"
#include "railcontact/error.hpp"
#include "railcontact/hertz.hpp"
#include "railcontact/normal.hpp"

namespace railcontact {
namespace {

const Material kSteel{2.1e11, 0.3};
constexpr double kLoad_N = 98.1e3;

double rel_diff(double value, double reference) { return std::abs(value / reference - 1.0); }

std::vector<double> quadratic_distance(const Mesh& mesh, double A, double B, double x1_centre = 0.0,
                                       double x2_centre = 0.0) {
  std::vector<double> h(mesh.size());
  for (int i2 = 0; i2 < mesh.n2; ++i2) {
    for (int i1 = 0; i1 < mesh.n1; ++i1) {
      const double x1 = mesh.x1(i1) - x1_centre, x2 = mesh.x2(i2) - x2_centre;
      h[mesh.index(i1, i2)] = A * x1 * x1 + B * x2 * x2;
    }
  }
  return h;
}

// Deformed gap g = h - delta + A33 p with the dense influence matrix on the whole mesh.
std::vector<double> dense_gap(const Mesh& mesh, const std::vector<double>& h, const NormalSolution& s) {
  std::vector<std::size_t> all(mesh.size());
  std::iota(all.begin(), all.end(), std::size_t{0});
  const Eigen::MatrixXd A = make_normal_operator(mesh, kSteel).dense(all);
  const auto n = static_cast<Eigen::Index>(mesh.size());
  const Eigen::VectorXd u = A * Eigen::Map<const Eigen::VectorXd>(s.pressure_Pa.data(), n);
  std::vector<double> g(mesh.size());
  for (std::size_t k = 0; k < mesh.size(); ++k) g[k] = h[k] - s.approach_m + u[static_cast<Eigen::Index>(k)];
  return g;
}

// p >= 0 everywhere, g >= -tol and |g| <= tol where p > 0, tol relative to the approach scale.
void expect_complementarity(const Mesh& mesh, const std::vector<double>& h, const NormalSolution& s,
                            double relative_tolerance) {
  const std::vector<double> g = dense_gap(mesh, h, s);
  double u_max = 0.0;
  for (std::size_t k = 0; k < mesh.size(); ++k) u_max = std::max(u_max, g[k] - h[k] + s.approach_m);
  const double tol = relative_tolerance * u_max;
  double worst_contact = 0.0, worst_penetration = 0.0, min_p = 0.0;
  for (std::size_t k = 0; k < mesh.size(); ++k) {
    min_p = std::min(min_p, s.pressure_Pa[k]);
    if (s.pressure_Pa[k] > 0.0) worst_contact = std::max(worst_contact, std::abs(g[k]));
    worst_penetration = std::max(worst_penetration, -g[k]);
  }
  EXPECT_GE(min_p, 0.0);
  EXPECT_LE(worst_contact, tol) << "gap on contact elements";
  EXPECT_LE(worst_penetration, tol) << "penetration";
}

double total_force(const Mesh& mesh, const NormalSolution& s) {
  return mesh.element_area_m2() * std::accumulate(s.pressure_Pa.begin(), s.pressure_Pa.end(), 0.0);
}

// Number of 4-connected patches of contact elements.
int count_patches(const Mesh& mesh, const std::vector<double>& p) {
  std::vector<int> label(mesh.size(), 0);
  int patches = 0;
  std::vector<std::size_t> stack;
  for (std::size_t seed = 0; seed < mesh.size(); ++seed) {
    if (!(p[seed] > 0.0) || label[seed] != 0) continue;
    ++patches;
    stack.assign(1, seed);
    label[seed] = patches;
    while (!stack.empty()) {
      const std::size_t k = stack.back();
      stack.pop_back();
      const int i1 = static_cast<int>(k % mesh.n1), i2 = static_cast<int>(k / mesh.n1);
      const int n[4][2] = {{i1 - 1, i2}, {i1 + 1, i2}, {i1, i2 - 1}, {i1, i2 + 1}};
      for (const auto& q : n) {
        if (q[0] < 0 || q[1] < 0 || q[0] >= mesh.n1 || q[1] >= mesh.n2) continue;
        const std::size_t m = mesh.index(q[0], q[1]);
        if (p[m] > 0.0 && label[m] == 0) {
          label[m] = patches;
          stack.push_back(m);
        }
      }
    }
  }
  return patches;
}

// ---- Hertz -------------------------------------------------------------------------------------

struct HertzCase {
  const char* name;
  double A_per_m, B_per_m;
};

// Semi-axes from the contact extent along the central row and column: (number of contact
// elements) x (element length) / 2, i.e. the edge put half an element beyond the last contact
// element centre (error <= dx/2 per edge).
struct MeasuredEllipse {
  double a_m, b_m;
};
MeasuredEllipse measure_semi_axes(const Mesh& mesh, const std::vector<double>& p) {
  const int c1 = mesh.n1 / 2, c2 = mesh.n2 / 2;  // odd counts: the centre element
  int along_x1 = 0, along_x2 = 0;
  for (int i1 = 0; i1 < mesh.n1; ++i1) along_x1 += p[mesh.index(i1, c2)] > 0.0 ? 1 : 0;
  for (int i2 = 0; i2 < mesh.n2; ++i2) along_x2 += p[mesh.index(c1, i2)] > 0.0 ? 1 : 0;
  return {0.5 * along_x1 * mesh.dx1_m, 0.5 * along_x2 * mesh.dx2_m};
}

class NormalHertz : public ::testing::TestWithParam<HertzCase> {};

// Quadratic h reproduces Hertz: semi-axes, p0 and approach within 1 % on a 141 x 141 mesh
// covering 1.2 a x 1.2 b (a / dx1 = b / dx2 = 58.75); load exact; complementarity.
TEST_P(NormalHertz, ReproducesHertz) {
  const HertzCase& c = GetParam();
  const HertzContact hertz = hertz_from_curvatures(c.A_per_m, c.B_per_m, kLoad_N, kSteel);
  const Mesh mesh = Mesh::covering(-1.2 * hertz.a_m, 1.2 * hertz.a_m, -1.2 * hertz.b_m, 1.2 * hertz.b_m, 141, 141);
  const std::vector<double> h = quadratic_distance(mesh, c.A_per_m, c.B_per_m);
  const NormalSolution s = solve_normal_contact(mesh, h, kLoad_N, kSteel);
  ASSERT_TRUE(s.converged) << "residual " << s.residual << " after " << s.iterations;
  EXPECT_LE(s.residual, 1e-10);
  EXPECT_FALSE(s.touches_border);

  const MeasuredEllipse e = measure_semi_axes(mesh, s.pressure_Pa);
  const double p0 = *std::max_element(s.pressure_Pa.begin(), s.pressure_Pa.end());
  const double area = static_cast<double>(s.elements_in_contact) * mesh.element_area_m2();
  std::printf("[ hertz %s ] a/b %.3f  a %.4f%%  b %.4f%%  area %.4f%%  p0 %.4f%%  delta %.4f%%  it %d  n %zu\n",
              c.name, hertz.a_over_b(), 100 * (e.a_m / hertz.a_m - 1), 100 * (e.b_m / hertz.b_m - 1),
              100 * (area / (M_PI * hertz.a_m * hertz.b_m) - 1), 100 * (p0 / hertz.max_pressure_Pa - 1),
              100 * (s.approach_m / hertz.approach_m - 1), s.iterations, s.elements_in_contact);
  EXPECT_LT(rel_diff(e.a_m, hertz.a_m), 0.01);
  EXPECT_LT(rel_diff(e.b_m, hertz.b_m), 0.01);
  EXPECT_LT(rel_diff(area, M_PI * hertz.a_m * hertz.b_m), 0.01);
  EXPECT_LT(rel_diff(p0, hertz.max_pressure_Pa), 0.01);
  EXPECT_LT(rel_diff(s.approach_m, hertz.approach_m), 0.01);
  EXPECT_LT(rel_diff(s.normal_force_N, kLoad_N), 1e-10);
  EXPECT_LT(rel_diff(total_force(mesh, s), kLoad_N), 1e-10);
}

HertzCase semi_axes_case(const char* name, double a_m, double b_m) {
  const HertzCurvatures k = hertz_curvatures_for_semi_axes(a_m, b_m, kLoad_N, kSteel);
  return {name, k.A_per_m, k.B_per_m};
}

INSTANTIATE_TEST_SUITE_P(Ellipses, NormalHertz,
                         ::testing::Values(
                             // wheel R = 0.46 m on a rail crown of 0.3 m
                             HertzCase{"WheelOnRailCrown", 1.0 / (2 * 0.46), 1.0 / (2 * 0.3)},
                             semi_axes_case("Circle", 6e-3, 6e-3), semi_axes_case("Narrow", 4e-3, 8e-3),
                             semi_axes_case("Long", 8e-3, 4e-3)),
                         [](const ::testing::TestParamInfo<HertzCase>& param_info) {
                           return std::string(param_info.param.name);
                         });

// Complementarity on a coarser Hertz case, checked with the dense influence matrix on every element.
TEST(NormalContact, ComplementarityWithDenseMatrix) {
  const HertzContact hertz = hertz_from_curvatures(1.0 / (2 * 0.46), 1.0 / (2 * 0.3), kLoad_N, kSteel);
  const Mesh mesh = Mesh::covering(-1.3 * hertz.a_m, 1.3 * hertz.a_m, -1.3 * hertz.b_m, 1.3 * hertz.b_m, 41, 35);
  const std::vector<double> h = quadratic_distance(mesh, 1.0 / (2 * 0.46), 1.0 / (2 * 0.3), 1e-4, -2e-4);
  const NormalSolution s = solve_normal_contact(mesh, h, kLoad_N, kSteel);
  ASSERT_TRUE(s.converged);
  expect_complementarity(mesh, h, s, 1e-9);
  EXPECT_LT(rel_diff(total_force(mesh, s), kLoad_N), 1e-10);
}

// ---- dense reference ---------------------------------------------------------------------------

struct DenseSolution {
  std::vector<double> pressure_Pa;
  double approach_m = 0.0;
};

// On the set J: A_JJ p - delta 1 = -h_J, S sum p = F3 (bordered system, dense LU).
DenseSolution solve_on_set(const Mesh& mesh, const InfluenceOperator& op, const std::vector<double>& h,
                           const std::vector<std::size_t>& J, double F3) {
  const auto n = static_cast<Eigen::Index>(J.size());
  const double S = mesh.element_area_m2();
  const double a00 = op.kernel(0, 0, 0, 0);
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n + 1, n + 1);
  Eigen::VectorXd rhs(n + 1);
  M.topLeftCorner(n, n) = op.dense(J) / a00;  // scaled to O(1)
  for (Eigen::Index i = 0; i < n; ++i) {
    M(i, n) = -1.0;
    M(n, i) = 1.0;
    rhs[i] = -h[J[static_cast<std::size_t>(i)]];
  }
  rhs[n] = F3 / S * a00;
  const Eigen::VectorXd x = Eigen::PartialPivLU<Eigen::MatrixXd>(M).solve(rhs);
  DenseSolution d;
  d.pressure_Pa.assign(mesh.size(), 0.0);
  for (Eigen::Index i = 0; i < n; ++i) d.pressure_Pa[J[static_cast<std::size_t>(i)]] = x[i] / a00;
  d.approach_m = x[n];
  return d;
}

// Kalker's NORM-type active-set iteration with dense LU: start from all elements, drop those
// with negative pressure, add the penetrating ones, until the set is consistent.
DenseSolution dense_active_set_solution(const Mesh& mesh, const std::vector<double>& h, double F3) {
  const InfluenceOperator op = make_normal_operator(mesh, kSteel);
  std::vector<std::size_t> all(mesh.size());
  std::iota(all.begin(), all.end(), std::size_t{0});
  const Eigen::MatrixXd A = op.dense(all);
  std::vector<std::uint8_t> in(mesh.size(), 1);
  for (int pass = 0; pass < 200; ++pass) {
    std::vector<std::size_t> J;
    for (std::size_t k = 0; k < mesh.size(); ++k)
      if (in[k] != 0) J.push_back(k);
    const DenseSolution d = solve_on_set(mesh, op, h, J, F3);
    bool changed = false;
    for (std::size_t k : J) {
      if (d.pressure_Pa[k] < 0.0) {
        in[k] = 0;
        changed = true;
      }
    }
    if (changed) continue;
    const auto n = static_cast<Eigen::Index>(mesh.size());
    const Eigen::VectorXd u = A * Eigen::Map<const Eigen::VectorXd>(d.pressure_Pa.data(), n);
    for (std::size_t k = 0; k < mesh.size(); ++k) {
      if (in[k] == 0 && h[k] - d.approach_m + u[static_cast<Eigen::Index>(k)] < -1e-14) {
        in[k] = 1;
        changed = true;
      }
    }
    if (!changed) return d;
  }
  ADD_FAILURE() << "dense active-set reference did not converge";
  return {};
}

// FFT solver vs the dense active-set reference on a small mesh: same contact set, p3 and delta to 1e-8.
TEST(NormalContact, MatchesDenseActiveSetReference) {
  const HertzContact hertz = hertz_from_curvatures(1.0 / (2 * 0.46), 1.0 / (2 * 0.3), kLoad_N, kSteel);
  const Mesh mesh = Mesh::covering(-1.3 * hertz.a_m, 1.4 * hertz.a_m, -1.25 * hertz.b_m, 1.35 * hertz.b_m, 22, 19);
  // A quadratic plus a cubic and a tilt: not elliptical, not symmetric.
  std::vector<double> h = quadratic_distance(mesh, 1.0 / (2 * 0.46), 1.0 / (2 * 0.3));
  for (int i2 = 0; i2 < mesh.n2; ++i2)
    for (int i1 = 0; i1 < mesh.n1; ++i1) {
      const double x1 = mesh.x1(i1), x2 = mesh.x2(i2);
      h[mesh.index(i1, i2)] += 40.0 * x2 * x2 * x2 + 2e-3 * x1;
    }
  const NormalSolution s = solve_normal_contact(mesh, h, kLoad_N, kSteel);
  ASSERT_TRUE(s.converged);
  const DenseSolution d = dense_active_set_solution(mesh, h, kLoad_N);
  ASSERT_EQ(d.pressure_Pa.size(), mesh.size());
  const double p_max = *std::max_element(d.pressure_Pa.begin(), d.pressure_Pa.end());
  std::size_t dense_count = 0;
  double worst = 0.0;
  for (std::size_t k = 0; k < mesh.size(); ++k) {
    dense_count += d.pressure_Pa[k] > 0.0 ? 1 : 0;
    EXPECT_EQ(s.pressure_Pa[k] > 0.0, d.pressure_Pa[k] > 0.0) << "element " << k;
    worst = std::max(worst, std::abs(s.pressure_Pa[k] - d.pressure_Pa[k]) / p_max);
  }
  EXPECT_EQ(s.elements_in_contact, dense_count);
  EXPECT_LT(worst, 1e-8);
  EXPECT_LT(rel_diff(s.approach_m, d.approach_m), 1e-8);
}

// The same check, directly on the final contact set: dense LU of the bordered system.
TEST(NormalContact, DenseSolveOnFinalContactSet) {
  const Mesh mesh = Mesh::covering(-10e-3, 10e-3, -8e-3, 8e-3, 30, 26);
  const std::vector<double> h = quadratic_distance(mesh, 1.0, 2.0, 0.7e-3, 0.0);
  const NormalSolution s = solve_normal_contact(mesh, h, kLoad_N, kSteel);
  ASSERT_TRUE(s.converged);
  std::vector<std::size_t> J;
  for (std::size_t k = 0; k < mesh.size(); ++k)
    if (s.pressure_Pa[k] > 0.0) J.push_back(k);
  const DenseSolution d = solve_on_set(mesh, make_normal_operator(mesh, kSteel), h, J, kLoad_N);
  const double p_max = *std::max_element(d.pressure_Pa.begin(), d.pressure_Pa.end());
  for (std::size_t k = 0; k < mesh.size(); ++k)
    EXPECT_NEAR(s.pressure_Pa[k], d.pressure_Pa[k], 1e-8 * p_max) << "element " << k;
  EXPECT_NEAR(s.approach_m, d.approach_m, 1e-8 * d.approach_m);
}

// ---- non-elliptical h --------------------------------------------------------------------------

// Flat-ended along X1 (h = 0 on |x1| < c at x2 = 0): one patch, positive pressure, elongated,
// with the edge pressure peaks of a flat punch end at |x1| ~ c.
TEST(NormalContact, FlatEndedProfileGivesOnePatch) {
  const Mesh mesh = Mesh::covering(-14e-3, 14e-3, -8e-3, 8e-3, 70, 40);
  std::vector<double> h(mesh.size());
  const double c = 5e-3;
  for (int i2 = 0; i2 < mesh.n2; ++i2)
    for (int i1 = 0; i1 < mesh.n1; ++i1) {
      const double x1 = std::max(0.0, std::abs(mesh.x1(i1)) - c), x2 = mesh.x2(i2);
      h[mesh.index(i1, i2)] = 1.0 / (2 * 0.46) * x1 * x1 + 1.0 / (2 * 0.3) * x2 * x2;
    }
  const NormalSolution s = solve_normal_contact(mesh, h, kLoad_N, kSteel);
  ASSERT_TRUE(s.converged);
  EXPECT_FALSE(s.touches_border);
  EXPECT_EQ(count_patches(mesh, s.pressure_Pa), 1);
  expect_complementarity(mesh, h, s, 1e-9);
  EXPECT_LT(rel_diff(s.normal_force_N, kLoad_N), 1e-10);
  // The whole flat part is in contact along the centre line, with pressure positive there.
  const int c2 = mesh.n2 / 2;
  for (int i1 = 0; i1 < mesh.n1; ++i1) {
    if (std::abs(mesh.x1(i1)) < c) {
      EXPECT_GT(s.pressure_Pa[mesh.index(i1, c2)], 0.0) << "i1 " << i1;
    }
  }
  // Pressure along the centre line peaks near the ends of the flat part, not at x1 = 0.
  const double p_centre = s.pressure_Pa[mesh.index(mesh.n1 / 2, c2)];
  double p_end = 0.0;
  for (int i1 = 0; i1 < mesh.n1; ++i1)
    if (std::abs(std::abs(mesh.x1(i1)) - c) < 1e-3) p_end = std::max(p_end, s.pressure_Pa[mesh.index(i1, c2)]);
  EXPECT_GT(p_end, p_centre);
}

// Two bumps (minima of h at x2 = +-3 mm, joined by a shallow saddle 20 um high): under the full
// load they merge into one patch; both bumps carry the higher pressure.
TEST(NormalContact, TwoBumpsMergeIntoOnePatch) {
  const Mesh mesh = Mesh::covering(-10e-3, 10e-3, -12e-3, 12e-3, 50, 60);
  std::vector<double> h(mesh.size());
  const double d = 3e-3, saddle = 20e-6;
  for (int i2 = 0; i2 < mesh.n2; ++i2)
    for (int i1 = 0; i1 < mesh.n1; ++i1) {
      const double x1 = mesh.x1(i1), x2 = mesh.x2(i2);
      const double s2 = (x2 * x2 - d * d) / (d * d);  // quartic double well in x2
      h[mesh.index(i1, i2)] = 1.0 / (2 * 0.46) * x1 * x1 + saddle * s2 * s2 - saddle;
    }
  const NormalSolution s = solve_normal_contact(mesh, h, kLoad_N, kSteel);
  ASSERT_TRUE(s.converged);
  EXPECT_FALSE(s.touches_border);
  EXPECT_EQ(count_patches(mesh, s.pressure_Pa), 1);
  expect_complementarity(mesh, h, s, 1e-9);
  EXPECT_LT(rel_diff(s.normal_force_N, kLoad_N), 1e-10);
  // The centre (saddle) is in contact but carries less pressure than the bumps.
  const int c1 = mesh.n1 / 2;
  double p_bump = 0.0, p_saddle = s.pressure_Pa[mesh.index(c1, mesh.n2 / 2)];
  for (int i2 = 0; i2 < mesh.n2; ++i2)
    if (std::abs(std::abs(mesh.x2(i2)) - d) < 0.5e-3) p_bump = std::max(p_bump, s.pressure_Pa[mesh.index(c1, i2)]);
  EXPECT_GT(p_saddle, 0.0);
  EXPECT_GT(p_bump, p_saddle);
}

// A mesh smaller than the Hertz ellipse: the contact reaches the border and is flagged; the
// solution is still the exact one of the truncated problem (load and complementarity).
TEST(NormalContact, TouchesBorderWhenMeshTooSmall) {
  const double A = 1.0 / (2 * 0.46), B = 1.0 / (2 * 0.3);
  const HertzContact hertz = hertz_from_curvatures(A, B, kLoad_N, kSteel);
  const Mesh small = Mesh::covering(-0.8 * hertz.a_m, 0.8 * hertz.a_m, -1.3 * hertz.b_m, 1.3 * hertz.b_m, 30, 40);
  const std::vector<double> h = quadratic_distance(small, A, B);
  const NormalSolution s = solve_normal_contact(small, h, kLoad_N, kSteel);
  ASSERT_TRUE(s.converged);
  EXPECT_TRUE(s.touches_border);
  EXPECT_LT(rel_diff(s.normal_force_N, kLoad_N), 1e-10);
  expect_complementarity(small, h, s, 1e-9);

  const Mesh large = Mesh::covering(-1.3 * hertz.a_m, 1.3 * hertz.a_m, -1.3 * hertz.b_m, 1.3 * hertz.b_m, 30, 40);
  EXPECT_FALSE(solve_normal_contact(large, quadratic_distance(large, A, B), kLoad_N, kSteel).touches_border);
}

// Interpenetration before the approach (h < 0) and an offset centre: the same pressure as h
// shifted (delta absorbs a constant), the patch moved with the centre.
TEST(NormalContact, ConstantShiftOfDistanceOnlyChangesApproach) {
  const Mesh mesh = Mesh::covering(-10e-3, 10e-3, -8e-3, 8e-3, 40, 32);
  const std::vector<double> h = quadratic_distance(mesh, 1.0, 2.0, 1e-3, -0.5e-3);
  std::vector<double> shifted = h;
  for (double& v : shifted) v -= 50e-6;
  const NormalSolution a = solve_normal_contact(mesh, h, kLoad_N, kSteel);
  const NormalSolution b = solve_normal_contact(mesh, shifted, kLoad_N, kSteel);
  ASSERT_TRUE(a.converged && b.converged);
  EXPECT_NEAR(b.approach_m, a.approach_m - 50e-6, 1e-12);
  const double p_max = *std::max_element(a.pressure_Pa.begin(), a.pressure_Pa.end());
  for (std::size_t k = 0; k < mesh.size(); ++k) EXPECT_NEAR(a.pressure_Pa[k], b.pressure_Pa[k], 1e-9 * p_max);
}

// The reusable plan gives the same answer as the free function, for several loads in a row.
TEST(NormalContact, ReusablePlanMatchesFreeFunction) {
  const Mesh mesh = Mesh::covering(-10e-3, 10e-3, -8e-3, 8e-3, 40, 32);
  const std::vector<double> h = quadratic_distance(mesh, 1.0, 2.0);
  NormalContactSolver solver(mesh, kSteel);
  for (const double F3 : {20e3, 98.1e3, 150e3}) {
    const NormalSolution a = solver.solve(h, F3);
    const NormalSolution b = solve_normal_contact(mesh, h, F3, kSteel);
    ASSERT_TRUE(a.converged);
    EXPECT_EQ(a.pressure_Pa, b.pressure_Pa);
    EXPECT_EQ(a.approach_m, b.approach_m);
  }
}

// Non-convergence is reported, not thrown.
TEST(NormalContact, ReportsNonConvergence) {
  const Mesh mesh = Mesh::covering(-10e-3, 10e-3, -8e-3, 8e-3, 40, 32);
  NormalOptions options;
  options.max_iterations = 2;
  const NormalSolution s = solve_normal_contact(mesh, quadratic_distance(mesh, 1.0, 2.0), kLoad_N, kSteel, options);
  EXPECT_FALSE(s.converged);
  EXPECT_GT(s.residual, options.tolerance);
  EXPECT_EQ(s.iterations, 2);
  EXPECT_LT(rel_diff(s.normal_force_N, kLoad_N), 1e-10);  // the load holds at every iterate
}

// A flat h: uniform pressure is the exact discrete solution only up to the edge singularity;
// the solver still converges with every element in contact.
TEST(NormalContact, FlatDistanceLoadsWholeMesh) {
  const Mesh mesh = Mesh::covering(-5e-3, 5e-3, -5e-3, 5e-3, 20, 20);
  const NormalSolution s = solve_normal_contact(mesh, std::vector<double>(mesh.size(), 1e-5), kLoad_N, kSteel);
  ASSERT_TRUE(s.converged);
  EXPECT_EQ(s.elements_in_contact, mesh.size());
  EXPECT_TRUE(s.touches_border);
  // Rigid flat punch: pressure highest at the corners, lowest at the centre.
  EXPECT_GT(s.pressure_Pa[mesh.index(0, 0)], s.pressure_Pa[mesh.index(10, 10)]);
}

// ---- bad input ---------------------------------------------------------------------------------

TEST(NormalContact, BadInputThrows) {
  const Mesh mesh = Mesh::covering(-10e-3, 10e-3, -8e-3, 8e-3, 20, 16);
  const std::vector<double> h = quadratic_distance(mesh, 1.0, 2.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(solve_normal_contact(mesh, h, 0.0, kSteel), Error);
  EXPECT_THROW(solve_normal_contact(mesh, h, -1.0, kSteel), Error);
  EXPECT_THROW(solve_normal_contact(mesh, h, nan, kSteel), Error);
  EXPECT_THROW(solve_normal_contact(mesh, h, inf, kSteel), Error);
  EXPECT_THROW(solve_normal_contact(mesh, std::vector<double>(h.begin(), h.end() - 1), kLoad_N, kSteel), Error);
  EXPECT_THROW(solve_normal_contact(mesh, {}, kLoad_N, kSteel), Error);
  for (const double bad : {nan, inf, -inf}) {
    std::vector<double> h_bad = h;
    h_bad[37] = bad;
    EXPECT_THROW(solve_normal_contact(mesh, h_bad, kLoad_N, kSteel), Error);
  }
  Mesh empty = mesh;
  empty.n1 = 0;
  EXPECT_THROW(solve_normal_contact(empty, {}, kLoad_N, kSteel), Error);
  Mesh negative = mesh;
  negative.dx2_m = -1e-3;
  EXPECT_THROW(solve_normal_contact(negative, h, kLoad_N, kSteel), Error);
  EXPECT_THROW(solve_normal_contact(mesh, h, kLoad_N, Material{-2.1e11, 0.3}), Error);
  EXPECT_THROW(solve_normal_contact(mesh, h, kLoad_N, Material{2.1e11, 0.51}), Error);  // nu = 0.5 is valid
  NormalOptions options;
  options.tolerance = 0.0;
  EXPECT_THROW(solve_normal_contact(mesh, h, kLoad_N, kSteel, options), Error);
  options = {};
  options.max_iterations = 0;
  EXPECT_THROW(solve_normal_contact(mesh, h, kLoad_N, kSteel, options), Error);
  // The message names the problem.
  try {
    solve_normal_contact(mesh, h, -5.0, kSteel);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("normal force"), std::string::npos) << e.what();
  }
}

// The call throws railcontact::Error whose message contains `expected`.
template <class Call>
void expect_error_mentioning(Call call, const std::string& expected) {
  try {
    call();
    ADD_FAILURE() << "no error; expected one mentioning: " << expected;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
  }
}

// Hertz's problem of a wheel of 0.46 m on a crown of 0.3 m under the wheel load, on 41 x 41 elements
// over 1.2 times its semi-axes.
struct HertzGrid {
  HertzContact hertz;
  Mesh mesh;
  std::vector<double> h;
};
HertzGrid hertz_grid_41() {
  const double A = 1.0 / (2 * 0.46), B = 1.0 / (2 * 0.3);
  const HertzContact hertz = hertz_from_curvatures(A, B, kLoad_N, kSteel);
  const Mesh mesh = Mesh::covering(-1.2 * hertz.a_m, 1.2 * hertz.a_m, -1.2 * hertz.b_m, 1.2 * hertz.b_m, 41, 41);
  return {hertz, mesh, quadratic_distance(mesh, A, B)};
}

// complementarity_residual (the check of a wheelset's contact window, docs/WHEELSET.md §8): a
// converged solution's residual is the solver's own; a pressure that leaves contact out or one that
// is not a solution is far from it; bad input is refused, naming it.
TEST(NormalContact, ComplementarityResidualChecksAGivenPressure) {
  const auto [hertz, mesh, h] = hertz_grid_41();
  NormalContactSolver solver(mesh, kSteel);
  const NormalSolution s = solver.solve_at_approach(h, hertz.approach_m);
  ASSERT_TRUE(s.converged);
  EXPECT_LT(solver.complementarity_residual(h, hertz.approach_m, s.pressure_Pa), 1e-9);
  std::vector<double> half = s.pressure_Pa;  // the left half of the contact left out: overlap there
  for (int i2 = 0; i2 < mesh.n2; ++i2)
    for (int i1 = 0; i1 < mesh.n1 / 2; ++i1) half[mesh.index(i1, i2)] = 0.0;
  EXPECT_GT(solver.complementarity_residual(h, hertz.approach_m, half), 1e-2);
  EXPECT_GT(solver.complementarity_residual(h, 0.5 * hertz.approach_m, s.pressure_Pa), 1e-2);
  std::vector<double> bad = s.pressure_Pa;
  bad[7] = -1.0;
  expect_error_mentioning([&] { (void)solver.complementarity_residual(h, hertz.approach_m, bad); },
                          "element 7 given for the residual must be finite and >= 0");
  bad[7] = std::numeric_limits<double>::quiet_NaN();
  expect_error_mentioning([&] { (void)solver.complementarity_residual(h, hertz.approach_m, bad); }, "element 7");
  expect_error_mentioning([&] { (void)solver.complementarity_residual(h, hertz.approach_m, {1.0, 2.0}); },
                          "2 pressures given for the residual on a mesh of 1681 elements");
  expect_error_mentioning(
      [&] { (void)solver.complementarity_residual(h, std::numeric_limits<double>::infinity(), s.pressure_Pa); },
      "approach inf m for the residual must be finite");
}

// A time step's start from a known product (normal/known_product.hpp, docs/WHEELSET.md §8 "The
// start's product"): the solution's product is A p; a start from a prediction with negative
// elements (floored at zero by the solver, its product corrected element by element) or with more
// of them than the correction takes (then a product by FFT) gives the solution of a start without
// it. A wrong correction would leave the iteration with a wrong A p and another pressure.
TEST(NormalContact, AStartFromAKnownProductGivesTheSameSolution) {
  const auto [hertz, mesh, h] = hertz_grid_41();
  NormalContactSolver solver(mesh, kSteel);
  std::vector<double> product;
  const NormalSolution first =
      detail::NormalSolverAccess::solve_at_approach(solver, h, hertz.approach_m, {}, nullptr, &product);
  ASSERT_TRUE(first.converged);
  std::vector<double> fresh;
  (void)solver.complementarity_residual(h, hertz.approach_m, first.pressure_Pa, &fresh);
  ASSERT_EQ(product.size(), fresh.size());
  const double u_max = *std::max_element(fresh.begin(), fresh.end());
  for (std::size_t k = 0; k < fresh.size(); ++k) EXPECT_NEAR(product[k], fresh[k], 1e-12 * u_max) << k;

  // At the same approach: few elements change, and the product follows by recursion from the start's
  // (a deeper approach changes the contact set by many elements, and a product by FFT would hide a
  // wrong start).
  InfluenceOperator op = make_normal_operator(mesh, kSteel);
  for (const int negative : {5, 40}) {
    detail::KnownProduct known{first.pressure_Pa, {}};
    const double p_max = *std::max_element(first.pressure_Pa.begin(), first.pressure_Pa.end());
    for (int k = 0; k < negative; ++k) known.pressure_Pa[mesh.index(20 + k % 5, 18 + k / 5)] = -0.1 * p_max;
    known.displacement_m.resize(mesh.size());
    op.apply_on_grid(known.pressure_Pa, known.displacement_m);
    std::vector<double> start = known.pressure_Pa;
    for (double& p : start) p = std::max(0.0, p);
    const NormalSolution with_known =
        detail::NormalSolverAccess::solve_at_approach(solver, h, hertz.approach_m, start, &known, nullptr);
    const NormalSolution without = solver.solve_at_approach(h, hertz.approach_m, start);
    ASSERT_TRUE(with_known.converged && without.converged) << negative;
    EXPECT_LT(rel_diff(with_known.normal_force_N, first.normal_force_N), 1e-9) << negative;
    EXPECT_LT(rel_diff(with_known.normal_force_N, without.normal_force_N), 1e-9) << negative;
    EXPECT_EQ(with_known.elements_in_contact, first.elements_in_contact) << negative;
    for (std::size_t k = 0; k < mesh.size(); ++k)
      EXPECT_NEAR(with_known.pressure_Pa[k], without.pressure_Pa[k], 1e-8 * p_max) << negative << " " << k;
    // Two iterations from either start product follow the same path: the iteration corrects a wrong
    // start only when many elements change at once, so a converged solution alone would not show it.
    NormalContactSolver two(mesh, kSteel, NormalOptions{1e-10, 2});
    const NormalSolution early_known =
        detail::NormalSolverAccess::solve_at_approach(two, h, hertz.approach_m, start, &known, nullptr);
    const NormalSolution early = two.solve_at_approach(h, hertz.approach_m, start);
    for (std::size_t k = 0; k < mesh.size(); ++k)
      EXPECT_NEAR(early_known.pressure_Pa[k], early.pressure_Pa[k], 1e-9 * p_max) << negative << " " << k;
  }
}

// A time step's start (detail::StartKind::time_step_prediction, docs/NORMAL.md "Preconditioner"):
// the Hertzian body moving by a tenth of an element per step (81 x 81 elements), each step started
// from the linear prediction of the last two steps' pressures as the wheelset does. The time step's
// preconditioner gives the default one's solution: the same contact, the normal force to the
// tolerance, the pressure within 1e-3 of its largest at the wheelset's tolerance 5e-6 (8e-5 to
// 2.2e-4 here) and within 1e-8 at 1e-10 (1.6e-9 to 3.8e-9). It is the time step's preconditioner that
// ran: the pressures are not the default's to the last bit. (Its iterations, not asserted: 29
// against 31 at 5e-6 here; in a wheelset's time step 14 % fewer, docs/NORMAL.md.)
TEST(NormalContact, ATimeStepsStartGivesTheDefaultStartsSolution) {
  const double A = 1.0 / (2 * 0.46), B = 1.0 / (2 * 0.3);
  const HertzContact hertz = hertz_from_curvatures(A, B, kLoad_N, kSteel);
  const Mesh mesh = Mesh::covering(-1.2 * hertz.a_m, 1.2 * hertz.a_m, -1.2 * hertz.b_m, 1.2 * hertz.b_m, 81, 81);
  const double shift_m = 0.1 * mesh.dx2_m;
  const auto h_at = [&](int step) { return quadratic_distance(mesh, A, B, 0.0, step * shift_m); };
  for (const double tolerance : {5e-6, 1e-10}) {
    NormalContactSolver solver(mesh, kSteel, NormalOptions{tolerance, 200});
    std::vector<double> older = solver.solve_at_approach(h_at(0), hertz.approach_m).pressure_Pa;
    std::vector<double> last = solver.solve_at_approach(h_at(1), hertz.approach_m).pressure_Pa;
    for (int step = 2; step <= 7; ++step) {
      std::vector<double> start(mesh.size());
      for (std::size_t k = 0; k < start.size(); ++k) start[k] = std::max(0.0, 2.0 * last[k] - older[k]);
      const std::vector<double> h = h_at(step);
      const NormalSolution given = detail::NormalSolverAccess::solve_at_approach(
          solver, h, hertz.approach_m, start, nullptr, nullptr, detail::StartKind::given);
      const NormalSolution time_step = detail::NormalSolverAccess::solve_at_approach(
          solver, h, hertz.approach_m, start, nullptr, nullptr, detail::StartKind::time_step_prediction);
      ASSERT_TRUE(given.converged && time_step.converged) << tolerance << " " << step;
      EXPECT_EQ(time_step.elements_in_contact, given.elements_in_contact) << tolerance << " " << step;
      EXPECT_LT(rel_diff(time_step.normal_force_N, given.normal_force_N), tolerance) << tolerance << " " << step;
      const double p_max = *std::max_element(given.pressure_Pa.begin(), given.pressure_Pa.end());
      double largest = 0.0;
      for (std::size_t k = 0; k < mesh.size(); ++k)
        largest = std::max(largest, std::abs(time_step.pressure_Pa[k] - given.pressure_Pa[k]));
      EXPECT_LT(largest, (tolerance > 1e-8 ? 1e-3 : 1e-8) * p_max) << tolerance << " " << step;
      EXPECT_GT(largest, 0.0) << tolerance << " " << step;
      older = std::move(last);
      last = time_step.pressure_Pa;
    }
  }
}

}  // namespace
}  // namespace railcontact

// ---- Approach given ----------------------------------------------------------------------------

namespace railcontact {
namespace {

// The approach-given solver on Hertz's problem: F3 = (4/3) E* sqrt(R_e) δ^(3/2) generalised by
// hertz_from_curvatures; at the approach the load-given solver finds for F3, it returns F3 and the
// same pressure; below the undeformed overlap it gives no contact (F3 = 0, not an error).
TEST(NormalContact, ApproachGivenReproducesHertzAndTheLoadGivenSolver) {
  const double A = 1.0 / (2 * 0.46), B = 1.0 / (2 * 0.3);
  const HertzContact hertz = hertz_from_curvatures(A, B, kLoad_N, kSteel);
  const Mesh mesh = Mesh::covering(-1.2 * hertz.a_m, 1.2 * hertz.a_m, -1.2 * hertz.b_m, 1.2 * hertz.b_m, 81, 81);
  const std::vector<double> h = quadratic_distance(mesh, A, B);
  NormalContactSolver solver(mesh, kSteel);
  const NormalSolution by_load = solver.solve(h, kLoad_N);
  const NormalSolution by_approach = solver.solve_at_approach(h, by_load.approach_m);
  ASSERT_TRUE(by_approach.converged) << by_approach.residual;
  EXPECT_LT(rel_diff(by_approach.normal_force_N, kLoad_N), 1e-8);
  EXPECT_EQ(by_approach.elements_in_contact, by_load.elements_in_contact);
  // Hertz: F3 ∝ δ^(3/2) within the discretisation error (1 %) at Hertz's own approach.
  const NormalSolution at_hertz = solver.solve_at_approach(h, hertz.approach_m);
  EXPECT_LT(rel_diff(at_hertz.normal_force_N, kLoad_N), 0.015);
  // A warm start from the previous pressure gives the same answer in fewer iterations.
  const NormalSolution warm = solver.solve_at_approach(h, 1.01 * by_load.approach_m, by_approach.pressure_Pa);
  const NormalSolution cold = solver.solve_at_approach(h, 1.01 * by_load.approach_m);
  EXPECT_LT(rel_diff(warm.normal_force_N, cold.normal_force_N), 1e-8);
  EXPECT_LT(warm.iterations, cold.iterations);
  // No overlap: no contact, zero force.
  const NormalSolution none = solver.solve_at_approach(h, -1e-6);
  EXPECT_TRUE(none.converged);
  EXPECT_EQ(none.elements_in_contact, 0u);
  EXPECT_EQ(none.normal_force_N, 0.0);
}

}  // namespace
}  // namespace railcontact
