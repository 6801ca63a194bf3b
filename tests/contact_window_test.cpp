// The contact window's check by a bound (wheel_rail/contact_window.hpp): a window solution proven
// to leave nothing outside the window overlapping from an earlier whole-area check, without a
// product on the whole area; and refused where the bound cannot prove it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "elastic/influence_coefficients.hpp"
#include "railcontact/normal.hpp"
#include "wheel_rail/contact_window.hpp"

namespace {

using namespace railcontact;

constexpr double kElement_m = 0.2e-3;
constexpr double kRadius_m = 0.3;  // a sphere on a plane: h = r² / 2R − δ

Mesh square_mesh(int n, double first_m) {
  Mesh m;
  m.n1 = m.n2 = n;
  m.dx1_m = m.dx2_m = kElement_m;
  m.x1_first_m = m.x2_first_m = first_m;
  return m;
}

std::vector<double> sphere_gap_m(const Mesh& mesh, double approach_m) {
  std::vector<double> h(mesh.size());
  for (int i2 = 0; i2 < mesh.n2; ++i2)
    for (int i1 = 0; i1 < mesh.n1; ++i1) {
      const double r2 = mesh.x1(i1) * mesh.x1(i1) + mesh.x2(i2) * mesh.x2(i2);
      h[mesh.index(i1, i2)] = r2 / (2.0 * kRadius_m) - approach_m;
    }
  return h;
}

// The solution on the whole mesh and its check (its product A p there), the window around its
// contact widened by 3 elements.
struct Solved {
  Mesh mesh;
  std::vector<double> h_m;
  detail::WholeAreaCheck check;
  detail::MeshWindow window;
};
Solved solve(const Mesh& mesh, double approach_m) {
  Solved s{mesh, sphere_gap_m(mesh, approach_m), {}, {}};
  NormalContactSolver solver(mesh, Material{});
  const NormalSolution n = solver.solve_at_approach(s.h_m, 0.0);
  EXPECT_TRUE(n.converged);
  s.check.mesh = mesh;
  s.check.pressure_Pa = n.pressure_Pa;
  EXPECT_LE(solver.complementarity_residual(s.h_m, 0.0, n.pressure_Pa, &s.check.displacement_m), 1e-6);
  s.window = *detail::contact_window(mesh, n.pressure_Pa, 3, 1, 1.0);
  return s;
}

// Some element outside `window` overlaps: h + u < 0 there (u = A p, the product on the whole mesh).
bool overlap_outside_window(const Mesh& mesh, const std::vector<double>& h_m, const std::vector<double>& u_m,
                            const detail::MeshWindow& window) {
  for (int i2 = 0; i2 < mesh.n2; ++i2)
    for (int i1 = 0; i1 < mesh.n1; ++i1) {
      const bool inside = i1 >= window.lo1 && i1 < window.lo1 + window.n1 && i2 >= window.lo2 &&
                          i2 < window.lo2 + window.n2;
      const std::size_t k = mesh.index(i1, i2);
      if (!inside && h_m[k] + u_m[k] < 0.0) return true;
    }
  return false;
}

TEST(ContactWindowBound, HoldsForTheCheckedSolutionAndOnAMeshMovedByWholeElements) {
  const Solved a = solve(square_mesh(64, -31.5 * kElement_m), 40e-6);
  const detail::NormalInfluenceBound A(kElement_m, kElement_m, Material{});
  EXPECT_TRUE(detail::window_solution_holds_outside(a.mesh, a.h_m, a.window, a.check.pressure_Pa, a.check, A));
  // The same sphere on a mesh two elements further along x1: the check's pressure moves with it.
  const Solved b = solve(square_mesh(64, -29.5 * kElement_m), 40e-6);
  EXPECT_TRUE(detail::window_solution_holds_outside(b.mesh, b.h_m, b.window, b.check.pressure_Pa, a.check, A));
}

TEST(ContactWindowBound, HoldsForANearbyStateAndFailsForAFarOne) {
  const detail::NormalInfluenceBound A(kElement_m, kElement_m, Material{});
  const Solved a = solve(square_mesh(64, -31.5 * kElement_m), 40e-6);
  // 0.1 µm deeper: the pressure changes a little, the bound still proves the outside free.
  const Solved near = solve(square_mesh(64, -31.5 * kElement_m), 40.1e-6);
  EXPECT_TRUE(detail::window_solution_holds_outside(near.mesh, near.h_m, near.window, near.check.pressure_Pa,
                                                    a.check, A));
  // 30 µm deeper, judged with the shallow state's window and pressure: the overlap outside that
  // window is real (the deep state's own product says so), and the bound does not hide it.
  const Solved deep = solve(square_mesh(64, -31.5 * kElement_m), 70e-6);
  const std::vector<double>& shallow_pressure = a.check.pressure_Pa;
  NormalContactSolver solver(deep.mesh, Material{});
  std::vector<double> u;
  (void)solver.complementarity_residual(deep.h_m, 0.0, shallow_pressure, &u);
  ASSERT_TRUE(overlap_outside_window(deep.mesh, deep.h_m, u, a.window));
  EXPECT_FALSE(
      detail::window_solution_holds_outside(deep.mesh, deep.h_m, a.window, shallow_pressure, a.check, A));
  // Half the checked pressure on the same gap: the ring of overlap around the contact opens up
  // outside the window. The check's product alone (h + u_c >= 0 there) would hide it; the bound's
  // change term does not.
  std::vector<double> half = a.check.pressure_Pa;
  for (double& p : half) p *= 0.5;
  NormalContactSolver shallow_solver(a.mesh, Material{});
  (void)shallow_solver.complementarity_residual(a.h_m, 0.0, half, &u);
  ASSERT_TRUE(overlap_outside_window(a.mesh, a.h_m, u, a.window));
  EXPECT_FALSE(detail::window_solution_holds_outside(a.mesh, a.h_m, a.window, half, a.check, A));
}

TEST(ContactWindowBound, TheInfluenceBoundIsTheCoefficientNearbyAndAboveItFarAway) {
  const Material m;
  const detail::NormalInfluenceBound A(kElement_m, 0.5 * kElement_m, m);
  EXPECT_DOUBLE_EQ(A.at(3, 5), normal_influence(3 * kElement_m, 5 * 0.5 * kElement_m,
                                                ElementSize{kElement_m, 0.5 * kElement_m}, m));
  for (const auto& [d1, d2] : {std::pair{40, 0}, std::pair{0, 50}, std::pair{100, 100}}) {
    const double exact =
        normal_influence(d1 * kElement_m, d2 * 0.5 * kElement_m, ElementSize{kElement_m, 0.5 * kElement_m}, m);
    EXPECT_GE(A.at(d1, d2), exact);
    EXPECT_LE(A.at(d1, d2), 1.05 * exact);
  }
  // Falling with either offset.
  EXPECT_GT(A.at(0, 0), A.at(1, 0));
  EXPECT_GT(A.at(31, 2), A.at(32, 2));
}

}  // namespace
